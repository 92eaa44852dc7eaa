# -*- coding: utf-8 -*-
"""
Scenario: SPHERE RESTING ON A FIXED PFacet (YADE 2023.02a reference).
Validation case 8 (node forces = barycentric weights of the contact point times the contact force).

Run:   yade -j 1 -n -x sphere_on_pfacet.py     (run from this directory: outputs go to the
                                                 current directory, or to $YADE_REF_OUT if set)
Cases: 'p0101' (sphere above barycentric/planar point (x,y) = (0.1, 0.1)) and 'p0201' (above
       (0.2, 0.1), asymmetric, so that every node has a distinct weight), run one after the other
       (O.reset() in between; identical PFacet, materials, engines, dt, sphere).

GEOMETRY (gravity along -z; all nodes fixed, so the PFacet does not move)
  3 GridNodes: id 0 at (0,0,0), id 1 at (1,0,0), id 2 at (0,1,0); radius r_f = 0.01 m.
  3 GridConnections (radius 0.01): id 3 = 0-1, id 4 = 1-2, id 5 = 2-0.
  1 PFacet (id 6) on nodes (0, 1, 2) made with yade.gridpfacet.pfacet(0, 1, 2): radius = node radius
  0.01, conn1 = 3, conn2 = 4, conn3 = 5; pfacet() makes the nodes and the 3 connections unbounded, so
  the sphere only meets the PFacet body.
  Sphere (id 7), radius r_s = 0.05 m, centre (x, y, z0) with z0 = r_s + r_f = 0.06 (touching, overlap
  0, at rest).  The correct barycentric weights of P = (x, y, 0) are
     w_node0 = 1 - x - y,  w_node1 = x,  w_node2 = y
     'p0101': (0.8, 0.1, 0.1)      'p0201': (0.7, 0.2, 0.1)
  YADE's projection returns (p1, p2, p3) = (x, y, 1 - x - y) with P = p3 V0 + p1 V1 + p2 V2 (reference
  notes 6.3).  The old (pre-MR-628) code gives node0 <- p1, node1 <- p2, node2 <- p3, i.e. 80 % on
  node 2 for 'p0101'; the fixed code gives node0 <- p3, node1 <- p1, node2 <- p2.
MATERIALS
  nodes (internal, links): CohFrictMat(young=1e8, poisson=0.3, density=1000, frictionAngle=30 deg,
        normalCohesion=1e100, shearCohesion=1e100, momentRotationLaw=True)
  connections and PFacet (external): FrictMat(young=1e8, poisson=0.3, density=1000, frictionAngle=30 deg)
  sphere: FrictMat(young=1e8, poisson=0.3, density=rho_s, frictionAngle=30 deg)
        rho_s = 1 / ((4/3) pi r_s^3) = 1909.859 kg/m3, so the sphere mass is m = 1 kg and, with
        g = 10 m/s2, its weight is W = 10 N.
  Sphere-PFacet contact (Ip2_FrictMat_FrictMat_FrictPhys, R_a = r_s, R_b = PFacet radius r_f):
        kn = 2 E r_s E r_f / (E r_s + E r_f) = 1.666667e6 N/m, ks = 0.3 kn = 5e5 N/m, tan(30 deg).
BOUNDARY CONDITIONS
  all GridNodes fixed (gridNode(fixed=True): blockedDOFs = 'xyzXYZ', zero velocity, no gravity).
  The sphere is free (6 DOF).
ENGINES (in this order)
  ForceResetter()
  InsertionSortCollider([Bo1_Sphere_Aabb(), Bo1_GridConnection_Aabb(), Bo1_PFacet_Aabb()])   # defaults
  InteractionLoop([Ig2_GridNode_GridNode_GridNodeGeom6D(), Ig2_Sphere_PFacet_ScGridCoGeom()],
                  [Ip2_CohFrictMat_CohFrictMat_CohFrictPhys(setCohesionNow=True, setCohesionOnNewContacts=False),
                   Ip2_FrictMat_FrictMat_FrictPhys()],
                  [Law2_ScGeom6D_CohFrictPhys_CohesionMoment(), Law2_ScGridCoGeom_FrictPhys_CundallStrack()])
  NewtonIntegrator(gravity=(0,0,-10), damping=0.3)    # Cundall local damping, also on the sphere
TIME STEP
  dt = 1e-4 s (fixed; PWaveTimeStep is written to the JSON for information).  Contact period
  2 pi sqrt(m/kn) = 4.87e-3 s, i.e. about 49 steps per period.
STEPS
  4000 steps (0.4 s) per case. History output every 20 steps.  Then (outside the history)
  NTIMING = 20000 more steps in a single O.run call are timed for the wall time per step
  (O.run(n, True) in small chunks costs ~40 ms of polling per call, so the history loop is not a
  fair timing).
ANALYTICAL EXPECTATIONS (static equilibrium)
  contact normal force = W = 10 N;  overlap delta = W / kn = 6.0e-6 m;
  sphere rest position (x, y, r_s + r_f - W/kn) = (x, y, 0.059994);  shear force 0.
  node forces (O.forces.f of the blocked nodes; nothing goes to the PFacet or connection bodies):
     f_z(node k) = -w_k W:  'p0101': (-8, -1, -1) N;  'p0201': (-7, -2, -1) N.
OUTPUTS
  sphere_on_pfacet_<case>_history.csv : step,time,sphere_z,sphere_vz,overlap,n_contacts,n_active,
          contact_fn,contact_fs,node_fz_0,node_fz_1,node_fz_2,sphere_fz (contact force on the sphere)
  sphere_on_pfacet_summary.json : per case: setup numbers, final contacts (after NSTEP steps: id2,
          isDuplicate, id3/id4/id5, weight, normal force, shear force, overlap), node forces and
          torques, sphere position, analytic values, wall time per step (from the NTIMING run).
"""
from yade import *
from yade.gridpfacet import gridNode, gridConnection, pfacet
import math, json, os, time

OUT = os.environ.get('YADE_REF_OUT', os.getcwd())
os.makedirs(OUT, exist_ok=True)

RC = 0.01
RS = 0.05
E = 1e8
NU = 0.3
RHO = 1000.0
PHI = math.radians(30)
RHO_S = 1.0 / (4.0 / 3.0 * math.pi * RS**3)
G = 10.0
DAMP = 0.3
DT = 1e-4
NSTEP = 4000
OUTPERIOD = 20
NTIMING = 20000
CASES = {'p0101': (0.1, 0.1), 'p0201': (0.2, 0.1)}


def build(case):
	O.reset()
	O.engines = [
	        ForceResetter(),
	        InsertionSortCollider([Bo1_Sphere_Aabb(), Bo1_GridConnection_Aabb(), Bo1_PFacet_Aabb()]),
	        InteractionLoop(
	                [Ig2_GridNode_GridNode_GridNodeGeom6D(), Ig2_Sphere_PFacet_ScGridCoGeom()],
	                [Ip2_CohFrictMat_CohFrictMat_CohFrictPhys(setCohesionNow=True, setCohesionOnNewContacts=False),
	                 Ip2_FrictMat_FrictMat_FrictPhys()],
	                [Law2_ScGeom6D_CohFrictPhys_CohesionMoment(), Law2_ScGridCoGeom_FrictPhys_CundallStrack()],
	        ),
	        NewtonIntegrator(gravity=(0, 0, -G), damping=DAMP, label='newton'),
	]
	O.materials.append(
	        CohFrictMat(
	                young=E, poisson=NU, density=RHO, frictionAngle=PHI, normalCohesion=1e100, shearCohesion=1e100,
	                momentRotationLaw=True, label='nodeMat'
	        )
	)
	O.materials.append(FrictMat(young=E, poisson=NU, density=RHO, frictionAngle=PHI, label='connMat'))
	O.materials.append(FrictMat(young=E, poisson=NU, density=RHO_S, frictionAngle=PHI, label='sphereMat'))
	nodes = [O.bodies.append(gridNode(Vector3(*p), RC, wire=False, fixed=True, material='nodeMat')) for p in [(0, 0, 0), (1, 0, 0), (0, 1, 0)]]
	conns = [O.bodies.append(gridConnection(nodes[i], nodes[j], RC, material='connMat')) for (i, j) in [(0, 1), (1, 2), (2, 0)]]
	pf = O.bodies.append(pfacet(nodes[0], nodes[1], nodes[2], wire=False, color=Vector3(0.5, 0.5, 0.5), material='connMat'))
	x, y = CASES[case]
	sph = O.bodies.append(sphere(Vector3(x, y, RS + RC), RS, material='sphereMat'))
	pw = PWaveTimeStep()
	O.dt = DT
	return nodes, conns, pf, sph, pw


def contacts(sph):
	out = []
	for i in O.interactions.withBody(sph):
		if not i.isReal: continue
		g, p = i.geom, i.phys
		out.append({
		        'id1': i.id1,
		        'id2': i.id2,
		        'isDuplicate': g.isDuplicate,
		        'trueInt': g.trueInt,
		        'relPos': g.relPos,
		        'id3': g.id3,
		        'id4': g.id4,
		        'id5': g.id5,
		        'weight': list(g.weight),
		        'contactPoint': list(g.contactPoint),
		        'overlap': g.penetrationDepth,
		        'normal': list(g.normal),
		        'normalForce': list(p.normalForce),
		        'shearForce': list(p.shearForce),
		        'kn': p.kn,
		        'ks': p.ks,
		})
	return out


summary = {'scenario': 'sphere_on_pfacet', 'yade_version': '2023.02a', 'threads': O.numThreads, 'cases': {}}
for case in ['p0101', 'p0201']:
	nodes, conns, pf, sph, pw = build(case)
	rows = []
	t0 = time.time()
	for k in range(NSTEP // OUTPERIOD + 1):
		if k > 0: O.run(OUTPERIOD, True)
		s = O.bodies[sph].state
		cs = contacts(sph)
		act = [c for c in cs if c['isDuplicate'] == 0 or c['trueInt'] == c['id2']]
		fn = sum(Vector3(*c['normalForce']).norm() for c in act)
		fs = sum(Vector3(*c['shearForce']).norm() for c in act)
		rows.append([O.iter, O.time, s.pos[2], s.vel[2], RS + RC - s.pos[2], len(cs), len(act), fn, fs] +
		            [O.forces.f(n, sync=True)[2] for n in nodes] + [O.forces.f(sph, sync=True)[2]])
	wall = time.time() - t0
	state_final = (list(O.bodies[sph].state.pos), list(O.bodies[sph].state.vel), contacts(sph),
	               {str(n): list(O.forces.f(n, sync=True)) for n in nodes}, {str(n): list(O.forces.t(n, sync=True)) for n in nodes},
	               list(O.forces.f(sph, sync=True)), O.iter, O.time)
	with open(os.path.join(OUT, 'sphere_on_pfacet_%s_history.csv' % case), 'w') as f:
		f.write('step,time,sphere_z,sphere_vz,overlap,n_contacts,n_active,contact_fn,contact_fs,' +
		        ','.join('node_fz_%d' % n for n in nodes) + ',sphere_fz\n')
		for r in rows:
			f.write('%d,%.10g,%.15e,%.6e,%.12e,%d,%d,%.12e,%.6e,' % tuple(r[:9]) + ','.join('%.12e' % v for v in r[9:]) + '\n')
	pos, vel, cs, nf, nt, sf, nit, ntime = state_final
	t1 = time.time()
	O.run(NTIMING, True)
	wall_timing = time.time() - t1
	kn = cs[0]['kn'] if cs else float('nan')
	W = O.bodies[sph].state.mass * G
	x, y = CASES[case]
	wts = [1 - x - y, x, y]
	expect_nodes = {str(n): -w * W for n, w in zip(nodes, wts)}
	expect_nodes_old_permuted = {str(n): -w * W for n, w in zip(nodes, [x, y, 1 - x - y])}
	share = {str(n): nf[str(n)][2] / -W for n in nodes}
	summary['cases'][case] = {
	        'node_ids': nodes,
	        'node_pos': [list(O.bodies[n].state.pos) for n in nodes],
	        'connection_ids': conns,
	        'pfacet_id': pf,
	        'barycentric_point_xy': [x, y],
	        'barycentric_weights_expected': wts,
	        'sphere_id': sph,
	        'sphere_mass': O.bodies[sph].state.mass,
	        'sphere_inertia': O.bodies[sph].state.inertia[0],
	        'node_mass': [O.bodies[n].state.mass for n in nodes],
	        'weight': W,
	        'PWaveTimeStep': pw,
	        'dt': O.dt,
	        'steps': nit,
	        'time': ntime,
	        'contacts_final': cs,
	        'n_contacts_final': len(cs),
	        'node_force_final': nf,
	        'node_torque_final': nt,
	        'node_fz_expected': expect_nodes,
	        'node_fz_expected_if_weights_permuted_(pre_MR628)': expect_nodes_old_permuted,
	        'node_force_share_of_weight': share,
	        'sum_node_fz': sum(v[2] for v in nf.values()),
	        'sphere_force_final': sf,
	        'sphere_pos_final': pos,
	        'sphere_vel_final': vel,
	        'sphere_z_expected': RS + RC - W / kn,
	        'overlap_final': RS + RC - pos[2],
	        'overlap_expected': W / kn,
	        'max_n_contacts_history': max(r[5] for r in rows),
	        'max_n_active_history': max(r[6] for r in rows),
	        'wall_s_history_loop': wall,
	        'timing_steps': NTIMING,
	        'wall_s': wall_timing,
	        'wall_s_per_step': wall_timing / NTIMING,
	        'sphere_pos_after_timing_run': list(O.bodies[sph].state.pos),
	}
	print(case, json.dumps(summary['cases'][case], indent=1))
with open(os.path.join(OUT, 'sphere_on_pfacet_summary.json'), 'w') as f:
	json.dump(summary, f, indent=1)
