#!/usr/bin/env python3
"""flexdem scene files that are the twins of the YADE reference runs (shared/reference/yade):
the same mesh (node positions written with Python's repr, i.e. bit for bit the floats YADE's
scripts compute), triangle split, masses, materials, boundary conditions, initial velocities
and the same FIXED time step, dt = 0.5 * YADE's PWaveTimeStep() of the scene, computed here by
YADE's formula (Shop::PWaveTimeStep: min over GridNodes, GridConnections and Spheres of
r / sqrt(E / rho_eff), rho_eff = mass / (4/3 pi r^3)); bench/run_vs_yade.sh checks it against
the value YADE prints.

   python3 bench/yade/twin.py tube     --out DIR    -> DIR/tube_impact_solid_yade.{toml,obj}
   python3 bench/yade/twin.py membrane --out DIR -n N -> DIR/membrane_N<N>.toml (self-contact),
                                                      DIR/membrane_N<N>_noself.toml (none), DIR/membrane_N<N>_spheres.csv
   python3 bench/yade/twin.py net      --out DIR    -> DIR/net_drop_yade.toml
   python3 bench/yade/twin.py dt SCENE [-n N]       -> prints the dt (s) only

Every scene uses flexdem's YADE options: link_kinematics = "yade" (YADE's 2r/L shear factor of
the links), mass lumping "connections" (YADE's: each connection puts pi r^2 L rho / 2 on each of
its nodes, PFacets nothing), ks/kn of contacts = YADE's "poisson" (shear_ratio defaults to it),
links unbreakable (YADE: cohesion 1e100), moments on (YADE: momentRotationLaw=True).
What cannot be the same is listed in bench/README.md ("YADE twins").

Each scene has [[output.series]] for its physical check (`flexdem run --summary` reads their
final values); `flexdem bench --scene-file` ignores [output] (output off).
"""
import argparse
import math
import os
import sys

PI = math.pi


def fmt(x):
    """Shortest round-trip text of a float (Rust parses it back to the same bits)."""
    return repr(float(x))


def vec(v):
    return '[' + ', '.join(fmt(c) for c in v) + ']'


def unique_edges(tris):
    """YADE's unique_edges: the triangles' edges in order of first appearance."""
    edges, seen = [], set()
    for t in tris:
        for a, b in ((t[0], t[1]), (t[1], t[2]), (t[2], t[0])):
            k = (min(a, b), max(a, b))
            if k not in seen:
                seen.add(k)
                edges.append(k)
    return edges


def norm(p):
    return math.sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2])


def sub(p, q):
    return (p[0] - q[0], p[1] - q[1], p[2] - q[2])


def pwave(nodes, edges, r, e_node, rho_node, e_ext, rho_ext, spheres=()):
    """YADE's PWaveTimeStep for a grid structure plus spheres (radius, young, mass).
    Node mass: sum of V rho_node over its connections, V = 0.5 L pi r^2 (gridConnection());
    a connection body has mass V rho_ext (it is fixed, but PWaveTimeStep reads it)."""
    mass = [0.0] * len(nodes)
    dt = math.inf
    vol = 4.0 / 3.0 * PI * r**3
    for a, b in edges:
        L = norm(sub(nodes[b], nodes[a]))
        V = 0.5 * L * PI * r**2
        mass[a] += V * rho_node
        mass[b] += V * rho_node
        dt = min(dt, r / math.sqrt(e_ext / (V * rho_ext / vol)))
    for m in mass:
        dt = min(dt, r / math.sqrt(e_node / (m / vol)))
    for rs, es, ms in spheres:
        dt = min(dt, rs / math.sqrt(es / (ms / (4.0 / 3.0 * PI * rs**3))))
    return dt


# ------------------------------------------------------------------------------------ tube
# shared/reference/yade/tube_impact/tube_impact.py, mode 'solid' (scenario 2)
T_RT, T_LT, T_NI, T_NJ, T_THOFF = 0.1, 0.8, 21, 16, 0.5
T_RN = 0.002
T_E_TUBE, T_E_IMP, T_NU, T_RHO, T_PHI_DEG = 1e6, 1e8, 0.3, 1000.0, 30
T_RS, T_GAP, T_V0 = 0.1, 0.001, 2.0


def octasphere(R):
    """The hollow impactor's mesh (tube_impact.py's octasphere), only for its mass."""
    verts, key, tris, NS = [], {}, [], 4

    def vid(p):
        k = tuple(round(c, 12) for c in p)
        if k not in key:
            key[k] = len(verts)
            verts.append(p)
        return key[k]

    for sx in (1, -1):
        for sy in (1, -1):
            for sz in (1, -1):
                V = [(sx, 0, 0), (0, sy, 0), (0, 0, sz)]
                if sx * sy * sz < 0:
                    V = [V[0], V[2], V[1]]
                g = {}
                for a in range(NS + 1):
                    for b in range(NS + 1 - a):
                        c = NS - a - b
                        p = tuple((V[0][k] * a + V[1][k] * b + V[2][k] * c) / float(NS) for k in range(3))
                        n = norm(p)
                        g[(a, b)] = vid(tuple(x / n * R for x in p))
                for a in range(NS):
                    for b in range(NS - a):
                        tris.append((g[(a, b)], g[(a + 1, b)], g[(a, b + 1)]))
                        if a + b < NS - 1:
                            tris.append((g[(a + 1, b)], g[(a + 1, b + 1)], g[(a, b + 1)]))
    return verts, tris


def tube_mesh():
    verts = []
    for i in range(T_NI):
        for j in range(T_NJ):
            th = 2 * PI * (j + T_THOFF) / T_NJ
            verts.append((T_LT * i / (T_NI - 1), T_RT * math.cos(th), T_RT * math.sin(th)))
    tid = lambda i, j: T_NJ * i + (j % T_NJ)
    tris = []
    for i in range(T_NI - 1):
        for j in range(T_NJ):
            if i < (T_NI - 1) // 2:
                tris += [(tid(i, j), tid(i + 1, j), tid(i + 1, j + 1)), (tid(i, j), tid(i + 1, j + 1), tid(i, j + 1))]
            else:
                tris += [(tid(i, j), tid(i + 1, j), tid(i, j + 1)), (tid(i + 1, j), tid(i + 1, j + 1), tid(i, j + 1))]
    return verts, tris


def tube_params():
    verts, tris = tube_mesh()
    ov, ot = octasphere(T_RS)
    m_hollow = PI * T_RN**2 * T_RHO * sum(norm(sub(ov[a], ov[b])) for a, b in unique_edges(ot))
    rho_s = m_hollow / (4. / 3. * PI * T_RS**3)
    m_s = 4. / 3. * PI * T_RS**3 * rho_s  # YADE's sphere(): mass = volume * density
    ztop = max(v[2] for v in verts)
    z0 = ztop + T_RN + T_RS + T_GAP
    dt = 0.5 * pwave(verts, unique_edges(tris), T_RN, T_E_TUBE, T_RHO, T_E_TUBE, T_RHO, [(T_RS, T_E_IMP, m_s)])
    return verts, tris, rho_s, m_s, z0, dt


def write_tube(out):
    verts, tris, rho_s, m_s, z0, dt = tube_params()
    with open(os.path.join(out, 'tube_impact_solid_yade.obj'), 'w') as f:
        f.write('# The tube of shared/reference/yade/tube_impact/tube_impact.py (written by bench/yade/twin.py):\n')
        f.write('# 21 rings x 16 nodes, node k = 16 i + j at (0.04 i, 0.1 cos th, 0.1 sin th), th = 2 pi (j + 0.5) / 16;\n')
        f.write('# quads split along (i,j)-(i+1,j+1) for i < 10 and along (i+1,j)-(i,j+1) for i >= 10.\n')
        for v in verts:
            f.write('v %s %s %s\n' % tuple(fmt(c) for c in v))
        for t in tris:
            f.write('f %d %d %d\n' % tuple(k + 1 for k in t))
    toml = f'''# The twin of YADE's tube impact, scenario 2 "solid" (shared/reference/yade/tube_impact/
# tube_impact.py solid), for the speed comparison bench/run_vs_yade.sh. Written by
# `python3 bench/yade/twin.py tube --out bench/scenes`: do not edit, regenerate.
#
# Tube: tube_impact_solid_yade.obj, YADE's mesh bit for bit (21 rings x 16 nodes with the
# half-step angular offset, the quads of the first 10 segments split along (i,j)-(i+1,j+1) and
# those of the last 10 along (i+1,j)-(i,j+1): mirror-symmetric about x = 0.4); 336 nodes,
# 976 connections, 640 PFacets, radius 2 mm; E = 1 MPa, nu = 0.3, 1000 kg/m3, 30 deg; YADE's
# mass lumping (connections only); both end rings (x = 0, x = 0.8) clamped (xyzXYZ).
# Impactor: rigid sphere, radius 0.1 m, E = 100 MPa, density {rho_s!r} kg/m3 (mass
# {m_s!r} kg, the hollow impactor's), centre (0.4, 0, z_top + 2 mm + 0.1 m + 1 mm),
# velocity (0, 0, -2) m/s. No gravity, no damping.
# dt: YADE's, 0.5 * PWaveTimeStep() = {dt!r} s (fixed; the sphere's P-wave step sets it).
# Differences from YADE that remain: bench/README.md, "YADE twins".

[simulation]
dt = {fmt(dt)}
steps = 5800                # about 0.15 s; bench/run_vs_yade.sh sets its own steps
gravity = [0, 0, 0]
damping = 0.0
link_kinematics = "yade"

[materials.tube]
young = 1e6
poisson = 0.3
density = 1000
friction_angle_deg = 30

[materials.sphere]
young = 1e8
poisson = 0.3
density = {fmt(rho_s)}
friction_angle_deg = 30

[[structures]]
name = "tube"
kind = "mesh"
material = "tube"
node_radius = 0.002
file = "tube_impact_solid_yade.obj"
merge_tolerance = 0         # YADE's nodes, one per vertex
mass = "connections"

[[spheres]]
name = "impactor"
kind = "single"
material = "sphere"
center = [0.4, 0.0, {fmt(z0)}]
radius = 0.1
velocity = [0, 0, -2]

[[boundary]]
select = {{ structure = "tube", plane = {{ point = [0, 0, 0], normal = [1, 0, 0], tolerance = 1e-9 }} }}
block = "xyzXYZ"

[[boundary]]
select = {{ structure = "tube", plane = {{ point = [0.8, 0, 0], normal = [1, 0, 0], tolerance = 1e-9 }} }}
block = "xyzXYZ"

[output]
directory = "output/tube_impact_solid_yade"
series_every = 25

[[output.series]]
name = "impactor_velocity"
quantity = "velocity"
of = {{ spheres = "impactor" }}
'''
    path = os.path.join(out, 'tube_impact_solid_yade.toml')
    with open(path, 'w') as f:
        f.write(toml)
    return path


# -------------------------------------------------------------------------------- membrane
# shared/reference/yade/membrane_scaling/membrane_scaling.py
M_RN, M_E, M_NU, M_RHO, M_RHO_S = 0.003, 1e7, 0.3, 1000.0, 2000.0


def membrane_params(n):
    h = 1.0 / (n - 1)
    nid = lambda i, j: n * i + j
    nodes = [(h * i, h * j, 0.0) for i in range(n) for j in range(n)]
    tris = []
    for i in range(n - 1):
        for j in range(n - 1):
            tris += [(nid(i, j), nid(i + 1, j), nid(i + 1, j + 1)), (nid(i, j), nid(i + 1, j + 1), nid(i, j + 1))]
    m = n // 2
    s = 1.0 / m
    rs = 0.35 * s
    spheres = [((a + 0.5) * s, (b + 0.5) * s, M_RN + rs) for a in range(m) for b in range(m)]
    ms = 4. / 3. * PI * rs**3 * M_RHO_S
    dt = 0.5 * pwave(nodes, unique_edges(tris), M_RN, M_E, M_RHO, M_E, M_RHO, [(rs, M_E, ms)])
    return h, m, s, rs, spheres, dt


def write_membrane(out, n, self_contact=True):
    """The twin of membrane_scaling.py N self (self_contact) or N noself (not): the second
    file, membrane_N<N>_noself.toml, turns the membrane's self-contact off."""
    h, m, s, rs, spheres, dt = membrane_params(n)
    base = 'membrane_N%d' % n
    stem = base if self_contact else base + '_noself'
    with open(os.path.join(out, base + '_spheres.csv'), 'w') as f:
        f.write('# membrane_scaling.py N=%d: sphere (a, b) at ((a + 0.5) s, (b + 0.5) s, r + R_s), s = 1/%d, in YADE order (a outer)\n' % (n, m))
        f.write('x,y,z,radius\n')
        for p in spheres:
            f.write('%s,%s,%s,%s\n' % (fmt(p[0]), fmt(p[1]), fmt(p[2]), fmt(rs)))
    c = n // 2
    probe_sphere = (m // 2) * m + (m // 2)  # YADE's sphere index a M + b, a = b = M/2
    toml = f'''# The twin of YADE's membrane scaling run (shared/reference/yade/membrane_scaling/
# membrane_scaling.py {n} {'self' if self_contact else 'noself'}), for bench/run_vs_yade.sh. Written by
# `python3 bench/yade/twin.py membrane -n {n}`: do not edit, regenerate.
#
# Membrane: 1 m x 1 m in z = 0, {n} x {n} nodes at (i h, j h, 0), h = 1/{n - 1} (flexdem's
# membrane builder computes the same floats), each cell split along (i,j)-(i+1,j+1) as YADE;
# {2 * (n - 1)**2} PFacets, {3 * (n - 1)**2 + 2 * (n - 1)} connections, radius 3 mm; E = 10 MPa, nu = 0.3,
# 1000 kg/m3, 30 deg; YADE's mass lumping (connections only); boundary nodes pinned (xyz).
# (flexdem numbers the nodes i + {n} j, YADE {n} i + j.)
# Spheres: {m * m} of radius 0.35 s = {rs!r} m (s = 1/{m}), {base}_spheres.csv (YADE's
# centres), 2000 kg/m3, E = 10 MPa, velocity (0, 0, -0.1) m/s, touching the membrane.
# Gravity -9.81 z, Cundall damping 0.2; dt: YADE's, 0.5 * PWaveTimeStep() = {dt!r} s (fixed).
# Self-contact: {'on: non-adjacent elements of the membrane pair (YADE' + "'" + 's "self" variant)' if self_contact else 'off (self_contact = false: YADE' + "'" + 's "noself" masks)'}.
# Differences: bench/README.md.

[simulation]
dt = {fmt(dt)}
steps = 250                 # YADE's 50 warm-up + 200 timed steps
gravity = [0, 0, -9.81]
damping = 0.2
link_kinematics = "yade"

[materials.membrane]
young = 1e7
poisson = 0.3
density = 1000
friction_angle_deg = 30

[materials.sphere]
young = 1e7
poisson = 0.3
density = 2000
friction_angle_deg = 30

[[structures]]
name = "membrane"
kind = "membrane"
material = "membrane"
node_radius = 0.003
origin = [0, 0, 0]
size = [1.0, 1.0]
cells = [{n - 1}, {n - 1}]
mass = "connections"
self_contact = {'true' if self_contact else 'false'}

[[spheres]]
name = "spheres"
kind = "file"
material = "sphere"
file = "{base}_spheres.csv"
velocity = [0, 0, -0.1]

[[boundary]]
select = {{ structure = "membrane", side = "boundary" }}
block = "xyz"

[output]
directory = "output/{stem}"
series_every = 50

[[output.series]]                # YADE's sphere a = b = {m // 2} (id {n * n + probe_sphere})
name = "probe_sphere_velocity"
quantity = "velocity"
of = {{ ids = [{n * n + probe_sphere}] }}

[[output.series]]                # node (i, j) = ({c}, {c}): flexdem id i + {n} j
name = "centre_node_position"
quantity = "position"
of = {{ ids = [{c + n * c}] }}
'''
    path = os.path.join(out, stem + '.toml')
    with open(path, 'w') as f:
        f.write(toml)
    return path


# ------------------------------------------------------------------------------------- net
# shared/reference/yade/net_drop/net_drop.py
N_N, N_H, N_RN, N_E, N_NU, N_RHO, N_RS = 10, 0.1, 0.005, 1e8, 0.3, 1000.0, 0.1
N_S0 = (0.45, 0.45, 0.15)


def net_params():
    nid = lambda i, j: (N_N + 1) * i + j
    nodes = [(N_H * i, N_H * j, 0.0) for i in range(N_N + 1) for j in range(N_N + 1)]
    links = [(nid(i, j), nid(i + 1, j)) for i in range(N_N) for j in range(N_N + 1)]
    links += [(nid(i, j), nid(i, j + 1)) for i in range(N_N + 1) for j in range(N_N)]
    ms = 4. / 3. * PI * N_RS**3 * N_RHO
    dt = 0.5 * pwave(nodes, links, N_RN, N_E, N_RHO, N_E, N_RHO, [(N_RS, N_E, ms)])
    return ms, dt


def write_net(out):
    ms, dt = net_params()
    toml = f'''# The twin of YADE's net drop (shared/reference/yade/net_drop/net_drop.py), for
# bench/run_vs_yade.sh. Written by `python3 bench/yade/twin.py net --out bench/scenes`: do not
# edit, regenerate.
#
# Net: 11 x 11 nodes at (0.1 i, 0.1 j, 0) (flexdem's net builder computes the same floats),
# 220 connections between nearest neighbours, no PFacets, no diagonals, radius 5 mm;
# E = 100 MPa, nu = 0.3, 1000 kg/m3, 30 deg; YADE's mass lumping; the 40 boundary nodes pinned
# (xyz, rotations free). Sphere: radius 0.1 m, E = 100 MPa, 1000 kg/m3 ({ms!r} kg), centre
# (0.45, 0.45, 0.15), at rest. Gravity -9.81 z, Cundall damping 0.3 on every body (gravity
# damped too, as YADE's NewtonIntegrator). dt: YADE's, 0.5 * PWaveTimeStep() = {dt!r} s
# (fixed; the connections' P-wave step sets it). YADE has no connection-connection contacts
# (masks); flexdem pairs non-adjacent connections of the net, which never meet here.

[simulation]
dt = {fmt(dt)}
duration = 3.0
gravity = [0, 0, -9.81]
damping = 0.3
link_kinematics = "yade"

[materials.net]
young = 1e8
poisson = 0.3
density = 1000
friction_angle_deg = 30

[materials.rock]
young = 1e8
poisson = 0.3
density = 1000
friction_angle_deg = 30

[[structures]]
name = "net"
kind = "net"
material = "net"
node_radius = 0.005
origin = [0, 0, 0]
size = [1.0, 1.0]
cells = [10, 10]
diagonals = false
mass = "connections"

[[spheres]]
name = "rock"
kind = "single"
material = "rock"
center = [0.45, 0.45, 0.15]
radius = 0.1

[[boundary]]
select = {{ structure = "net", side = "boundary" }}
block = "xyz"

[output]
directory = "output/net_drop_yade"
series_every = 1000

[[output.series]]
name = "rock_position"
quantity = "position"
of = {{ spheres = "rock" }}

[[output.series]]
name = "rock_velocity"
quantity = "velocity"
of = {{ spheres = "rock" }}
'''
    path = os.path.join(out, 'net_drop_yade.toml')
    with open(path, 'w') as f:
        f.write(toml)
    return path


def main():
    ap = argparse.ArgumentParser(description=__doc__.split('\n')[0])
    ap.add_argument('scene', choices=['tube', 'membrane', 'net', 'dt'])
    ap.add_argument('what', nargs='?', help='for dt: tube, membrane or net')
    ap.add_argument('--out', default='.')
    ap.add_argument('-n', type=int, default=20, help='membrane nodes per side')
    a = ap.parse_args()
    if a.scene == 'dt':
        dt = {'tube': lambda: tube_params()[-1], 'membrane': lambda: membrane_params(a.n)[-1],
              'net': lambda: net_params()[-1]}[a.what]()
        print(repr(dt))
        return
    os.makedirs(a.out, exist_ok=True)
    path = {'tube': lambda: write_tube(a.out),
            'membrane': lambda: (write_membrane(a.out, a.n, False), write_membrane(a.out, a.n))[1],
            'net': lambda: write_net(a.out)}[a.scene]()
    print(path)


if __name__ == '__main__':
    sys.exit(main())
