# -*- coding: utf-8 -*-
"""
Scenario: SPHERE DROPPED ON A NET PINNED AT ITS 4 CORNERS (YADE 2023.02a reference).
Exercises sphere-cylinder contacts on several connections at once, the duplicate-contact logic at
shared nodes (the sphere lands exactly above the centre node, shared by 4 connections), and link
bending/stretching of a whole structure under gravity.

Run:   yade -j 1 -n -x sphere_on_net.py        (run from this directory: outputs go to the
                                                 current directory, or to $YADE_REF_OUT if set)

GEOMETRY (gravity along -z)
  Square net of NC x NC = 6 x 6 cells, spacing S = 0.1 m, in the plane z = 0, x, y in [0, 0.6]:
  7 x 7 = 49 GridNodes, node (i, j) (i along x, j along y, 0..6) at (i S, j S, 0) with body id 7 j + i.
  84 GridConnections, radius r_c = 0.005 m (= node radius), created in this order (ids 49..132):
     first all x-direction ones, for j = 0..6, i = 0..5: nodes (i, j)-(i+1, j),
     then all y-direction ones, for i = 0..6, j = 0..5: nodes (i, j)-(i, j+1).
  Sphere (id 133), radius r_s = 0.1 m, centre (0.3, 0.3, z0) with z0 = r_s + r_c = 0.105: exactly above
  the centre node (3, 3) = id 24, touching it (overlap 0), at rest.  The net starts flat and unstressed.
MATERIALS
  nodes (internal, links): CohFrictMat(young=1e8, poisson=0.3, density=1000, frictionAngle=30 deg,
        normalCohesion=1e100, shearCohesion=1e100, momentRotationLaw=True)
  connections (external):  FrictMat(young=1e8, poisson=0.3, density=1000, frictionAngle=30 deg)
  sphere:                  FrictMat(young=1e8, poisson=0.3, density=rho_s, frictionAngle=30 deg)
        rho_s = 1 / ((4/3) pi r_s^3) = 238.732 kg/m3: sphere mass 1 kg, weight W = 10 N (g = 10).
  Link stiffnesses (gridConnection, L = 0.1, r = 0.005): A = pi r^2 = 7.853982e-5, I = pi r^4/4 = 4.908739e-10,
     kn = EA/L = 78539.8 N/m, ks = 12EI/L^3 = 589.049 N/m, kr = EI/L = 0.490874, ktw = 2IG/L = 0.377595.
  Node masses: pi r^2 L rho / 2 = 3.926991e-3 kg per attached connection (corner 2, edge 3, interior 4
     connections); inertia 0.4 (pi r^2 L/2) r^2 rho per attached connection.  Net mass 84 pi r^2 L rho
     = 0.659734 kg, net weight 6.59734 N.
  Sphere-connection contact (Ip2_FrictMat_FrictMat_FrictPhys, R_a = r_s, R_b = r_c):
     kn = 2 E r_s E r_c / (E r_s + E r_c) = 952381 N/m, ks = 0.3 kn, tan(30 deg).
BOUNDARY CONDITIONS
  the 4 corner nodes (ids 0, 6, 42, 48) pinned: blockedDOFs = 'xyz' (rotations free).  All other nodes
  and the sphere free.
ENGINES (in this order)
  ForceResetter()
  InsertionSortCollider([Bo1_Sphere_Aabb(), Bo1_GridConnection_Aabb()])      # defaults (verletDist=-0.5)
  InteractionLoop([Ig2_GridNode_GridNode_GridNodeGeom6D(), Ig2_Sphere_GridConnection_ScGridCoGeom(),
                   Ig2_GridConnection_GridConnection_GridCoGridCoGeom()],
                  [Ip2_CohFrictMat_CohFrictMat_CohFrictPhys(setCohesionNow=True, setCohesionOnNewContacts=False),
                   Ip2_FrictMat_FrictMat_FrictPhys()],
                  [Law2_ScGeom6D_CohFrictPhys_CohesionMoment(), Law2_ScGridCoGeom_FrictPhys_CundallStrack(),
                   Law2_GridCoGridCoGeom_FrictPhys_CundallStrack()])
  NewtonIntegrator(gravity=(0,0,-10), damping=0.3)    # Cundall local damping (nodes and sphere)
  Why Ig2_GridConnection_GridConnection_GridCoGridCoGeom is in the list even though no cylinder-cylinder
  contact is wanted: a GridConnection IS-A Sphere, so without it the collider's connection-connection
  pairs are dispatched to Ig2_Sphere_GridConnection_ScGridCoGeom with the first connection treated as a
  sphere at its body position (= its node1).  Where that point is the other connection's end node the
  distance is 0 and the normal NaN, and the NaN forces blow up the nodes (seen in the net: every free
  node NaN after step 1).  The GridCo-GridCo functor rejects pairs that share a node.
  Net self-contact (non-adjacent connections) is thus possible; the history counts it (n_selfcontacts).
TIME STEP
  dt = 4e-5 s (fixed; just below PWaveTimeStep = 4.33e-5, which is limited by the connection bodies;
  the stiffest real oscillator, sphere contact on an interior node, has 2 sqrt(m/kn) = 2.6e-4 s).
STEPS
  NSTEP = 400000 steps (16 s).  History output every 1000 steps.  Then NTIMING = 50000 more steps in a
  single O.run call are timed for the wall time per step.
ANALYTICAL EXPECTATIONS (static equilibrium; no closed form for the shape)
  sum of the contact forces on the sphere = (0, 0, W) = 10 N up;  sphere stays at x = y = 0.3 (symmetry);
  sum of the corner-node reactions (O.forces.f of the 4 pinned corners, i.e. the link forces on them)
  = (0, 0, W + weight of the free nodes) = 10 + 6.59734 - 4 x 0.0785398 = 16.28319 N down on the corners
  (each 4.0708 N by symmetry; the pinned corners' own weight is not applied: YADE applies no gravity on
  blocked DOFs).
  One active contact per touching place: at the centre node the 4 connections meet; exactly one of them
  carries the contact, the others are rejected or inert (isDuplicate = 1).
OUTPUTS
  sphere_on_net_history.csv : step,time,sphere_z,sphere_vz,centre_node_z,centre_node_disp_z,n_contacts,
         n_active,n_duplicate,sum_contact_fz (z force of all contacts on the sphere),max_node_speed,
         n_selfcontacts (real GridConnection-GridConnection interactions)
  sphere_on_net_final_nodes.csv : node,i,j,x0,y0,x,y,z (final node positions, after NSTEP steps)
  sphere_on_net_final_contacts.csv : id2,node1,node2,relPos,isDuplicate,trueInt,overlap,fn,fs,
         cx,cy,cz (contact point) for every real sphere interaction at the end
  sphere_on_net_summary.json
"""
from yade import *
from yade.gridpfacet import gridNode, gridConnection
import math, json, os, time

OUT = os.environ.get('YADE_REF_OUT', os.getcwd())
os.makedirs(OUT, exist_ok=True)

NC = 6
S = 0.1
RC = 0.005
RS = 0.1
E = 1e8
NU = 0.3
RHO = 1000.0
PHI = math.radians(30)
RHO_S = 1.0 / (4.0 / 3.0 * math.pi * RS**3)
G = 10.0
DAMP = 0.3
DT = 4e-5
NSTEP = 400000
OUTPERIOD = 1000
NTIMING = 50000

O.reset()
O.engines = [
        ForceResetter(),
        InsertionSortCollider([Bo1_Sphere_Aabb(), Bo1_GridConnection_Aabb()]),
        InteractionLoop(
                [Ig2_GridNode_GridNode_GridNodeGeom6D(), Ig2_Sphere_GridConnection_ScGridCoGeom(),
                   Ig2_GridConnection_GridConnection_GridCoGridCoGeom()],
                [Ip2_CohFrictMat_CohFrictMat_CohFrictPhys(setCohesionNow=True, setCohesionOnNewContacts=False),
                 Ip2_FrictMat_FrictMat_FrictPhys()],
                [Law2_ScGeom6D_CohFrictPhys_CohesionMoment(), Law2_ScGridCoGeom_FrictPhys_CundallStrack(),
                   Law2_GridCoGridCoGeom_FrictPhys_CundallStrack()],
        ),
        NewtonIntegrator(gravity=(0, 0, -G), damping=DAMP, label='newton'),
]
O.materials.append(
        CohFrictMat(
                young=E, poisson=NU, density=RHO, frictionAngle=PHI, normalCohesion=1e100, shearCohesion=1e100, momentRotationLaw=True,
                label='nodeMat'
        )
)
O.materials.append(FrictMat(young=E, poisson=NU, density=RHO, frictionAngle=PHI, label='connMat'))
O.materials.append(FrictMat(young=E, poisson=NU, density=RHO_S, frictionAngle=PHI, label='sphereMat'))

N = NC + 1
nid = {}
for j in range(N):
	for i in range(N):
		nid[(i, j)] = O.bodies.append(gridNode(Vector3(i * S, j * S, 0), RC, wire=False, fixed=False, material='nodeMat'))
conns = []
for j in range(N):
	for i in range(NC):
		conns.append(O.bodies.append(gridConnection(nid[(i, j)], nid[(i + 1, j)], RC, material='connMat')))
for i in range(N):
	for j in range(NC):
		conns.append(O.bodies.append(gridConnection(nid[(i, j)], nid[(i, j + 1)], RC, material='connMat')))
corners = [nid[(0, 0)], nid[(NC, 0)], nid[(0, NC)], nid[(NC, NC)]]
for c in corners:
	O.bodies[c].state.blockedDOFs = 'xyz'
centre = nid[(NC // 2, NC // 2)]
sph = O.bodies.append(sphere(Vector3(NC // 2 * S, NC // 2 * S, RS + RC), RS, material='sphereMat'))
nodes = [nid[(i, j)] for j in range(N) for i in range(N)]
pw = PWaveTimeStep()
O.dt = DT
W = O.bodies[sph].state.mass * G
netW = sum(O.bodies[n].state.mass for n in nodes) * G
netW_free = sum(O.bodies[n].state.mass for n in nodes if n not in corners) * G


def contacts():
	out = []
	for i in O.interactions.withBody(sph):
		if not i.isReal: continue
		g, p = i.geom, i.phys
		other = i.id2 if i.id1 == sph else i.id1
		out.append({
		        'id2': other,
		        'node1': g.id3,
		        'node2': g.id4,
		        'relPos': g.relPos,
		        'isDuplicate': g.isDuplicate,
		        'trueInt': g.trueInt,
		        'overlap': g.penetrationDepth,
		        'fn': p.normalForce.norm(),
		        'fs': p.shearForce.norm(),
		        'normalForce': list(p.normalForce),
		        'shearForce': list(p.shearForce),
		        'contactPoint': list(g.contactPoint),
		})
	return out


def active(c):
	return c['isDuplicate'] == 0 or c['trueInt'] == c['id2']


def nself():
	return len([i for i in O.interactions if i.isReal and isinstance(i.geom, GridCoGridCoGeom)])


def maxvel():
	return max([O.bodies[n].state.vel.norm() for n in nodes] + [O.bodies[sph].state.vel.norm()])


rows = []
t0 = time.time()
for k in range(NSTEP // OUTPERIOD + 1):
	if k > 0: O.run(OUTPERIOD, True)
	cs = contacts()
	act = [c for c in cs if active(c)]
	rows.append((
	        O.iter, O.time, O.bodies[sph].state.pos[2], O.bodies[sph].state.vel[2], O.bodies[centre].state.pos[2], O.bodies[centre].state.pos[2], len(cs),
	        len(act), len([c for c in cs if c['isDuplicate'] == 1]), O.forces.f(sph, sync=True)[2], maxvel(), nself()
	))
wall_hist = time.time() - t0
with open(os.path.join(OUT, 'sphere_on_net_history.csv'), 'w') as f:
	f.write('step,time,sphere_z,sphere_vz,centre_node_z,centre_node_disp_z,n_contacts,n_active,n_duplicate,sum_contact_fz,max_node_speed,n_selfcontacts\n')
	for r in rows:
		f.write('%d,%.10g,%.12e,%.6e,%.12e,%.12e,%d,%d,%d,%.10e,%.6e,%d\n' % r)
with open(os.path.join(OUT, 'sphere_on_net_final_nodes.csv'), 'w') as f:
	f.write('node,i,j,x0,y0,x,y,z\n')
	for j in range(N):
		for i in range(N):
			p = O.bodies[nid[(i, j)]].state.pos
			f.write('%d,%d,%d,%.6f,%.6f,%.12e,%.12e,%.12e\n' % (nid[(i, j)], i, j, i * S, j * S, p[0], p[1], p[2]))
cs = contacts()
with open(os.path.join(OUT, 'sphere_on_net_final_contacts.csv'), 'w') as f:
	f.write('id2,node1,node2,relPos,isDuplicate,trueInt,overlap,fn,fs,cx,cy,cz\n')
	for c in sorted(cs, key=lambda c: c['id2']):
		f.write('%d,%d,%d,%.12e,%d,%d,%.12e,%.12e,%.12e,%.12e,%.12e,%.12e\n' % ((c['id2'], c['node1'], c['node2'], c['relPos'], c['isDuplicate'],
		                                                                          c['trueInt'], c['overlap'], c['fn'], c['fs']) + tuple(c['contactPoint'])))
act = [c for c in cs if active(c)]
sp = O.bodies[sph].state
cf = {str(c): list(O.forces.f(c, sync=True)) for c in corners}
final = {
        'steps': O.iter,
        'time': O.time,
        'sphere_pos_final': list(sp.pos),
        'sphere_vel_final': list(sp.vel),
        'sphere_drop_final': RS + RC - sp.pos[2],
        'centre_node_id': centre,
        'centre_node_pos_final': list(O.bodies[centre].state.pos),
        'centre_node_disp_z_final': O.bodies[centre].state.pos[2],
        'n_contacts_final': len(cs),
        'n_active_final': len(act),
        'n_duplicate_final': len([c for c in cs if c['isDuplicate'] == 1]),
        'active_contacts_final': sorted(act, key=lambda c: c['id2']),
        'sum_contact_force_on_sphere': list(O.forces.f(sph, sync=True)),
        'sum_contact_fz_expected': W,
        'corner_force_final': cf,
        'sum_corner_force_final': list(sum((O.forces.f(c, sync=True) for c in corners), Vector3.Zero)),
        'sum_corner_fz_expected': -(W + netW_free),
        'max_speed_final': maxvel(),
        'sphere_z_change_last_50k_steps': sp.pos[2] - [r for r in rows if r[0] == NSTEP - 50000][0][2],
        'max_n_contacts_history': max(r[6] for r in rows),
        'max_n_active_history': max(r[7] for r in rows),
        'max_n_duplicate_history': max(r[8] for r in rows),
        'min_sphere_z_history': min(r[2] for r in rows),
        'max_n_selfcontacts_history': max(r[11] for r in rows),
}
t1 = time.time()
O.run(NTIMING, True)
wall = time.time() - t1
summary = {
        'scenario': 'sphere_on_net',
        'yade_version': '2023.02a',
        'threads': O.numThreads,
        'n_nodes': len(nodes),
        'n_connections': len(conns),
        'corner_ids': corners,
        'sphere_id': sph,
        'sphere_mass': O.bodies[sph].state.mass,
        'weight': W,
        'net_weight': netW,
        'net_weight_free_nodes': netW_free,
        'node_mass': {
                'corner': O.bodies[corners[0]].state.mass,
                'edge': O.bodies[nid[(1, 0)]].state.mass,
                'interior': O.bodies[centre].state.mass
        },
        'node_inertia': {
                'corner': O.bodies[corners[0]].state.inertia[0],
                'edge': O.bodies[nid[(1, 0)]].state.inertia[0],
                'interior': O.bodies[centre].state.inertia[0]
        },
        'PWaveTimeStep': pw,
        'dt': O.dt,
        'final': final,
        'wall_s_history_loop': wall_hist,
        'timing_steps': NTIMING,
        'wall_s': wall,
        'wall_s_per_step': wall / NTIMING,
}
ph = O.interactions[nid[(0, 0)], nid[(1, 0)]].phys
summary['bond_stiffness'] = {'kn': ph.kn, 'ks': ph.ks, 'kr': ph.kr, 'ktw': ph.ktw}
print(json.dumps(summary, indent=1))
with open(os.path.join(OUT, 'sphere_on_net_summary.json'), 'w') as f:
	json.dump(summary, f, indent=1)
