#!/usr/bin/env python3
"""Writes the granular twin of flexdem and LAMMPS: the same spheres, start state, contact law,
walls, gravity, time step and neighbour skin in both codes.

    bench/lammps/twin.py --flexdem target/release/flexdem --out DIR [--count 16000]

makes, in DIR:
  pack.toml       a flexdem scene whose only job is the start state: `count` equal spheres in a
                  box at solid fraction 0.57 (FIRE minimisation, seed 1), written by
                  `flexdem spheres pack.toml -o spheres.csv`;
  spheres.csv     that start state (x, y, z, radius);
  granular.toml   the flexdem scene: those spheres, resting in the box on 5 walls (open top),
                  gravity, fixed dt, no global damping, output off;
  data.granular   the same spheres for LAMMPS (atom_style sphere);
  in.granular     the LAMMPS input: pair gran/hooke/history and fix wall/gran
                  hooke/history with the same kn, kt, friction, damping, the same dt and skin,
                  nve/sphere, gravity; `run WARMUP` then the timed `run STEPS`.

The contact law is the same linear spring with Coulomb friction: flexdem's kn = 2·E·r1·r2/(r1 +
r2) = E·r for equal spheres and for a sphere on a wall (eq 3, a wall takes the sphere's
radius), so E = kn/r; ks = shear_ratio·kn = kt; tan φ = xmu. LAMMPS stores the shear
displacement and flexdem the shear force (equal for a constant kt); both test Coulomb on the
shear spring plus the tangential dashpot against the normal force with its damping part and
rescale the spring when it slides, but LAMMPS does not clamp the damped normal force at 0
(unless `limit_damping`) and takes |Fn| for the limit, while flexdem clamps it (docs/model.md
§7). With the default gamma_n = gamma_t = 0 (no contact damping) the two laws are the same.
"""
import argparse
import math
import os
import subprocess
import sys

# The system (SI units): equal glass-like beads.
RADIUS = 0.005          # m (the packing scales it a little to make phi exact)
DENSITY = 2500.0        # kg/m^3
KN = 1.0e5              # N/m
KT_OVER_KN = 2.0 / 7.0  # LAMMPS's usual kt = 2/7 kn
XMU = 0.5               # friction coefficient
DT = 1.0e-5             # s (contact time pi*sqrt(m_eff/kn) = 2.5e-4 s for two beads: 25 steps)
GRAVITY = 9.81          # m/s^2, along -z
SOLID_FRACTION = 0.57
BASE = 0.2              # m, side of the square box
# Neighbour skin: flexdem grows each sphere's box by verlet_factor/2 * r (default 0.5: r/4
# each side) and rebuilds when a sphere has moved by that much; LAMMPS's skin is the extra
# pair distance, rebuilt when an atom has moved by half of it: skin = r/2 is the same.
SKIN_OVER_R = 0.5


def box_height(count, radius):
    volume = count * 4.0 / 3.0 * math.pi * radius**3 / SOLID_FRACTION
    return volume / (BASE * BASE)


def write(path, text):
    with open(path, "w") as f:
        f.write(text)


def material(gamma_n, gamma_t):
    young = KN / RADIUS
    phi = math.degrees(math.atan(XMU))
    text = (f"young = {young!r}\npoisson = 0.3\ndensity = {DENSITY!r}\n"
            f"friction_angle_deg = {phi!r}\nshear_ratio = {KT_OVER_KN!r}\n")
    if gamma_n > 0.0 or gamma_t > 0.0:
        text += f"gamma_n = {gamma_n!r}\ngamma_t = {gamma_t!r}\n"
    return text


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--flexdem", required=True, help="the flexdem binary")
    ap.add_argument("--out", required=True, help="folder to write into")
    ap.add_argument("--count", type=int, default=16000, help="spheres (16000)")
    ap.add_argument("--warmup", type=int, default=200, help="untimed steps (200)")
    ap.add_argument("--steps", type=int, default=2000, help="timed steps (2000)")
    ap.add_argument("--gamma-n", type=float, default=0.0, help="LAMMPS gamma_n (1/s), 0")
    ap.add_argument("--gamma-t", type=float, default=0.0, help="LAMMPS gamma_t (1/s), 0")
    a = ap.parse_args()
    os.makedirs(a.out, exist_ok=True)
    height = box_height(a.count, RADIUS)
    mat = material(0.0, 0.0)
    write(os.path.join(a.out, "pack.toml"), f"""# start state of the granular twin (bench/lammps/twin.py)
[simulation]
dt = 1e-5
steps = 1

[materials.bead]
{mat}
[[spheres]]
kind = "dense"
material = "bead"
box = {{ min = [0, 0, 0], max = [{BASE!r}, {BASE!r}, {height!r}] }}
radius = {RADIUS!r}
count = {a.count}
solid_fraction = {SOLID_FRACTION!r}
seed = 1
""")
    csv = os.path.join(a.out, "spheres.csv")
    # made once per flexdem binary: a file of an older binary may be in another order (since
    # 9d1ff55 `flexdem spheres` writes them in the order of space), which changes the speed
    if not os.path.exists(csv) or os.path.getmtime(csv) < os.path.getmtime(a.flexdem):
        subprocess.run([a.flexdem, "spheres", os.path.join(a.out, "pack.toml"), "-o", csv],
                       check=True)
    spheres = []
    with open(csv) as f:
        header = None
        for line in f:
            if line.startswith("#") or not line.strip():
                continue
            cells = line.strip().split(",")
            if header is None:
                header = cells
                continue
            row = dict(zip(header, cells))
            spheres.append(tuple(float(row[k]) for k in ("x", "y", "z", "radius")))
    if len(spheres) != a.count:
        sys.exit(f"{csv}: {len(spheres)} spheres, expected {a.count}")
    r = spheres[0][3]
    if any(abs(s[3] - r) > 1e-12 * r for s in spheres):
        sys.exit(f"{csv}: the spheres are not all of one radius")
    # the packing scaled the radius: kn = E*r stays KN with E = KN/r
    young = KN / r
    mat = material(a.gamma_n, a.gamma_t).replace(f"young = {KN / RADIUS!r}", f"young = {young!r}")
    write(os.path.join(a.out, "granular.toml"), f"""# granular twin of in.granular (bench/lammps/twin.py): {a.count} beads of radius {r:.6g} m
# settling in a box of 5 walls; linear spring, Coulomb friction, no global damping
[simulation]
dt = {DT!r}
steps = {a.warmup + a.steps}
gravity = [0, 0, {-GRAVITY!r}]
damping = 0
verlet_factor = {SKIN_OVER_R!r}

[materials.bead]
{mat}
[[spheres]]
kind = "file"
file = "spheres.csv"
material = "bead"

[[walls]]
point = [0, 0, 0]
normal = [0, 0, 1]
material = "bead"
[[walls]]
point = [0, 0, 0]
normal = [1, 0, 0]
material = "bead"
[[walls]]
point = [{BASE!r}, 0, 0]
normal = [-1, 0, 0]
material = "bead"
[[walls]]
point = [0, 0, 0]
normal = [0, 1, 0]
material = "bead"
[[walls]]
point = [0, {BASE!r}, 0]
normal = [0, -1, 0]
material = "bead"
""")
    lines = [f"LAMMPS data file: granular twin (bench/lammps/twin.py)", "",
             f"{a.count} atoms", "1 atom types", "",
             f"{-0.1 * BASE!r} {1.1 * BASE!r} xlo xhi",
             f"{-0.1 * BASE!r} {1.1 * BASE!r} ylo yhi",
             f"{-0.1 * BASE!r} {2.0 * height!r} zlo zhi", "", "Atoms # sphere", ""]
    for i, (x, y, z, rad) in enumerate(spheres):
        lines.append(f"{i + 1} 1 {2.0 * rad!r} {DENSITY!r} {x!r} {y!r} {z!r}")
    write(os.path.join(a.out, "data.granular"), "\n".join(lines) + "\n")
    kt = KT_OVER_KN * KN
    law = f"{KN!r} {kt!r} {a.gamma_n!r} {a.gamma_t!r} {XMU!r} 1"
    write(os.path.join(a.out, "in.granular"), f"""# granular twin of granular.toml (bench/lammps/twin.py)
units           si
atom_style      sphere
atom_modify     map array
boundary        f f f
newton          off
comm_modify     vel yes
read_data       data.granular
pair_style      gran/hooke/history {law}
pair_coeff      * *
neighbor        {SKIN_OVER_R * r!r} bin
neigh_modify    delay 0 every 1 check yes
timestep        {DT!r}
fix             integrate all nve/sphere
fix             weight all gravity {GRAVITY!r} vector 0 0 -1
fix             floor all wall/gran hooke/history {law} zplane 0.0 NULL
fix             xwalls all wall/gran hooke/history {law} xplane 0.0 {BASE!r}
fix             ywalls all wall/gran hooke/history {law} yplane 0.0 {BASE!r}
compute         touching all contact/atom
compute         contacts all reduce sum c_touching
thermo_style    custom step atoms ke c_contacts
thermo          {max(a.steps // 4, 1)}
run             {a.warmup}
run             {a.steps}
""")
    print(f"twin written in {a.out}: {a.count} spheres of radius {r:.6g} m, box {BASE} x {BASE} x "
          f"{height:.4f} m, dt {DT}, {a.warmup} + {a.steps} steps")


if __name__ == "__main__":
    main()
