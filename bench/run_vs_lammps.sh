#!/usr/bin/env bash
# flexdem against LAMMPS on the same granular system (bench/lammps/twin.py): equal beads
# settling in a box of 5 walls under gravity, linear spring + Coulomb friction
# (pair gran/hooke/history and fix wall/gran in LAMMPS), the same start state, kn, kt,
# friction, damping, dt, neighbour skin and steps, output off in both, 1 thread.
# The runs are interleaved (flexdem, LAMMPS, flexdem, LAMMPS, ...) and the medians compared.
#
#   bench/run_vs_lammps.sh [COUNT] [STEPS] [REPEATS]     (defaults 16000 2000 3)
#
# Contact damping in both (LAMMPS's gamma_n, gamma_t per unit mass; flexdem's material keys of
# the same names, docs/model.md §7): GAMMA_N and GAMMA_T in the environment, default 5000 and
# 2500 1/s (a restitution of about 0.5 between two beads: damping ratio gamma_n/(2*omega0),
# omega0 = sqrt(kn/m_eff) = 12 400 rad/s); GAMMA_N=0 GAMMA_T=0 runs the undamped law.
#
# Needs LAMMPS's `lmp` (Debian: apt-get install lammps) and python3. Prints the engine time
# per sphere-step of both codes (flexdem: the timed steps of `flexdem bench --scene-file`;
# LAMMPS: the "Loop time" of its timed run) and their ratio.
set -euo pipefail
cd "$(dirname "$0")/.."
count=${1:-16000}
steps=${2:-2000}
repeats=${3:-3}
warmup=200
gamma_n=${GAMMA_N:-5000}
gamma_t=${GAMMA_T:-2500}
out=target/flexdem/bench/lammps_${count}_g${gamma_n}
command -v lmp >/dev/null || { echo "lmp not found: apt-get install lammps" >&2; exit 1; }
cargo build --release -p flexdem-cli >/dev/null
flexdem=$PWD/target/release/flexdem
python3 bench/lammps/twin.py --flexdem "$flexdem" --out "$out" --count "$count" \
    --warmup "$warmup" --steps "$steps" --gamma-n "$gamma_n" --gamma-t "$gamma_t"
fx=(); lx=()
for r in $(seq "$repeats"); do
    line=$(cd "$out" && RAYON_NUM_THREADS=1 "$flexdem" bench --scene-file granular.toml \
        --threads 1 --warmup "$warmup" --steps "$steps" --csv - 2>/dev/null | tail -1)
    f_ms=$(echo "$line" | cut -d, -f14)
    f_contacts=$(echo "$line" | cut -d, -f27)
    fx+=("$f_ms")
    log=$(cd "$out" && OMP_NUM_THREADS=1 lmp -in in.granular -log none -nocite 2>&1)
    l_contacts=$(echo "$log" | awk '/^ +[0-9]+ +[0-9]+ +[-0-9.e+]+ +[0-9]+ *$/ {c=$4} END {print c/2}')
    l_s=$(echo "$log" | grep "Loop time" | tail -1 | awk '{print $4}')
    l_ms=$(python3 -c "print($l_s * 1e3 / $steps)")
    lx+=("$l_ms")
    echo "repeat $r: flexdem $f_ms ms/step ($f_contacts contacts at the end, walls included)," \
        "LAMMPS $l_ms ms/step ($l_contacts sphere-sphere contacts at the end)"
done
python3 - "$count" "${fx[*]}" "${lx[*]}" <<'PY'
import statistics, sys
n = int(sys.argv[1])
f = statistics.median(map(float, sys.argv[2].split()))
l = statistics.median(map(float, sys.argv[3].split()))
print(f"FLEXDEM_NS_PER_SPHERE_STEP {f * 1e6 / n:.1f}")
print(f"LAMMPS_NS_PER_SPHERE_STEP {l * 1e6 / n:.1f}")
print(f"RATIO_FLEXDEM_OVER_LAMMPS {f / l:.2f}")
PY
