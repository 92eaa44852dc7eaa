#!/usr/bin/env python3
"""Writes the malformed scene corpus: NAME.toml and NAME.expected (message fragments, one per
line; the first is "NAME.toml:LINE:" where LINE is the line marked `# <- error`).
Run from this folder: python3 generate.py"""

SIM = '[simulation]\nsteps = 10\n'
MAT = '''
[materials.steel]
young = 210e9
poisson = 0.3
density = 7850
friction_angle_deg = 30

[materials.rubber]
young = 1e6
poisson = 0.45
density = 1100
friction_angle_deg = 35
'''
CHAIN = '''
[[structures]]
name = "cable"
kind = "chain"
material = "steel"
node_radius = 0.01
start = [0, 0, 0]
end = [1, 0, 0]
segments = 4
'''
BASE = SIM + MAT + CHAIN
WALL = '\n[[walls]]\npoint = [0, 0, 0]\nnormal = [0, 0, 1]\nmaterial = "steel"\n'
SERIES = '\n[output]\nseries_every = 10\n\n[[output.series]]\nname = "s"\n'

CASES = {
    "toml_syntax": ('[simulation]\nsteps = 10 20  # <- error\n', ["`simulation.steps`"]),
    "toml_unterminated_string": (SIM + MAT + CHAIN.replace('name = "cable"', 'name = "cable  # <- error'), ["`structures.name`", "string"]),
    "unknown_section": (SIM + MAT + '\n[[structure]]  # <- error\nname = "x"\n', ["unknown field `structure`", "did you mean `structures`?"]),
    "unknown_key_simulation": (SIM + 'gravty = [0, 0, -9.81]  # <- error\n', ["`simulation.gravty`", "unknown field `gravty`", "did you mean `gravity`?"]),
    "unknown_material_key": (SIM + '\n[materials.steel]\nyoung = 1e9\nyoung_modulus = 1e9  # <- error\npoisson = 0.3\ndensity = 7850\nfriction_angle_deg = 30\n', ["`materials.steel.young_modulus`", "unknown field `young_modulus`"]),
    "unknown_material_name": (SIM + MAT + CHAIN.replace('material = "steel"', 'material = "stel"  # <- error'), ["`structures.material`", "unknown material `stel`", "rubber, steel", "did you mean `steel`?"]),
    "no_material_defined": (SIM + CHAIN.replace('material = "steel"', 'material = "steel"  # <- error'), ["unknown material `steel`", "no material is defined"]),
    "negative_node_radius": (SIM + MAT + CHAIN.replace('node_radius = 0.01', 'node_radius = -0.01  # <- error'), ["`structures.node_radius`", "is -0.01", "expected a finite number > 0 (m)"]),
    "nan_gravity": ('[simulation]\nsteps = 10\ngravity = [0, nan, -9.81]  # <- error\n', ["`simulation.gravity`", "expected three finite numbers"]),
    "steps_and_duration": ('[simulation]\nsteps = 10\nduration = 0.5  # <- error\n', ["`simulation.duration`", "conflicts with `steps`"]),
    "no_run_length": ('[simulation]  # <- error\ndt = 1e-6\n', ["`simulation.steps`", "give `steps = N` or `duration = T`"]),
    "dt_zero": ('[simulation]\ndt = 0.0  # <- error\nsteps = 10\n', ["`simulation.dt`", "is 0", "finite time step > 0"]),
    "dt_word": ('[simulation]\ndt = "automatic"  # <- error\nsteps = 10\n', ["`simulation.dt`", "\"auto\" or a time step in seconds"]),
    "damping_too_large": ('[simulation]\nsteps = 10\ndamping = 1.5  # <- error\n', ["`simulation.damping`", "expected a number in [0, 1)"]),
    "steps_wrong_type": ('[simulation]\nsteps = "many"  # <- error\n', ["`simulation.steps`", "invalid type: string", "expected a whole number"]),
    "poisson_out_of_range": (SIM + '\n[materials.steel]\nyoung = 1e9\npoisson = 0.7  # <- error\ndensity = 7850\nfriction_angle_deg = 30\n', ["`materials.steel.poisson`", "-1 < poisson <= 0.5"]),
    "friction_in_radians_key": (SIM + '\n[materials.steel]\nyoung = 1e9\npoisson = 0.3\ndensity = 7850\nfriction_angle = 0.5  # <- error\n', ["unknown field `friction_angle`", "did you mean `friction_angle_deg`?"]),
    "missing_density": (SIM + '\n[materials.steel]  # <- error\nyoung = 1e9\npoisson = 0.3\nfriction_angle_deg = 30\n', ["missing field `density`"]),
    "unknown_kind": (SIM + MAT + CHAIN.replace('kind = "chain"', 'kind = "tub"  # <- error'), ["`structures.kind`", "unknown kind `tub`", "did you mean `tube`?"]),
    "key_of_other_kind": (SIM + MAT + CHAIN.replace('segments = 4', 'segments = 4\nlength = 2.0  # <- error'), ["`structures.length`", "does not apply to kind = \"chain\"", "points, start, end, segments"]),
    "tube_missing_length": (SIM + MAT + '\n[[structures]]  # <- error\nname = "t"\nkind = "tube"\nmaterial = "rubber"\nnode_radius = 0.002\nradius = 0.1\naround = 16\nalong = 20\n', ["`structures.length`", "kind = \"tube\" needs `length`"]),
    "duplicate_structure": (BASE + CHAIN.replace('name = "cable"', 'name = "cable"  # <- error'), ["`structures.name`", "`cable` already exists"]),
    "mesh_missing_file": (SIM + MAT + '\n[[structures]]\nname = "m"\nkind = "mesh"\nmaterial = "steel"\nnode_radius = 0.01\nfile = "no_such_mesh.obj"  # <- error\n', ["`structures.file`", "cannot read the mesh", "no_such_mesh.obj"]),
    "mesh_broken_file": (SIM + MAT + '\n[[structures]]\nname = "m"\nkind = "mesh"\nmaterial = "steel"\nnode_radius = 0.01\nfile = "broken.obj"  # <- error\n', ["`structures.file`", "cannot read the mesh", "broken.obj:3:"]),
    "placement_both_rotations": (BASE.replace('segments = 4', 'segments = 4\nplacement = { rotate_deg = [0, 0, 90], axis = [0, 0, 1], angle_deg = 90 }  # <- error'), ["`structures.placement.rotate_deg`", "not both"]),
    "placement_zero_scale": (BASE.replace('segments = 4', 'segments = 4\nplacement = { scale = 0 }  # <- error'), ["`structures.placement.scale`", "expected a finite number > 0"]),
    "selection_matches_nothing": (BASE + '\n[[boundary]]\nselect = { structure = "cable", box = { min = [5, 5, 5], max = [6, 6, 6] } }  # <- error\nblock = "xyz"\n', ["`boundary.select`", "matches no particle"]),
    "selection_unknown_structure": (BASE + '\n[[boundary]]\nselect = { structure = "cabel" }  # <- error\nblock = "xyz"\n', ["`boundary.select.structure`", "unknown structure `cabel`", "did you mean `cable`?"]),
    "selection_bad_side": (BASE + '\n[[boundary]]\nselect = { structure = "cable", side = "corners" }  # <- error\nblock = "xyz"\n', ["`boundary.select.side`", "structure `cable`: unknown side `corners`", "start, end, ends"]),
    "bad_dofs": (BASE + '\n[[boundary]]\nselect = { structure = "cable", side = "start" }\nblock = "xyw"  # <- error\n', ["`boundary.block`", "x, y, z (translations) and X, Y, Z"]),
    "selection_ids_out_of_range": (BASE + '\n[[loads]]\nselect = { ids = [2, 99] }  # <- error\nforce = [0, 0, -1]\n', ["`loads.select.ids`", "particle id 99 does not exist", "5 particles"]),
    "load_force_and_total": (BASE + '\n[[loads]]\nselect = { structure = "cable", side = "end" }\nforce = [0, 0, -1]\ntotal_force = [0, 0, -1]  # <- error\n', ["`loads.total_force`", "not both"]),
    "ramp_negative_duration": (BASE + '\n[[loads]]\nselect = { structure = "cable", side = "end" }\nforce = [0, 0, -1]\nramp = { start = 0, duration = -1 }  # <- error\n', ["`loads.ramp.duration`", "expected a finite number > 0 (s)"]),
    "wall_zero_normal": (SIM + MAT + '\n[[walls]]\npoint = [0, 0, 0]\nnormal = [0, 0, 0]  # <- error\nmaterial = "steel"\n', ["`walls.normal`", "non-zero direction"]),
    "wrong_vector_length": (SIM + MAT + '\n[[walls]]\npoint = [0, 0]  # <- error\nnormal = [0, 0, 1]\nmaterial = "steel"\n', ["`walls.point`", "invalid length 2", "expected three numbers [x, y, z]"]),
    "random_packing_too_dense": (SIM + MAT + '\n[[spheres]]  # <- error\nkind = "random"\nmaterial = "steel"\nbox = { min = [0, 0, 0], max = [0.1, 0.1, 0.1] }\nradius = 0.02\ncount = 500\nseed = 1\n', ["only", "of 500 spheres fit"]),
    "spheres_bad_kind_key": (SIM + MAT + '\n[[spheres]]\nkind = "single"\nmaterial = "steel"\ncenter = [0, 0, 0]\nradius = 0.1\ncount = 3  # <- error\n', ["`spheres.count`", "does not apply to kind = \"single\""]),
    "series_needs_one_particle": (BASE + '\n[output]\nseries_every = 10\n\n[[output.series]]\nname = "p"\nquantity = "position"\nof = { structure = "cable" }  # <- error\n', ["`output.series.of`", "needs exactly one particle", "has 5"]),
    "series_unknown_quantity": (BASE + '\n[output]\nseries_every = 10\n\n[[output.series]]\nname = "e"\nquantity = "energie"  # <- error\n', ["`output.series.quantity`", "unknown quantity `energie`", "did you mean `energy`?"]),
    "threads_zero": ('[simulation]\nsteps = 10\nthreads = 0  # <- error\n', ["`simulation.threads`", "expected a whole number >= 1"]),
    "link_kinematics_typo": ('[simulation]\nsteps = 10\nlink_kinematics = "yadee"  # <- error\n', ["`simulation.link_kinematics`", "did you mean `yade`?"]),
    # issue 13: input that cannot crash it
    "non_ascii_in_unterminated_string": ('[simulation]\nsteps = 10\ndt = "a·b = 1  # <- error\n', ["`simulation.dt`"]),
    "threads_too_many": ('[simulation]\nsteps = 10\nthreads = 100000  # <- error\n', ["`simulation.threads`", "is 100000", "expected a whole number in [1, 4096]"]),
    "vector_four_components": ('[simulation]\nsteps = 10\ngravity = [0, 0, -9.81, 1]  # <- error\n', ["`simulation.gravity`", "invalid length 4", "expected three numbers [x, y, z]"]),
    "pair_three_components": (SIM + MAT + '\n[[structures]]\nname = "m"\nkind = "membrane"\nmaterial = "steel"\nnode_radius = 0.001\nsize = [1, 1, 1]  # <- error\ncells = [4, 4]\n', ["`structures.size`", "invalid length 3", "expected two numbers [a, b]"]),
    "dt_tiny_for_duration": ('[simulation]\ndt = 1e-300\nduration = 1  # <- error\n', ["`simulation.duration`", "is 1.000e300 steps", "expected at most 1e12"]),
    "steps_too_many": ('[simulation]\nsteps = 9223372036854775807  # <- error\n', ["`simulation.steps`", "expected at most 1000000000000"]),
    "shell_too_many_nodes": (SIM + MAT + '\n[[structures]]  # <- error\nname = "ball"\nkind = "sphere_shell"\nmaterial = "steel"\nnode_radius = 0.0001\nradius = 1.0\nsubdivisions = 9\n', ["`structures`", "2621442 nodes", "more than the 2000000 allowed"]),
    "helix_pitch_zero": (SIM + MAT + '\n[[structures]]  # <- error\nname = "spring"\nkind = "helix"\nmaterial = "steel"\nnode_radius = 0.01\nradius = 0.1\npitch = 0\nturns = 2\n', ["`structures`", "structure `spring` overlaps itself at the start", "connection"]),
    # issue 15: walls that hold a stress, and the measures of walls and samples
    "wall_servo_and_velocity": (SIM + MAT + WALL + 'velocity = [0, 0, 1]\nservo = { stress = 1e5, area = 0.01, max_speed = 0.1 }  # <- error\n', ["`walls.servo`", "conflicts with `velocity`"]),
    "wall_servo_negative_stress": (SIM + MAT + WALL + 'servo = { stress = -1e5, area = 0.01, max_speed = 0.1 }  # <- error\n', ["`walls.servo.stress`", "is -100000", "expected a finite number >= 0"]),
    "wall_servo_zero_speed": (SIM + MAT + WALL + 'servo = { stress = 1e5, area = 0.01, max_speed = 0 }  # <- error\n', ["`walls.servo.max_speed`", "is 0", "expected a finite number > 0 (m/s)"]),
    "wall_servo_missing_max_speed": (SIM + MAT + WALL + 'servo = { stress = 1e5, area = 0.01 }  # <- error\n', ["`walls.servo`", "missing field `max_speed`"]),
    "wall_servo_unknown_key": (SIM + MAT + WALL + 'servo = { stress = 1e5, area = 0.01, max_speed = 0.1, gian = 1e-6 }  # <- error\n', ["unknown field `gian`", "did you mean `gain`?"]),
    "series_wall_out_of_range": (BASE + WALL + SERIES + 'quantity = "wall_force"\nwall = 3  # <- error\n', ["`output.series.wall`", "is 3", "from 0 to 0 (in file order)"]),
    "series_wall_stress_needs_area": (BASE + WALL + SERIES.replace('[[output.series]]', '[[output.series]]  # <- error') + 'quantity = "wall_stress"\nwall = 0\n', ["`output.series.area`", "wall 0 has no servo", "give `area`"]),
    "series_stress_needs_region": (BASE + SERIES.replace('[[output.series]]', '[[output.series]]  # <- error') + 'quantity = "stress"\n', ["`output.series.box`", "needs a region", "cylinder"]),
    "series_key_of_other_quantity": (BASE + SERIES + 'quantity = "energy"\nwall = 0  # <- error\n', ["`output.series.wall`", "quantity = \"energy\" does not take `wall`", "wall_force and wall_stress"]),
    "series_flat_box": (BASE + SERIES + 'quantity = "solid_fraction"\nbox = { min = [0, 0, 0], max = [1, 0, 1] }  # <- error\n', ["`output.series.box`", "not below max", "no volume"]),
    "plot_without_series": (BASE + '\n[output]  # <- error\nvtk_every = 100\nplot = true\n', ["`output.plot`", "nothing to plot", "[[output.series]]"]),
    # viscous contact damping (model.md §7)
    "restitution_out_of_range": (SIM + '\n[materials.steel]\nyoung = 1e9\npoisson = 0.3\ndensity = 7850\nfriction_angle_deg = 30\nrestitution = 1.2  # <- error\n', ["`materials.steel.restitution`", "is 1.2", "0 < restitution <= 1"]),
    "damping_restitution_and_rates": (SIM + '\n[materials.steel]\nyoung = 1e9\npoisson = 0.3\ndensity = 7850\nfriction_angle_deg = 30\nrestitution = 0.5\ngamma_n = 100  # <- error\n', ["`materials.steel.gamma_n`", "conflicts with `restitution`", "not both"]),
    "negative_gamma_t": (SIM + '\n[materials.steel]\nyoung = 1e9\npoisson = 0.3\ndensity = 7850\nfriction_angle_deg = 30\ngamma_t = -5  # <- error\n', ["`materials.steel.gamma_t`", "is -5", "expected a finite number >= 0 (1/s"]),
    "chain_thicker_than_its_segments": (SIM + MAT + CHAIN.replace('[[structures]]', '[[structures]]  # <- error').replace('segments = 4', 'segments = 1000000'), ["`structures`", "structure `cable` overlaps itself at the start", "connection 0 (nodes 0–1)", "connection 2 (nodes 2–3)"]),
}

for name, (text, fragments) in CASES.items():
    lines = text.split("\n")
    marked = [i + 1 for i, l in enumerate(lines) if "# <- error" in l]
    assert len(marked) == 1, name
    with open(f"{name}.toml", "w") as f:
        f.write(f"# Malformed scene for the error-message tests: {name.replace('_', ' ')}.\n" + text)
    with open(f"{name}.expected", "w") as f:
        f.write(f"{name}.toml:{marked[0] + 1}:\n" + "\n".join(fragments) + "\n")

with open("broken.obj", "w") as f:
    f.write("# a mesh with a bad vertex line\nv 0 0 0\nv 1 zero 0\nv 0 1 0\nf 1 2 3\n")
print(len(CASES), "cases")
