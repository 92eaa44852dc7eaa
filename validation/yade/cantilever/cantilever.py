# -*- coding: utf-8 -*-
"""
flexdem validation: cantilever of GridNodes and GridConnections under a tip load, YADE side.

Run (headless, one thread; outputs go to the current directory or to $YADE_OUT if set):
    yade -j 1 -n -x cantilever.py

Setup (the same scene is rebuilt by flexdem's validation case `yade_cantilever` with the
`yade` link kinematics):
  - 11 GridNodes at x = 0, 0.1, ..., 1.0 m (y = z = 0), 10 GridConnections between
    neighbours; radius r = 0.01 m for nodes and connections.
  - One CohFrictMat for everything: E = 1e8 Pa, poisson = 0.3, density = 1000 kg/m3,
    friction angle 30 deg, cohesion 1e100 (unbreakable), momentRotationLaw = True.
  - Node 0 clamped (blockedDOFs 'xyzXYZ'), no gravity.
  - Tip force P = 0.01 N along -z on node 10 (O.forces.setPermF, constant from step 0).
  - Engines: ForceResetter; InteractionLoop with Ig2_GridNode_GridNode_GridNodeGeom6D,
    Ip2_CohFrictMat_CohFrictMat_CohFrictPhys(setCohesionNow=True), Law2_ScGeom6D_CohFrictPhys_CohesionMoment;
    NewtonIntegrator(damping=0.3) (Cundall local damping).
  - dt = 0.5 * PWaveTimeStep().
  - Run in chunks of 20000 steps until the tip deflection changes by less than 1e-9 relative
    over a chunk and the largest node speed is below 1e-8 m/s (at most 2e6 steps).

Outputs:
  cantilever_nodes.csv     node,x0,x,y,z,rot_y,deflection   (deflection = -z, rot_y in rad)
  cantilever_summary.json  parameters, dt, steps, tip deflection and rotation, P L^3/(3EI)
"""
from yade import *
from yade.gridpfacet import gridNode, gridConnection
import json, math, os

out_dir = os.environ.get('YADE_OUT', os.getcwd())
segments, length, radius = 10, 1.0, 0.01
young, poisson, density, damping = 1e8, 0.3, 1000.0, 0.3
load = 0.01
chunk, max_steps = 20000, 2000000

O.engines = [
        ForceResetter(),
        InteractionLoop(
                [Ig2_GridNode_GridNode_GridNodeGeom6D()],
                [Ip2_CohFrictMat_CohFrictMat_CohFrictPhys(setCohesionNow=True, setCohesionOnNewContacts=False)],
                [Law2_ScGeom6D_CohFrictPhys_CohesionMoment()],
        ),
        NewtonIntegrator(gravity=(0, 0, 0), damping=damping),
]
O.materials.append(
        CohFrictMat(
                young=young,
                poisson=poisson,
                density=density,
                frictionAngle=math.radians(30),
                normalCohesion=1e100,
                shearCohesion=1e100,
                momentRotationLaw=True,
                label='beam'
        )
)
step_length = length / segments
nodes = [O.bodies.append(gridNode(Vector3(k * step_length, 0, 0), radius, wire=False, fixed=False, material='beam')) for k in range(segments + 1)]
for k in range(segments):
	O.bodies.append(gridConnection(nodes[k], nodes[k + 1], radius, material='beam'))
O.bodies[nodes[0]].state.blockedDOFs = 'xyzXYZ'
O.dt = 0.5 * PWaveTimeStep()
tip = nodes[-1]
O.forces.setPermF(tip, Vector3(0, 0, -load))


def max_speed():
	return max(O.bodies[n].state.vel.norm() for n in nodes)


def rotation_y(body):
	axis, angle = O.bodies[body].state.ori.toAxisAngle()
	return (axis * angle)[1]


previous = None
while O.iter < max_steps:
	O.run(chunk, True)
	deflection = -O.bodies[tip].state.pos[2]
	settled = previous is not None and abs(deflection - previous) <= 1e-9 * abs(deflection)
	previous = deflection
	if settled and max_speed() < 1e-8:
		break

with open(os.path.join(out_dir, 'cantilever_nodes.csv'), 'w') as f:
	f.write('node,x0,x,y,z,rot_y,deflection\n')
	for k, n in enumerate(nodes):
		p = O.bodies[n].state.pos
		f.write('%d,%.6f,%.15e,%.15e,%.15e,%.15e,%.15e\n' % (k, k * step_length, p[0], p[1], p[2], rotation_y(n), -p[2]))

inertia = math.pi * radius**4 / 4.0
summary = {
        'yade_version': '2023.02a',
        'segments': segments,
        'length': length,
        'radius': radius,
        'young': young,
        'poisson': poisson,
        'density': density,
        'damping': damping,
        'tip_load': load,
        'dt': O.dt,
        'steps': O.iter,
        'max_node_speed': max_speed(),
        'tip_deflection': -O.bodies[tip].state.pos[2],
        'tip_rotation_y': rotation_y(tip),
        'euler_bernoulli_deflection': load * length**3 / (3 * young * inertia),
        'euler_bernoulli_rotation': load * length**2 / (2 * young * inertia),
}
with open(os.path.join(out_dir, 'cantilever_summary.json'), 'w') as f:
	json.dump(summary, f, indent=1)
print('cantilever:', summary)
