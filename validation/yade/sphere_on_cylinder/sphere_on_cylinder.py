# -*- coding: utf-8 -*-
"""
Scenario: SPHERE RESTING ON A HORIZONTAL GridConnection (YADE 2023.02a reference).
Validation cases 7 (sphere on a cylinder, node force split) and 9 (one contact at a shared node).

Run:   yade -j 1 -n -x sphere_on_cylinder.py   (run from this directory: outputs go to the
                                                 current directory, or to $YADE_REF_OUT if set)
Cases: 't025' and 'node', run one after the other (O.reset() in between; identical materials,
       engines, dt, sphere).

GEOMETRY (gravity along -z; all nodes fixed, so the structure does not move)
  't025': 2 GridNodes, id 0 at (0,0,0) and id 1 at (1,0,0), one GridConnection 0-1 (id 2), L = 1.
          Sphere (id 3) centre (0.25, 0, z0): above the axis parameter t = 0.25.
  'node': 3 GridNodes, id 0 at (0,0,0), id 1 at (0.5,0,0), id 2 at (1,0,0), GridConnections 0-1
          (id 3) and 1-2 (id 4). Sphere (id 5) centre (0.5, 0, z0): exactly above the shared
          node 1 (t = 1 on connection 3, t = 0 on connection 4).
  Node radius = connection radius r_c = 0.01 m.  Sphere radius r_s = 0.05 m.
  z0 = r_s + r_c = 0.06 (the sphere starts touching, overlap 0, at rest).
MATERIALS
  nodes (internal, links): CohFrictMat(young=1e8, poisson=0.3, density=1000, frictionAngle=30 deg,
        normalCohesion=1e100, shearCohesion=1e100, momentRotationLaw=True)
  connections (external):  FrictMat(young=1e8, poisson=0.3, density=1000, frictionAngle=30 deg)
  sphere:                  FrictMat(young=1e8, poisson=0.3, density=rho_s, frictionAngle=30 deg)
        rho_s = 1 / ((4/3) pi r_s^3) = 1909.859 kg/m3, so the sphere mass is m = 1 kg and, with
        g = 10 m/s2, its weight is W = 10 N.
  Sphere-connection contact (Ip2_FrictMat_FrictMat_FrictPhys, R_a = r_s, R_b = r_c; poisson acts as
  ks/kn):  kn = 2 E r_s E r_c / (E r_s + E r_c) = 1.666667e6 N/m, ks = 0.3 kn = 5e5 N/m, tan(30 deg).
BOUNDARY CONDITIONS
  all GridNodes fixed (gridNode(fixed=True): blockedDOFs = 'xyzXYZ', zero velocity, no gravity).
  The sphere is free (6 DOF).
ENGINES (in this order)
  ForceResetter()
  InsertionSortCollider([Bo1_Sphere_Aabb(), Bo1_GridConnection_Aabb()])     # defaults (verletDist=-0.5)
  InteractionLoop([Ig2_GridNode_GridNode_GridNodeGeom6D(), Ig2_Sphere_GridConnection_ScGridCoGeom(),
                   Ig2_GridConnection_GridConnection_GridCoGridCoGeom()],
                  [Ip2_CohFrictMat_CohFrictMat_CohFrictPhys(setCohesionNow=True, setCohesionOnNewContacts=False),
                   Ip2_FrictMat_FrictMat_FrictPhys()],
                  [Law2_ScGeom6D_CohFrictPhys_CohesionMoment(), Law2_ScGridCoGeom_FrictPhys_CundallStrack(),
                   Law2_GridCoGridCoGeom_FrictPhys_CundallStrack()])
  NewtonIntegrator(gravity=(0,0,-10), damping=0.3)    # Cundall local damping, also on the sphere
  Why Ig2_GridConnection_GridConnection_GridCoGridCoGeom is in the list even though no cylinder-cylinder
  contact is wanted: a GridConnection IS-A Sphere, so without it the collider's connection-connection
  pairs are dispatched to Ig2_Sphere_GridConnection_ScGridCoGeom with the first connection treated as a
  sphere at its body position (= its node1).  Where that point is the other connection's end node the
  distance is 0 and the normal NaN, and the NaN forces blow up the nodes (seen in the net: every free
  node NaN after step 1).  The GridCo-GridCo functor rejects pairs that share a node.
TIME STEP
  dt = 1e-4 s (fixed; PWaveTimeStep is written to the JSON for information).  Contact period
  2 pi sqrt(m/kn) = 4.87e-3 s, i.e. about 49 steps per period.
STEPS
  4000 steps (0.4 s) per case; the sphere is at rest (|v| < 1e-13) after about 2200 steps.
  History output every 20 steps.  Then (outside the history) NTIMING = 20000 more steps in a single
  O.run call are timed for the wall time per step (O.run(n, True) in small chunks costs ~40 ms of
  polling per call, so the history loop is not a fair timing).
ANALYTICAL EXPECTATIONS (static equilibrium)
  contact normal force = W = 10 N;  overlap delta = W / kn = 6.0e-6 m;
  sphere rest z = r_s + r_c - W/kn = 0.059994 m;  shear force 0.
  't025': force on node 0 = (1-t) W = 7.5 N down, on node 1 = t W = 2.5 N down (O.forces.f of the
          blocked nodes; in YADE the contact force is distributed to the nodes, nothing goes to the
          GridConnection body).
  'node': exactly one active contact carrying W = 10 N; the whole force on node 1, nothing on 0 and 2.
OUTPUTS
  sphere_on_cylinder_<case>_history.csv : step,time,sphere_z,sphere_vz,overlap,n_contacts,n_active,
          contact_fn,contact_fs,node_fz_<id>... (force z on each node), sphere_fz (contact force on the sphere)
  sphere_on_cylinder_summary.json : per case: setup numbers, final contacts (after NSTEP steps: id2, isDuplicate,
          relPos, normal force, shear force, overlap), node forces and torques, sphere position, analytic
          values, wall time per step (from the NTIMING run).
"""
from yade import *
from yade.gridpfacet import gridNode, gridConnection
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


def build(case):
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
	                young=E, poisson=NU, density=RHO, frictionAngle=PHI, normalCohesion=1e100, shearCohesion=1e100,
	                momentRotationLaw=True, label='nodeMat'
	        )
	)
	O.materials.append(FrictMat(young=E, poisson=NU, density=RHO, frictionAngle=PHI, label='connMat'))
	O.materials.append(FrictMat(young=E, poisson=NU, density=RHO_S, frictionAngle=PHI, label='sphereMat'))
	xs = [0.0, 1.0] if case == 't025' else [0.0, 0.5, 1.0]
	nodes = [O.bodies.append(gridNode(Vector3(x, 0, 0), RC, wire=False, fixed=True, material='nodeMat')) for x in xs]
	conns = [O.bodies.append(gridConnection(nodes[i], nodes[i + 1], RC, material='connMat')) for i in range(len(nodes) - 1)]
	xsph = 0.25 if case == 't025' else 0.5
	sph = O.bodies.append(sphere(Vector3(xsph, 0, RS + RC), RS, material='sphereMat'))
	pw = PWaveTimeStep()
	O.dt = DT
	return nodes, conns, sph, pw


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
		        'overlap': g.penetrationDepth,
		        'normal': list(g.normal),
		        'normalForce': list(p.normalForce),
		        'shearForce': list(p.shearForce),
		        'kn': p.kn,
		        'ks': p.ks,
		})
	return out


summary = {'scenario': 'sphere_on_cylinder', 'yade_version': '2023.02a', 'threads': O.numThreads, 'cases': {}}
for case in ['t025', 'node']:
	nodes, conns, sph, pw = build(case)
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
	with open(os.path.join(OUT, 'sphere_on_cylinder_%s_history.csv' % case), 'w') as f:
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
	if case == 't025':
		t = 0.25
		expect_nodes = {str(nodes[0]): -(1 - t) * W, str(nodes[1]): -t * W}
	else:
		expect_nodes = {str(nodes[0]): 0.0, str(nodes[1]): -W, str(nodes[2]): 0.0}
	summary['cases'][case] = {
	        'node_ids': nodes,
	        'node_pos': [list(O.bodies[n].state.pos) for n in nodes],
	        'connection_ids': conns,
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
with open(os.path.join(OUT, 'sphere_on_cylinder_summary.json'), 'w') as f:
	json.dump(summary, f, indent=1)
