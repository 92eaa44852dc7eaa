# -*- coding: utf-8 -*-
"""
Speed twin of YADE's tube impact, scenario 2 "solid" (shared/reference/yade/tube_impact/
tube_impact.py solid): the scene is built by the reference script's code, copied here
unchanged except that nothing is written and no PyRunner samples the run (output off).
flexdem's twin: bench/scenes/tube_impact_solid_yade.toml (bench/yade/twin.py tube).

Run:  yade -j 1 -n -x bench/yade/tube_impact.py        (bench/run_vs_yade.sh does)
      environment: WARMUP untimed steps (default 25: the sphere, 1 mm above the tube at 2 m/s,
      touches it after about 19 steps), STEPS timed steps (default 5800, to t = 0.15 s).
Prints parseable lines (one value each):
      YADE_DT          the time step: 0.5 * PWaveTimeStep(), as the reference script sets it
      YADE_WALL_S      wall seconds of O.run(STEPS, True) after O.run(WARMUP, True)
      YADE_CPU_S       CPU seconds of the process (all its threads) over the same run
      YADE_STEPS       STEPS
      YADE_CONTACTS    real interactions other than the links, at the end
      YADE_IMPACTOR_VZ the sphere's vertical velocity after WARMUP + STEPS steps (m/s)
      YADE_IMPACTOR_MASS, YADE_BODIES

SCENE (the reference's header has every detail): tube along x, 21 rings x 16 nodes,
node (i, j) = body 16 i + j at (0.04 i, 0.1 cos th, 0.1 sin th), th = 2 pi (j + 0.5)/16; quads
split along (i,j)-(i+1,j+1) for i < 10, along (i+1,j)-(i,j+1) for i >= 10; 336 GridNodes,
976 GridConnections, 640 PFacets, r = 2 mm; CohFrictMat nodes / FrictMat connections and
PFacets, E = 1 MPa, nu = 0.3, 1000 kg/m3, 30 deg; end rings blockedDOFs 'xyzXYZ'. Sphere r = 0.1,
E = 100 MPa, density such that its mass is the hollow impactor's (0.1121157 kg), 1 mm above
the tube, (0, 0, -2) m/s. No gravity, no damping. PFacet-PFacet (tube self-contact) enabled.
"""
from yade import *
from yade.gridpfacet import gridNode, gridConnection, pfacet
import math, os, time

WARMUP = int(os.environ.get('WARMUP', '25'))
STEPS = int(os.environ.get('STEPS', '5800'))

# ---------------------------------------------------------------- parameters (reference)
RT, LT, NI, NJ, THOFF = 0.1, 0.8, 21, 16, 0.5
RN = 0.002
E_TUBE, E_IMP, NU, RHO, PHI = 1e6, 1e8, 0.3, 1000.0, math.radians(30)
RS = 0.1
GAP = 0.001
V0 = 2.0
SAFETY = 0.5


def octasphere(R):
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
				V = [Vector3(sx, 0, 0), Vector3(0, sy, 0), Vector3(0, 0, sz)]
				if sx * sy * sz < 0: V = [V[0], V[2], V[1]]
				g = {}
				for a in range(NS + 1):
					for b in range(NS + 1 - a):
						p = (V[0] * a + V[1] * b + V[2] * (NS - a - b)) / float(NS)
						g[(a, b)] = vid(p / p.norm() * R)
				for a in range(NS):
					for b in range(NS - a):
						tris.append((g[(a, b)], g[(a + 1, b)], g[(a, b + 1)]))
						if a + b < NS - 1: tris.append((g[(a + 1, b)], g[(a + 1, b + 1)], g[(a, b + 1)]))
	return verts, tris


def unique_edges(tris):
	edges, seen = [], set()
	for t in tris:
		for a, b in ((t[0], t[1]), (t[1], t[2]), (t[2], t[0])):
			k = (min(a, b), max(a, b))
			if k not in seen:
				seen.add(k)
				edges.append(k)
	return edges


OV, OT = octasphere(RS)
OE = unique_edges(OT)
M_HOLLOW = math.pi * RN**2 * RHO * sum((OV[a] - OV[b]).norm() for a, b in OE)
RHO_S = M_HOLLOW / (4. / 3. * math.pi * RS**3)

O.engines = [
        ForceResetter(),
        InsertionSortCollider([Bo1_Sphere_Aabb(), Bo1_GridConnection_Aabb(), Bo1_PFacet_Aabb()], label='collider'),
        InteractionLoop(
                [
                        Ig2_GridNode_GridNode_GridNodeGeom6D(),
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
        NewtonIntegrator(gravity=(0, 0, 0), damping=0.0, label='newton'),
]

O.materials.append(
        CohFrictMat(
                young=E_TUBE, poisson=NU, density=RHO, frictionAngle=PHI, normalCohesion=1e100, shearCohesion=1e100, momentRotationLaw=True,
                label='tubeNode'
        )
)
O.materials.append(FrictMat(young=E_TUBE, poisson=NU, density=RHO, frictionAngle=PHI, label='tubeExt'))
O.materials.append(FrictMat(young=E_IMP, poisson=NU, density=RHO_S, frictionAngle=PHI, label='sphereMat'))


def build_mesh(verts, tris, nodeMat, extMat, color, mask=1):
	nids = [O.bodies.append(gridNode(v, RN, wire=False, fixed=False, material=nodeMat, color=color)) for v in verts]
	edges = unique_edges(tris)
	cids = [O.bodies.append(gridConnection(nids[a], nids[b], RN, material=extMat, color=color, mask=mask)) for a, b in edges]
	pids = [O.bodies.append(pfacet(nids[t[0]], nids[t[1]], nids[t[2]], wire=False, material=extMat, color=color, mask=mask)) for t in tris]
	return nids, edges, cids, pids


tverts = []
for i in range(NI):
	for j in range(NJ):
		th = 2 * math.pi * (j + THOFF) / NJ
		tverts.append(Vector3(LT * i / (NI - 1), RT * math.cos(th), RT * math.sin(th)))
tid = lambda i, j: NJ * i + (j % NJ)
ttris = []
for i in range(NI - 1):
	for j in range(NJ):
		if i < (NI - 1) // 2:
			ttris += [(tid(i, j), tid(i + 1, j), tid(i + 1, j + 1)), (tid(i, j), tid(i + 1, j + 1), tid(i, j + 1))]
		else:
			ttris += [(tid(i, j), tid(i + 1, j), tid(i, j + 1)), (tid(i + 1, j), tid(i + 1, j + 1), tid(i, j + 1))]
tN, tE, tC, tP = build_mesh(tverts, ttris, 'tubeNode', 'tubeExt', Vector3(0.2, 0.4, 0.8))
for i in (0, NI - 1):
	for j in range(NJ):
		O.bodies[tN[tid(i, j)]].state.blockedDOFs = 'xyzXYZ'
ZTOP = max(v[2] for v in tverts)
Z0 = ZTOP + RN + RS + GAP
sid = O.bodies.append(sphere(Vector3(0.4, 0, Z0), RS, material='sphereMat', color=Vector3(0.8, 0.2, 0.2)))
O.bodies[sid].state.vel = Vector3(0, 0, -V0)

O.dt = SAFETY * PWaveTimeStep()

# ---------------------------------------------------------------- timing (output off)
if WARMUP > 0: O.run(WARMUP, True)  # O.run(0) would run for ever
w0, c0 = time.perf_counter(), time.process_time()
O.run(STEPS, True)
wall, cpu = time.perf_counter() - w0, time.process_time() - c0
contacts = sum(1 for I in O.interactions if not isinstance(I.geom, GridNodeGeom6D))
print('YADE_DT %r' % O.dt)
print('YADE_WALL_S %.6f' % wall)
print('YADE_CPU_S %.6f' % cpu)
print('YADE_STEPS %d' % STEPS)
print('YADE_CONTACTS %d' % contacts)
print('YADE_IMPACTOR_VZ %.9e' % O.bodies[sid].state.vel[2])
print('YADE_IMPACTOR_MASS %r' % O.bodies[sid].state.mass)
print('YADE_BODIES %d' % len(O.bodies))
