# -*- coding: utf-8 -*-
"""
Speed twin of YADE's net drop (shared/reference/yade/net_drop/net_drop.py): the scene is
built by the reference script's code, copied here unchanged; nothing is written and no
PyRunner samples the run (output off).
flexdem's twin: bench/scenes/net_drop_yade.toml (bench/yade/twin.py net).

Run:  yade -j 1 -n -x bench/yade/net_drop.py        (bench/run_vs_yade.sh does)
      environment: WARMUP untimed steps (default 6000: the sphere falls at 0.7 g and touches
      the net after about 0.13 s = 6000 steps), STEPS timed steps (default 20000, 0.43 s: the
      impact, the sag and the first rebound).
Prints parseable lines: YADE_DT, YADE_WALL_S, YADE_CPU_S, YADE_STEPS, YADE_CONTACTS
(sphere-connection contacts at the end), YADE_SPHERE_Z, YADE_SPHERE_VZ (m, m/s, after
WARMUP + STEPS steps), YADE_BODIES.

SCENE (the reference's header has every detail): 11 x 11 GridNodes at (0.1 i, 0.1 j, 0),
220 GridConnections (x links then y links), r = 5 mm, CohFrictMat nodes / FrictMat connections
E = 100 MPa, nu = 0.3, 1000 kg/m3, 30 deg; the 40 boundary nodes blockedDOFs 'xyz'. Sphere
r = 0.1 m, E = 100 MPa, 1000 kg/m3, at (0.45, 0.45, 0.15), at rest. Gravity -9.81 z, damping
0.3 on every body, dt = 0.5 * PWaveTimeStep(). Connections mask 2, sphere mask 3,
avoidSelfInteractionMask 2: no connection-connection pairs.
"""
from yade import *
from yade.gridpfacet import gridNode, gridConnection
import math, os, time

WARMUP = int(os.environ.get('WARMUP', '6000'))
STEPS = int(os.environ.get('STEPS', '20000'))
N, H, RN = 10, 0.1, 0.005
E_NET, E_S, NU, RHO, PHI = 1e8, 1e8, 0.3, 1000.0, math.radians(30)
RS = 0.1
S0 = Vector3(0.45, 0.45, 0.15)
G = -9.81
DAMP = 0.3

O.engines = [
        ForceResetter(),
        InsertionSortCollider([Bo1_Sphere_Aabb(), Bo1_GridConnection_Aabb()], avoidSelfInteractionMask=2),
        InteractionLoop(
                [Ig2_GridNode_GridNode_GridNodeGeom6D(), Ig2_Sphere_GridConnection_ScGridCoGeom()],
                [Ip2_CohFrictMat_CohFrictMat_CohFrictPhys(setCohesionNow=True, setCohesionOnNewContacts=False),
                 Ip2_FrictMat_FrictMat_FrictPhys()],
                [Law2_ScGeom6D_CohFrictPhys_CohesionMoment(), Law2_ScGridCoGeom_FrictPhys_CundallStrack()],
        ),
        NewtonIntegrator(gravity=(0, 0, G), damping=DAMP, label='newton'),
]
O.materials.append(
        CohFrictMat(
                young=E_NET, poisson=NU, density=RHO, frictionAngle=PHI, normalCohesion=1e100, shearCohesion=1e100, momentRotationLaw=True,
                label='netNode'
        )
)
O.materials.append(FrictMat(young=E_NET, poisson=NU, density=RHO, frictionAngle=PHI, label='netExt'))
O.materials.append(FrictMat(young=E_S, poisson=NU, density=RHO, frictionAngle=PHI, label='sphereMat'))

nid = lambda i, j: (N + 1) * i + j
nodes = []
for i in range(N + 1):
	for j in range(N + 1):
		nodes.append(O.bodies.append(gridNode(Vector3(H * i, H * j, 0), RN, wire=False, fixed=False, material='netNode')))
links = []
for i in range(N):
	for j in range(N + 1):
		links.append((nid(i, j), nid(i + 1, j)))
for i in range(N + 1):
	for j in range(N):
		links.append((nid(i, j), nid(i, j + 1)))
conns = [O.bodies.append(gridConnection(nodes[a], nodes[b], RN, material='netExt', mask=2)) for a, b in links]
for i in range(N + 1):
	for j in range(N + 1):
		if i in (0, N) or j in (0, N): O.bodies[nodes[nid(i, j)]].state.blockedDOFs = 'xyz'
sid = O.bodies.append(sphere(S0, RS, material='sphereMat', mask=3))
O.dt = 0.5 * PWaveTimeStep()

# ---------------------------------------------------------------- timing (output off)
if WARMUP > 0: O.run(WARMUP, True)  # O.run(0) would run for ever
w0, c0 = time.perf_counter(), time.process_time()
O.run(STEPS, True)
wall, cpu = time.perf_counter() - w0, time.process_time() - c0
s = O.bodies[sid].state
print('YADE_DT %r' % O.dt)
print('YADE_WALL_S %.6f' % wall)
print('YADE_CPU_S %.6f' % cpu)
print('YADE_STEPS %d' % STEPS)
print('YADE_CONTACTS %d' % sum(1 for I in O.bodies[sid].intrs() if I.isReal))
print('YADE_SPHERE_Z %.9e' % s.pos[2])
print('YADE_SPHERE_VZ %.9e' % s.vel[2])
print('YADE_BODIES %d' % len(O.bodies))
