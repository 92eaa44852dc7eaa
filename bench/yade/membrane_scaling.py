# -*- coding: utf-8 -*-
"""
Speed twin of YADE's membrane scaling run (shared/reference/yade/membrane_scaling/
membrane_scaling.py): the scene is built by the reference script's code, copied here unchanged;
the timing is the wall and CPU time of O.run(STEPS, True) after O.run(WARMUP, True) instead of
the reference's PyRunner marks, and nothing is written (output off).
flexdem's twin: `python3 bench/yade/twin.py membrane -n N` (bench/run_vs_yade.sh writes it).

Run:  yade -j 1 -n -x bench/yade/membrane_scaling.py N VARIANT     (bench/run_vs_yade.sh does)
      N: nodes per side (20, 40, 80); VARIANT: 'noself' (membrane self-contact off by collision
      masks) or 'self' (PFacet-PFacet candidates processed, as in the tube scenarios)
      environment: WARMUP (default 50) untimed steps, STEPS (default 200) timed steps: the
      reference's 50 + 200.
Prints parseable lines: YADE_DT, YADE_WALL_S, YADE_CPU_S, YADE_STEPS, YADE_CONTACTS (real
interactions other than links, at the end), YADE_SPHERE_VZ (vz of sphere a = b = N/4, the
sphere nearest the centre, m/s), YADE_NODE_Z (z of node (N/2, N/2), m), YADE_KE (translational
kinetic energy of the nodes and spheres, J), YADE_BODIES.

SCENE (the reference's header has every detail): 1 m x 1 m membrane in z = 0, N x N GridNodes at
(i h, j h, 0), h = 1/(N-1), cells split along (i,j)-(i+1,j+1), r = 3 mm, CohFrictMat nodes /
FrictMat connections and PFacets E = 10 MPa, nu = 0.3, 1000 kg/m3, 30 deg; boundary nodes
blockedDOFs 'xyz'. (N/2)^2 spheres of radius 0.35 s (s = 2/N) at ((a + 0.5) s, (b + 0.5) s,
r + R_s), E = 10 MPa, 2000 kg/m3, velocity (0, 0, -0.1). Gravity -9.81 z, damping 0.2,
dt = 0.5 * PWaveTimeStep().
"""
from yade import *
from yade.gridpfacet import gridNode, gridConnection, pfacet
import math, os, sys, time

N = int(sys.argv[1]) if len(sys.argv) > 1 else 20
VARIANT = sys.argv[2] if len(sys.argv) > 2 else 'noself'
assert VARIANT in ('self', 'noself')
WARM = int(os.environ.get('WARMUP', '50'))
NT = int(os.environ.get('STEPS', '200'))
RN = 0.003
H = 1.0 / (N - 1)
E, NU, RHO, PHI = 1e7, 0.3, 1000.0, math.radians(30)
MEMMASK, SPHMASK, AVOID = (3, 1, 2) if VARIANT == 'noself' else (1, 1, 0)

O.engines = [
        ForceResetter(),
        InsertionSortCollider([Bo1_Sphere_Aabb(), Bo1_GridConnection_Aabb(), Bo1_PFacet_Aabb()], avoidSelfInteractionMask=AVOID, label='collider'),
        InteractionLoop(
                [
                        Ig2_GridNode_GridNode_GridNodeGeom6D(),
                        Ig2_Sphere_Sphere_ScGeom(),
                        Ig2_Sphere_PFacet_ScGridCoGeom(),
                        Ig2_GridConnection_GridConnection_GridCoGridCoGeom(),
                        Ig2_GridConnection_PFacet_ScGeom(),
                        Ig2_PFacet_PFacet_ScGeom(),
                ],
                [
                        Ip2_CohFrictMat_CohFrictMat_CohFrictPhys(setCohesionNow=True, setCohesionOnNewContacts=False),
                        Ip2_FrictMat_FrictMat_FrictPhys()
                ],
                [
                        Law2_ScGeom6D_CohFrictPhys_CohesionMoment(),
                        Law2_ScGeom_FrictPhys_CundallStrack(),
                        Law2_ScGridCoGeom_FrictPhys_CundallStrack(),
                        Law2_GridCoGridCoGeom_FrictPhys_CundallStrack(),
                ],
        ),
        NewtonIntegrator(gravity=(0, 0, -9.81), damping=0.2, label='newton'),
]
O.materials.append(
        CohFrictMat(
                young=E, poisson=NU, density=RHO, frictionAngle=PHI, normalCohesion=1e100, shearCohesion=1e100, momentRotationLaw=True, label='memNode'
        )
)
O.materials.append(FrictMat(young=E, poisson=NU, density=RHO, frictionAngle=PHI, label='memExt'))
O.materials.append(FrictMat(young=E, poisson=NU, density=2000.0, frictionAngle=PHI, label='sphMat'))

nid = lambda i, j: N * i + j
nodes = [O.bodies.append(gridNode(Vector3(H * i, H * j, 0), RN, wire=False, fixed=False, material='memNode')) for i in range(N) for j in range(N)]
tris = []
for i in range(N - 1):
	for j in range(N - 1):
		tris += [(nid(i, j), nid(i + 1, j), nid(i + 1, j + 1)), (nid(i, j), nid(i + 1, j + 1), nid(i, j + 1))]
edges, seen = [], set()
for t in tris:
	for a, b in ((t[0], t[1]), (t[1], t[2]), (t[2], t[0])):
		k = (min(a, b), max(a, b))
		if k not in seen:
			seen.add(k)
			edges.append(k)
conns = [O.bodies.append(gridConnection(nodes[a], nodes[b], RN, material='memExt', mask=MEMMASK)) for a, b in edges]
pfs = [O.bodies.append(pfacet(nodes[t[0]], nodes[t[1]], nodes[t[2]], wire=False, material='memExt', mask=MEMMASK)) for t in tris]
for i in range(N):
	for j in range(N):
		if i in (0, N - 1) or j in (0, N - 1): O.bodies[nodes[nid(i, j)]].state.blockedDOFs = 'xyz'
M = N // 2
S = 1.0 / M
RS = 0.35 * S
sph = [O.bodies.append(sphere(Vector3((a + 0.5) * S, (b + 0.5) * S, RN + RS), RS, material='sphMat', mask=SPHMASK)) for a in range(M) for b in range(M)]
for b in sph:
	O.bodies[b].state.vel = Vector3(0, 0, -0.1)
O.dt = 0.5 * PWaveTimeStep()

# ---------------------------------------------------------------- timing (output off)
if WARM > 0: O.run(WARM, True)  # O.run(0) would run for ever
w0, c0 = time.perf_counter(), time.process_time()
O.run(NT, True)
wall, cpu = time.perf_counter() - w0, time.process_time() - c0
contacts = sum(1 for I in O.interactions if not isinstance(I.geom, GridNodeGeom6D))
print('YADE_DT %r' % O.dt)
print('YADE_WALL_S %.6f' % wall)
print('YADE_CPU_S %.6f' % cpu)
print('YADE_STEPS %d' % NT)
print('YADE_CONTACTS %d' % contacts)
print('YADE_SPHERE_VZ %.9e' % O.bodies[sph[(M // 2) * M + M // 2]].state.vel[2])
print('YADE_NODE_Z %.9e' % O.bodies[nodes[nid(N // 2, N // 2)]].state.pos[2])
print('YADE_KE %.9e' % sum(0.5 * O.bodies[b].state.mass * O.bodies[b].state.vel.squaredNorm() for b in nodes + sph))
print('YADE_BODIES %d' % len(O.bodies))
