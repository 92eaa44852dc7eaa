#!/usr/bin/env python3
"""Writes the unit-cube test meshes of this folder (run from this folder).

The same cube [0,1]^3 (8 corners, 12 outward-oriented triangles, each face (q0 q1 q2 q3)
split into (q0 q1 q2) and (q0 q2 q3)) in every format flexdem-mesh reads. The binary Gmsh files
are written by gmsh itself from cube_v22_ascii.msh (gmsh 4.8.4, Debian):
    gmsh cube_v22_ascii.msh -save -format msh22 -bin -o cube_v22_binary.msh
    gmsh cube_v22_ascii.msh -save -format msh41 -o cube_v41_ascii.msh
    gmsh cube_v22_ascii.msh -save -format msh41 -bin -o cube_v41_binary.msh
"""
import struct

CORNERS = [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0),
           (0, 0, 1), (1, 0, 1), (1, 1, 1), (0, 1, 1)]
QUADS = [(0, 3, 2, 1), (4, 5, 6, 7), (0, 1, 5, 4),
         (2, 3, 7, 6), (0, 4, 7, 3), (1, 2, 6, 5)]
TRIANGLES = [t for q in QUADS for t in ((q[0], q[1], q[2]), (q[0], q[2], q[3]))]


def normal(t):
    a, b, c = (CORNERS[i] for i in t)
    u = [b[k] - a[k] for k in range(3)]
    v = [c[k] - a[k] for k in range(3)]
    return (u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0])


def stl_ascii():
    lines = ["solid cube"]
    for t in TRIANGLES:
        lines.append("  facet normal %g %g %g" % normal(t))
        lines.append("    outer loop")
        for i in t:
            lines.append("      vertex %g %g %g" % CORNERS[i])
        lines.append("    endloop")
        lines.append("  endfacet")
    lines.append("endsolid cube")
    open("cube_ascii.stl", "w").write("\n".join(lines) + "\n")


def stl_binary():
    # A header starting with "solid", as many exporters write: detection must use the size.
    header = b"solid cube (binary STL written by generate.py)".ljust(80, b" ")
    data = header + struct.pack("<I", len(TRIANGLES))
    for t in TRIANGLES:
        values = list(normal(t)) + [x for i in t for x in CORNERS[i]]
        data += struct.pack("<12fH", *values, 0)
    open("cube_binary.stl", "wb").write(data)


def obj():
    # Quads (fan-triangulated by the reader), every corner form, negative indices.
    text = """# unit cube, quads
mtllib cube.mtl
o cube
v 0 0 0
v 1 0 0
v 1 1 0
v 0 1 0
v 0 0 1
v 1 0 1
v 1 1 1
v 0 1 1
vt 0 0
vt 1 0
vt 1 1
vt 0 1
vn 0 0 -1
vn 0 0 1
g bottom
usemtl grey
s off
f 1/1/1 4/4/1 3/3/1 2/2/1
g top
f 5//2 6//2 7//2 8//2   # v//vn
f 1/1 2/2 6/3 5/4
f -6 -5 -1 -2
f 1 5 8 4
f 2 3 7 6
"""
    open("cube.obj", "w").write(text)


def gts():
    edges = []
    faces = []
    for t in TRIANGLES:
        face = []
        for a, b in ((t[0], t[1]), (t[1], t[2]), (t[2], t[0])):
            key = (min(a, b), max(a, b))
            if key not in edges:
                edges.append(key)
            face.append(edges.index(key) + 1)
        faces.append(face)
    lines = ["%d %d %d GtsSurface GtsFace GtsEdge GtsVertex" % (len(CORNERS), len(edges), len(faces))]
    lines += ["%g %g %g" % c for c in CORNERS]
    lines += ["%d %d" % (a + 1, b + 1) for a, b in edges]
    lines += ["%d %d %d" % tuple(f) for f in faces]
    open("cube.gts", "w").write("\n".join(lines) + "\n")


def medit():
    # Extra sections and an interior vertex used only by a tetrahedron: all ignored.
    lines = ["MeshVersionFormatted 2", "", "Dimension 3", "", "# the cube's corners and its centre",
             "Vertices", str(len(CORNERS) + 1)]
    lines += ["%g %g %g 0" % c for c in CORNERS]
    lines += ["0.5 0.5 0.5 1"]
    lines += ["", "Edges", "2", "1 2 0", "2 3 0", "", "Triangles", str(len(TRIANGLES))]
    lines += ["%d %d %d 1" % tuple(i + 1 for i in t) for t in TRIANGLES]
    lines += ["", "Tetrahedra", "1", "1 2 4 9 2", "", "Corners", "1", "1", "", "End"]
    open("cube.mesh", "w").write("\n".join(lines) + "\n")


def msh22():
    # Non-contiguous node tags, a point, lines, a tetrahedron with an interior node, and two
    # of the triangles as 6-node triangles (type 9) with mid-side nodes.
    tag = [10 * (i + 1) for i in range(len(CORNERS))]
    nodes = [(tag[i],) + c for i, c in enumerate(CORNERS)]
    nodes.append((500, 0.5, 0.5, 0.5))
    elements = ["1 15 2 1 1 %d" % tag[0], "2 1 2 2 1 %d %d" % (tag[0], tag[1]),
                "3 1 2 2 1 %d %d" % (tag[1], tag[2])]
    mid_tag = 1000
    for k, t in enumerate(TRIANGLES):
        number = k + 4
        if k < 2:
            mids = []
            for a, b in ((t[0], t[1]), (t[1], t[2]), (t[2], t[0])):
                p = tuple((CORNERS[a][j] + CORNERS[b][j]) / 2 for j in range(3))
                nodes.append((mid_tag,) + p)
                mids.append(mid_tag)
                mid_tag += 1
            elements.append("%d 9 2 3 1 %s %s" % (number, " ".join(str(tag[i]) for i in t),
                                                 " ".join(map(str, mids))))
        else:
            elements.append("%d 2 2 3 1 %s" % (number, " ".join(str(tag[i]) for i in t)))
    elements.append("%d 4 2 4 2 %d %d %d 500" % (len(TRIANGLES) + 4, tag[0], tag[1], tag[3]))
    lines = ["$MeshFormat", "2.2 0 8", "$EndMeshFormat",
             "$PhysicalNames", "4", "0 1 \"corner\"", "1 2 \"edges\"", "2 3 \"skin\"", "3 4 \"solid\"",
             "$EndPhysicalNames", "$Nodes", str(len(nodes))]
    lines += ["%d %g %g %g" % n for n in nodes]
    lines += ["$EndNodes", "$Elements", str(len(elements))] + elements + ["$EndElements"]
    open("cube_v22_ascii.msh", "w").write("\n".join(lines) + "\n")


if __name__ == "__main__":
    stl_ascii()
    stl_binary()
    obj()
    gts()
    medit()
    msh22()
