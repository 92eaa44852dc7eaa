# -*- coding: utf-8 -*-
"""
The tube impact benchmark of flexdem (`flexdem bench --scene tube_impact`) in YADE 2023.02a:
the same mesh, materials, time step and steps, to compare the speed (steps per second).

Run:  yade -j 1 -n -x bench/yade/tube_impact.py
      (environment: TUBE_WARMUP = untimed steps, default 25; TUBE_STEPS = timed steps,
       default 725: 750 steps of 0.2 ms = the first 0.15 s of examples/tube_impact_solid.toml)
Prints parseable lines:
      YADE_STEPS_PER_S <timed steps / wall seconds of O.run(TUBE_STEPS, True)>
      YADE_STEPS_PER_CPU_S <timed steps / CPU seconds of the process during that run>
      YADE_IMPACTOR_VZ <vertical velocity of the sphere at the end, m/s>
      (and YADE_IMPACTOR_VZ_AT <step> <vz> during the warm-up and at the end)

SCENE (examples/tube_impact_solid.toml, flexdem's paper_tube(); paper section 7)
  Tube along x from the origin, radius 0.1 m, length 0.8 m: 21 rings (j = 0..20) of 16 nodes
  (i = 0..15); node (i, j) = GridNode number 16 j + i at
      (0.8 j / 20, 0.1 sin(2 pi i / 16), -0.1 cos(2 pi i / 16)),
  the order and positions of flexdem's tube() builder (its basis for the axis x is
  e1 = -z, e2 = +y; checked by crates/bench's tests). Each quad (i, j) is split into the
  PFacets [(i,j), (i+1,j), (i,j+1)] and [(i+1,j), (i+1,j+1), (i,j+1)] (i + 1 modulo 16), in
  this order; the GridConnections are the PFacets' unique edges in order of first appearance.
  336 nodes, 976 connections, 640 PFacets, radius 2 mm.  Both end rings (j = 0 and j = 20)
  clamped: gridNode(fixed=True), blockedDOFs 'xyzXYZ'.
  Impactor: a sphere of radius 0.1 m at (0.4, 0, 0.207) (5 mm above the tube top, which is
  node (8, 10)), velocity (0, 0, -2) m/s.
MATERIALS (tube E = 1 MPa, sphere E = 100 MPa, nu = 0.3, 1000 kg/m3, friction 30 deg)
  nodes (links): CohFrictMat(young=1e6, poisson=0.3, density=1000, frictionAngle=30 deg,
                 normalCohesion=shearCohesion=1e100 (unbreakable), momentRotationLaw=True)
  connections and PFacets (external contacts): FrictMat(young=1e6, poisson=0.3, density=1000, 30 deg)
  sphere: FrictMat(young=1e8, poisson=0.3, density=1000, 30 deg)
  Mass: YADE's lumping (each connection puts pi r^2 L rho / 2 on each node), the same as
  flexdem's default "connections" lumping.
ENGINES: the standard PFacet list (YADE's examples/pfacet/*.py): sphere-PFacet,
  PFacet-PFacet and its sub-contacts (node-PFacet, connection-connection), links.
  No gravity, no damping.  dt fixed at 2e-4 s (flexdem's TUBE_IMPACT_DT).
Differences that remain: flexdem's links use the beam kinematics (model.md section 3; YADE's
ratcheting-avoidance factor 2r/L is not applied), and the contact laws differ in the details
listed in shared/reference/yade-grid-pfacet.md; the speed comparison does not depend on them.
"""
from yade import *
from yade.gridpfacet import gridNode, gridConnection, pfacet
import math, os, time

N_AROUND, N_ALONG = 16, 20
RADIUS, LENGTH, R_NODE = 0.1, 0.8, 0.002
E_TUBE, E_SPHERE, NU, RHO, PHI = 1e6, 100e6, 0.3, 1000.0, math.radians(30)
R_SPHERE, CENTER, VELOCITY = 0.1, (0.4, 0.0, 0.207), (0.0, 0.0, -2.0)
DT = 2e-4
WARMUP = int(os.environ.get('TUBE_WARMUP', '25'))
STEPS = int(os.environ.get('TUBE_STEPS', '725'))

O.engines = [
        ForceResetter(),
        InsertionSortCollider([Bo1_Sphere_Aabb(), Bo1_GridConnection_Aabb(), Bo1_PFacet_Aabb()]),
        InteractionLoop(
                [
                        Ig2_GridNode_GridNode_GridNodeGeom6D(),
                        Ig2_Sphere_PFacet_ScGridCoGeom(),
                        Ig2_GridConnection_GridConnection_GridCoGridCoGeom(),
                        Ig2_GridConnection_PFacet_ScGeom(),
                        Ig2_PFacet_PFacet_ScGeom(),
                ],
                [Ip2_CohFrictMat_CohFrictMat_CohFrictPhys(setCohesionNow=True, setCohesionOnNewContacts=False),
                 Ip2_FrictMat_FrictMat_FrictPhys()],
                [
                        Law2_ScGeom6D_CohFrictPhys_CohesionMoment(),
                        Law2_ScGridCoGeom_FrictPhys_CundallStrack(),
                        Law2_GridCoGridCoGeom_FrictPhys_CundallStrack(),
                ],
        ),
        NewtonIntegrator(gravity=(0, 0, 0), damping=0.0),
]
O.materials.append(
        CohFrictMat(
                young=E_TUBE, poisson=NU, density=RHO, frictionAngle=PHI, normalCohesion=1e100, shearCohesion=1e100,
                momentRotationLaw=True, label='nodeMat'
        )
)
O.materials.append(FrictMat(young=E_TUBE, poisson=NU, density=RHO, frictionAngle=PHI, label='tubeMat'))
O.materials.append(FrictMat(young=E_SPHERE, poisson=NU, density=RHO, frictionAngle=PHI, label='sphereMat'))


def node_position(i, j):
	theta = 2.0 * math.pi * i / N_AROUND
	return Vector3(LENGTH * j / N_ALONG, RADIUS * math.sin(theta), -RADIUS * math.cos(theta))


nodes = []
for j in range(N_ALONG + 1):
	for i in range(N_AROUND):
		fixed = j == 0 or j == N_ALONG
		nodes.append(O.bodies.append(gridNode(node_position(i, j), R_NODE, wire=False, fixed=fixed, material='nodeMat')))


def node(i, j):
	return nodes[(i % N_AROUND) + j * N_AROUND]


faces = []
for j in range(N_ALONG):
	for i in range(N_AROUND):
		faces.append((node(i, j), node(i + 1, j), node(i, j + 1)))
		faces.append((node(i + 1, j), node(i + 1, j + 1), node(i, j + 1)))
edges = {}
for f in faces:
	for k in range(3):
		a, b = f[k], f[(k + 1) % 3]
		key = (min(a, b), max(a, b))
		if key not in edges:
			edges[key] = O.bodies.append(gridConnection(a, b, R_NODE, material='tubeMat'))
pfacets = [O.bodies.append(pfacet(a, b, c, wire=False, color=Vector3(0.6, 0.6, 0.6), material='tubeMat')) for (a, b, c) in faces]
impactor = O.bodies.append(sphere(CENTER, R_SPHERE, material='sphereMat'))
O.bodies[impactor].state.vel = Vector3(*VELOCITY)
O.dt = DT
print('YADE_COUNTS nodes %d connections %d pfacets %d mass_tube %.9g mass_sphere %.9g' %
      (len(nodes), len(edges), len(pfacets), sum(O.bodies[n].state.mass for n in nodes), O.bodies[impactor].state.mass))

for k in range(WARMUP):
	O.run(1, True)
	if (k + 1) % 5 == 0:
		print('YADE_IMPACTOR_VZ_AT %d %.9g' % (O.iter, O.bodies[impactor].state.vel[2]))
t0, c0 = time.time(), time.process_time()
O.run(STEPS, True)
wall, cpu = time.time() - t0, time.process_time() - c0
vz = O.bodies[impactor].state.vel[2]
print('YADE_IMPACTOR_VZ_AT %d %.9g' % (O.iter, vz))
print('YADE_IMPACTOR_Z %.9g' % O.bodies[impactor].state.pos[2])
print('YADE_INTERACTIONS real %d' % sum(1 for i in O.interactions if i.isReal))
print('YADE_WALL_S %.6f' % wall)
print('YADE_CPU_S %.6f' % cpu)
print('YADE_STEPS_PER_S %.6f' % (STEPS / wall))
print('YADE_STEPS_PER_CPU_S %.6f' % (STEPS / cpu))
print('YADE_IMPACTOR_VZ %.9g' % vz)
