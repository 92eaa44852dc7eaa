#!/usr/bin/env python3
"""Writes the malformed meshes of this folder (run from this folder). Each must make its
reader return an error naming the file (and the line, for text) -- see
crates/mesh/tests/mesh_bad_inputs.rs for the expected messages."""
import struct

GOOD = "../meshes/"
CUBE_V = "".join("v %d %d %d\n" % c for c in [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0),
                                              (0, 0, 1), (1, 0, 1), (1, 1, 1), (0, 1, 1)])
TRI_V = "v 0 0 0\nv 1 0 0\nv 0 1 0\n"

TEXT = {
    # OBJ
    "empty.obj": "",
    "obj_face_two_vertices.obj": "# a face needs 3 corners\n" + TRI_V + "f 1 2\n",
    "obj_index_out_of_range.obj": "# index 9 of 8 vertices\n" + CUBE_V + "f 1 2 9\n",
    "obj_nan_vertex.obj": "v nan 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n",
    "obj_non_numeric.obj": "v 0 0 0\nv 1 zero 0\nv 0 1 0\nf 1 2 3\n",
    "obj_relative_index_too_far.obj": TRI_V + "f -1 -2 -4\n",
    "obj_zero_index.obj": TRI_V + "\nf 0 1 2\n",
    "obj_bad_corner.obj": TRI_V + "f 1/1/1/1 2 3\n",
    "obj_short_vertex.obj": "v 0 0 0\nv 1 0\nv 0 1 0\nf 1 2 3\n",
    "obj_only_vertices.obj": TRI_V,
    # GTS
    "gts_edge_missing_vertex.gts": "3 3 1\n0 0 0\n1 0 0\n0 1 0\n1 2\n2 4\n3 1\n1 2 3\n",
    "gts_truncated.gts": "".join(open(GOOD + "cube.gts").readlines()[:13]),
    "gts_face_not_triangle.gts": "4 4 1\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n1 2\n2 3\n3 4\n4 1\n1 2 3\n",
    "gts_bad_header.gts": "eight 18 12\n",
    "gts_face_edge_out_of_range.gts": "3 3 1\n0 0 0\n1 0 0\n0 1 0\n1 2\n2 3\n3 1\n1 2 4\n",
    "gts_huge_count.gts": "1000000000 1000000000 1\n0 0 0\n",
    "gts_inf_vertex.gts": "3 3 1\n0 0 0\n1 inf 0\n0 1 0\n1 2\n2 3\n3 1\n1 2 3\n",
    # MEDIT
    "mesh_triangle_out_of_range.mesh": "MeshVersionFormatted 1\nDimension 3\nVertices\n3\n0 0 0 0\n1 0 0 0\n0 1 0 0\n"
                                       "Triangles\n2\n1 2 3 0\n1 2 9 0\nEnd\n",
    "mesh_missing_triangles.mesh": "MeshVersionFormatted 1\nDimension 3\nVertices\n3\n0 0 0 0\n1 0 0 0\n0 1 0 0\nEnd\n",
    "mesh_dimension_2.mesh": "MeshVersionFormatted 1\nDimension 2\nVertices\n3\n0 0 0\n1 0 0\n0 1 0\nEnd\n",
    "mesh_truncated_vertices.mesh": "MeshVersionFormatted 1\nDimension 3\nVertices\n4\n0 0 0 0\n1 0 0 0\n0 1 0 0\n"
                                    "Triangles\n1\n1 2 3 0\nEnd\n",
    "mesh_count_too_large.mesh": "MeshVersionFormatted 1\nDimension 3\nVertices\n1000\n0 0 0 0\n1 0 0 0\n0 1 0 0\n"
                                 "Triangles\n1\n1 2 3 0\nEnd\n",
    "mesh_inf_coordinate.mesh": "MeshVersionFormatted 1\nDimension 3\nVertices\n3\n0 0 0 0\n1 0 0 0\ninf 1 0 0\n"
                                "Triangles\n1\n1 2 3 0\nEnd\n",
    "mesh_no_version.mesh": "Dimension 3\nVertices\n3\n0 0 0 0\n1 0 0 0\n0 1 0 0\nTriangles\n1\n1 2 3 0\nEnd\n",
    # ASCII STL
    "stl_ascii_truncated.stl": "".join(open(GOOD + "cube_ascii.stl").readlines()[:12]),
    "stl_ascii_two_vertices.stl": "solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\n"
                                  "endloop\nendfacet\nendsolid t\n",
    "stl_ascii_bad_number.stl": "solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\n"
                                "vertex 0 1 z\nendloop\nendfacet\nendsolid t\n",
    "stl_ascii_empty_solid.stl": "solid t\nendsolid t\n",
    "stl_too_short.stl": "abc\n",
    # Gmsh
    "msh_version3.msh": "$MeshFormat\n3.0 0 8\n$EndMeshFormat\n",
    "msh_missing_nodes.msh": "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Elements\n1\n1 2 2 0 1 1 2 3\n$EndElements\n",
    "msh_no_format.msh": "$Nodes\n1\n1 0 0 0\n$EndNodes\n",
    "msh_unterminated_section.msh": "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$PhysicalNames\n1\n2 1 \"skin\"\n",
    "msh22_node_three_numbers.msh": "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n3\n1 0 0 0\n2 1 0\n3 0 1 0\n$EndNodes\n",
    "msh22_unknown_node_tag.msh": "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n3\n1 0 0 0\n2 1 0 0\n3 0 1 0\n$EndNodes\n"
                                  "$Elements\n1\n1 2 2 0 1 1 2 99\n$EndElements\n",
    "msh22_no_triangles.msh": "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n2\n1 0 0 0\n2 1 0 0\n$EndNodes\n"
                              "$Elements\n1\n1 1 2 0 1 1 2\n$EndElements\n",
    "msh22_count_too_small.msh": "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n2\n1 0 0 0\n2 1 0 0\n3 0 1 0\n$EndNodes\n",
    "msh22_count_too_large.msh": "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n4\n1 0 0 0\n2 1 0 0\n3 0 1 0\n$EndNodes\n",
    "msh22_nan_node.msh": "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n3\n1 0 0 0\n2 NaN 0 0\n3 0 1 0\n$EndNodes\n",
    "msh22_duplicate_node_tag.msh": "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n3\n1 0 0 0\n2 1 0 0\n2 0 1 0\n$EndNodes\n"
                                    "$Elements\n1\n1 2 2 0 1 1 2 2\n$EndElements\n",
    "msh22_triangle_two_nodes.msh": "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n3\n1 0 0 0\n2 1 0 0\n3 0 1 0\n$EndNodes\n"
                                    "$Elements\n1\n1 2 2 0 1 1 2\n$EndElements\n",
    "msh41_block_total_mismatch.msh": "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Nodes\n1 5 1 4\n2 1 0 4\n1\n2\n3\n4\n"
                                      "0 0 0\n1 0 0\n0 1 0\n0 0 1\n$EndNodes\n",
    "msh41_bad_coordinates.msh": "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Nodes\n1 3 1 3\n2 1 0 3\n1\n2\n3\n"
                                 "0 0 0\n1 0 0\n0 1\n$EndNodes\n",
}

for name, text in TEXT.items():
    open(name, "w").write(text)

# Binary STL: declares 12 triangles, holds 11.
cube = open(GOOD + "cube_binary.stl", "rb").read()
open("stl_binary_wrong_size.stl", "wb").write(cube[:-50])
# Binary STL with a NaN x for the first vertex of its only triangle (byte 84 + 12 = 96).
one = b"binary".ljust(80, b"\0") + struct.pack("<I", 1) + struct.pack("<12fH", 0, 0, 1, float("nan"), 0, 0, 1, 0, 0, 0, 1, 0, 0)
open("stl_binary_nan.stl", "wb").write(one)
# Gmsh binary files cut short, and one whose byte-order integer is 2.
v22 = open(GOOD + "cube_v22_binary.msh", "rb").read()
start = v22.index(b"$Nodes")
open("msh22_binary_truncated.msh", "wb").write(v22[: start + 100])
v41 = open(GOOD + "cube_v41_binary.msh", "rb").read()
start = v41.index(b"$Elements")
open("msh41_binary_truncated.msh", "wb").write(v41[: start + 60])
open("msh22_binary_bad_byte_order.msh", "wb").write(v22.replace(b"8\n\x01\x00\x00\x00", b"8\n\x02\x00\x00\x00", 1))
