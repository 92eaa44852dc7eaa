#!/usr/bin/env bash
# flexdem against YADE 2023.02a on twins of YADE's reference runs (shared/reference/yade): the
# same scene in both codes (mesh, masses, materials, boundary conditions, initial velocities,
# the same FIXED time step: YADE's own, 0.5 * PWaveTimeStep() as the reference scripts set it),
# the same untimed warm-up and timed steps, 1 thread, output off. The runs are interleaved
# (flexdem, YADE, flexdem, YADE, ...; one process at a time) and the medians compared. Per
# scene it prints both codes' time per step (ms, wall and process CPU), steps per CPU-second,
# the ratio YADE time / flexdem time, and a physical check value from both codes.
#
#   bench/run_vs_yade.sh [SCENE ...]      SCENE: tube, membrane20, membrane40, membrane80,
#                                         membrane (the three), net, all (default)
#   REPEATS=3 FLEXDEM=path/to/flexdem YADE=yade bench/run_vs_yade.sh tube
#   (without FLEXDEM it builds target/release/flexdem with cargo)
#   steps: TUBE_WARMUP/TUBE_STEPS (25/5800), MEMBRANE_WARMUP/MEMBRANE_STEPS (50/200),
#          NET_WARMUP/NET_STEPS (6000/20000)
#
# Scenes (flexdem side written by bench/yade/twin.py; YADE side bench/yade/*.py, the reference
# scripts' scene-building code unchanged):
#   tube        tube_impact.py scenario 2 "solid": 640-PFacet tube with the half-step node
#               offset and the mirrored split, the light rigid sphere (0.1121 kg) at 2 m/s,
#               dt 2.587e-5 s; flexdem: bench/scenes/tube_impact_solid_yade.toml (+ .obj).
#               25 + 5800 steps (to t = 0.15 s). Check: the sphere's vz at the end.
#   membraneN   membrane_scaling.py N (20, 40, 80): flat PFacet membrane, N x N nodes, under
#               (N/2)^2 spheres; YADE variants 'noself' (masks: no PFacet-PFacet pairs) and
#               'self'; flexdem always pairs them (it is the twin of 'self'). 50 + 200 steps.
#               Check: vz of the sphere nearest the centre, z of the centre node, kinetic energy.
#   net         net_drop.py: 10 x 10 net of connections, a 4.19 kg sphere dropped on it,
#               damping 0.3; flexdem: bench/scenes/net_drop_yade.toml. 6000 (the fall) + 20000
#               (impact and rebound) steps. Check: the sphere's z and vz at the end.
# What differs between the twins: bench/README.md, "YADE twins".
# Raw results: bench/results/vs_yade_<scene>.csv.
set -euo pipefail
cd "$(dirname "$0")/.."
if [ -z "${FLEXDEM:-}" ]; then
    cargo build --release -p flexdem-cli >&2
    FLEXDEM=./target/release/flexdem
fi
exec python3 bench/yade/run.py --flexdem "$FLEXDEM" --yade "${YADE:-yade}" --repeats "${REPEATS:-3}" "$@"
