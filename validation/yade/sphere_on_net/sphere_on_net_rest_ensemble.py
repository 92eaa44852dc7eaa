# -*- coding: utf-8 -*-
"""
REST FORCES OF THE SPHERE ON A NET, OVER 100 STARTS (YADE 2023.02a reference), for flexdem's
`yade_sphere_on_net` case.

At rest the sphere sits on four contacts whose split into normal and shear force is locked in by friction
during the bouncing transient, which is chaotic: over the 16 starts 1e-10 m apart of
`sphere_on_net_ensemble.py` the mean normal force per contact ranges over 2.55-2.68 N, and neighbouring
starts give close values, so a mean over them moves by 1-2 % when the transient changes by round-off.
This script runs the scene of `sphere_on_net.py` (its scene-building part, executed as is) from
NSTART = 100 starts k x SHIFT higher, SHIFT = 1e-8 m, k = -50..49 (the middle half of
`sphere_on_net_first_dip.py`'s starts), each until at rest by flexdem's criterion (every body's speed at
most 1e-9 m/s at 10 successive checks 1000 steps apart, checked by a PyRunner after the NewtonIntegrator)
or MAXSTEP = 400 000 steps, and writes the contacts carrying load (as `sphere_on_net.py`'s `active`).

Run:   yade -j 1 -n -x sphere_on_net_rest_ensemble.py   (from this directory; about 20 minutes; output to
                                                        the current directory, or to $YADE_REF_OUT if set)
OUTPUT sphere_on_net_rest_ensemble.csv : k,shift,steps,sphere_z,n_active,fn_mean,fs_mean (means over the
       active contacts at the end; steps: the step at which the run stopped)
"""
import os

HERE = os.getcwd()
OUT = os.environ.get('YADE_REF_OUT', os.getcwd())
SOURCE = open(os.path.join(HERE, 'sphere_on_net.py')).read()
SCENE = SOURCE[:SOURCE.index('rows = []')]
KS = list(range(-50, 50))
SHIFT = 1e-8
MAXSTEP = 400000
QUIET_SPEED = 1e-9
QUIET_CHECKS = 10
CHECK_PERIOD = 1000

rows = []
for k in KS:
	ns = dict(globals())
	exec(SCENE, ns)
	O, Vector3, PyRunner = ns['O'], ns['Vector3'], ns['PyRunner']
	sph, contacts, active, maxvel = ns['sph'], ns['contacts'], ns['active'], ns['maxvel']
	O.bodies[sph].state.pos = O.bodies[sph].state.pos + Vector3(0, 0, k * SHIFT)
	quiet = [0]

	def check_rest():
		quiet[0] = quiet[0] + 1 if maxvel() <= QUIET_SPEED else 0
		if quiet[0] >= QUIET_CHECKS:
			O.pause()

	# a PyRunner's command is evaluated in the __main__ namespace; after the NewtonIntegrator, so it reads
	# the velocities of the step just done
	__builtins__.check_rest = check_rest
	O.engines = O.engines + [PyRunner(command='check_rest()', iterPeriod=CHECK_PERIOD)]
	O.run(MAXSTEP, True)
	act = [c for c in contacts() if active(c)]
	n = max(len(act), 1)
	fn = sum(c['fn'] for c in act) / n
	fs = sum(c['fs'] for c in act) / n
	rows.append((k, k * SHIFT, O.iter, O.bodies[sph].state.pos[2], len(act), fn, fs))
	print('start %d: %d steps, %d contacts, fn_mean %.6f N, fs_mean %.6f N' % (k, O.iter, len(act), fn, fs), flush=True)
with open(os.path.join(OUT, 'sphere_on_net_rest_ensemble.csv'), 'w') as f:
	f.write('k,shift,steps,sphere_z,n_active,fn_mean,fs_mean\n')
	for r in rows:
		f.write('%d,%.3e,%d,%.12e,%d,%.12e,%.12e\n' % r)
