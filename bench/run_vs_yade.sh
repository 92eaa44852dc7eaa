#!/usr/bin/env bash
# The tube impact (examples/tube_impact_heavy.toml, fixed dt = 2e-4 s) in flexdem and in YADE
# 2023.02a, one thread each, the same 25 untimed + 725 timed steps; prints both speeds in steps
# per second, their ratio, and the impactor's final vertical velocity in both codes.
#
#   bench/run_vs_yade.sh                 (from anywhere; needs cargo and /usr/bin/yade)
#   REPEATS=5 STEPS=725 WARMUP=25 bench/run_vs_yade.sh
#   FLEXDEM=path/to/flexdem bench/run_vs_yade.sh    (use this binary, do not build)
#
# flexdem runs REPEATS times (its 725 steps last a fraction of a second); the median speed is
# used. Outputs: bench/results/tube_impact_flexdem.csv, bench/results/tube_impact_yade.log.
set -euo pipefail
cd "$(dirname "$0")/.."
STEPS=${STEPS:-725}
WARMUP=${WARMUP:-25}
REPEATS=${REPEATS:-5}
YADE=${YADE:-yade}
mkdir -p bench/results

if [ -z "${FLEXDEM:-}" ]; then
    cargo build --release -p flexdem-cli >&2
    FLEXDEM=./target/release/flexdem
fi
threads=$(printf '1,%.0s' $(seq "$REPEATS")); threads=${threads%,}
csv=bench/results/tube_impact_flexdem.csv
"$FLEXDEM" bench --scene tube_impact --threads "$threads" \
    --warmup "$WARMUP" --steps "$STEPS" --csv "$csv" >&2

# A CSV column of the data rows, by its header name.
column() {
    awk -F, -v name="$1" 'NR == 1 { for (i = 1; i <= NF; i++) if ($i == name) c = i; next }
                          { print $c }' "$csv"
}
median() { sort -g | awk '{ v[NR] = $1 } END { print v[int((NR + 1) / 2)] }'; }
ours=$(column steps_per_s | median)
ours_cpu=$(column steps_per_cpu_s | median)
ours_vz=$(column probe_value | head -n 1)

log=bench/results/tube_impact_yade.log
TUBE_WARMUP=$WARMUP TUBE_STEPS=$STEPS "$YADE" -j 1 -n -x bench/yade/tube_impact.py > "$log" 2>&1 || {
    echo "YADE failed, see $log" >&2
    exit 1
}
theirs=$(awk '$1 == "YADE_STEPS_PER_S" { print $2 }' "$log")
theirs_cpu=$(awk '$1 == "YADE_STEPS_PER_CPU_S" { print $2 }' "$log")
theirs_vz=$(awk '$1 == "YADE_IMPACTOR_VZ" { print $2 }' "$log")

echo "tube impact: 640 PFacets, dt 2e-4 s, $WARMUP + $STEPS steps, 1 thread (machine: $(nproc) cores, load $(cut -d' ' -f1-3 /proc/loadavg))"
printf '%-8s %12s %16s %14s\n' "" "steps/s" "steps/CPU-s" "impactor vz"
printf '%-8s %12.1f %16.1f %+14.4f m/s\n' flexdem "$ours" "$ours_cpu" "$ours_vz"
printf '%-8s %12.1f %16.1f %+14.4f m/s\n' YADE "$theirs" "$theirs_cpu" "$theirs_vz"
awk -v a="$ours" -v b="$theirs" -v c="$ours_cpu" -v d="$theirs_cpu" 'BEGIN {
    printf "%-8s %11.1fx %15.1fx   (flexdem / YADE; target >= 20 with 1 thread)\n", "ratio", a / b, c / d }'
echo "(flexdem: median of $REPEATS runs; steps/CPU-s = steps per second of process CPU time, the"
echo " speed on an idle core: use it when the machine is shared and the two differ)"
