# -*- coding: utf-8 -*-
"""
ENSEMBLE OF THE SPHERE ON A NET (YADE 2023.02a reference), for flexdem's `yade_sphere_on_net` case.

The rest state's heights are set by the net's stiffness, but how each contact's force splits into normal
and shear parts is not: friction locks in shear during the bouncing transient, and which shear it locks in
is chaotic (a start 1e-12 m higher changes it). One run is one sample. This script runs the scene of
`sphere_on_net.py` (its scene-building part, executed as is) from starts shifted vertically by
k x 1e-10 m, k = -7..8 (k = 0 is the reference run), each for NSTEP = 400000 steps, and writes one row
per start.

Run:   yade -j 1 -n -x sphere_on_net_ensemble.py     (from this directory; output to the current
                                                       directory, or to $YADE_REF_OUT if set)
OUTPUT sphere_on_net_ensemble.csv : k,shift,sphere_z,centre_node_z,min_sphere_z_history,n_active,
       fn_mean,fs_mean,sum_contact_fz (active contacts only; min over outputs every 1000 steps)
       sphere_on_net_ensemble_history.csv : k,step,sphere_z,n_active,fn_mean,fs_mean every 1000
       steps up to HISTORY_STEPS = 100000 (4 s)
"""
import os

HERE = os.getcwd()
OUT = os.environ.get('YADE_REF_OUT', os.getcwd())
SOURCE = open(os.path.join(HERE, 'sphere_on_net.py')).read()
SCENE = SOURCE[:SOURCE.index('rows = []')]
KS = [int(k) for k in os.environ.get('ENSEMBLE_KS', ','.join(str(k) for k in range(-7, 9))).split(',')]
SHIFT = 1e-10

HISTORY_STEPS = 100000
rows = []
history = []
for k in KS:
	ns = dict(globals())
	exec(SCENE, ns)
	O, Vector3 = ns['O'], ns['Vector3']
	sph, centre, active, contacts = ns['sph'], ns['centre'], ns['active'], ns['contacts']
	O.bodies[sph].state.pos = O.bodies[sph].state.pos + Vector3(0, 0, k * SHIFT)
	lowest = O.bodies[sph].state.pos[2]
	for _ in range(ns['NSTEP'] // ns['OUTPERIOD']):
		O.run(ns['OUTPERIOD'], True)
		lowest = min(lowest, O.bodies[sph].state.pos[2])
		if O.iter <= HISTORY_STEPS:
			act = [c for c in contacts() if active(c)]
			n = max(len(act), 1)
			history.append((k, O.iter, O.bodies[sph].state.pos[2], len(act), sum(c['fn'] for c in act) / n, sum(c['fs'] for c in act) / n))
	act = [c for c in contacts() if active(c)]
	fn = sum(c['fn'] for c in act) / max(len(act), 1)
	fs = sum(c['fs'] for c in act) / max(len(act), 1)
	rows.append((k, k * SHIFT, O.bodies[sph].state.pos[2], O.bodies[centre].state.pos[2], lowest, len(act), fn, fs,
	             O.forces.f(sph, sync=True)[2]))
	print('start %d: fn_mean %.6f N, fs_mean %.6f N, sphere z %.9f m' % (k, fn, fs, rows[-1][2]))
with open(os.path.join(OUT, 'sphere_on_net_ensemble.csv'), 'w') as f:
	f.write('k,shift,sphere_z,centre_node_z,min_sphere_z_history,n_active,fn_mean,fs_mean,sum_contact_fz\n')
	for r in rows:
		f.write('%d,%.3e,%.12e,%.12e,%.12e,%d,%.12e,%.12e,%.10e\n' % r)
with open(os.path.join(OUT, 'sphere_on_net_ensemble_history.csv'), 'w') as f:
	f.write('k,step,sphere_z,n_active,fn_mean,fs_mean\n')
	for r in history:
		f.write('%d,%d,%.12e,%d,%.10e,%.10e\n' % r)
