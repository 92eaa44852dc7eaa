#!/usr/bin/env bash
# How much faster two threads step a scene than one, measured as a series of paired runs: each
# round one `flexdem bench ... --threads 1,2` (the two runs seconds apart, so a disturbance of
# the host falls on both or on neither, more than between runs minutes apart), preceded by the
# host's memory bandwidth from one and from two threads (`bench/membw.c`, built here) to show
# how loaded the host was, and the round trip of a cache line between the two CPUs
# (`bench/pingpong.c`: under about 150 ns the host has put them on cores that share a cache,
# above on two core complexes, where data the two threads share costs several times more).
# Prints every round (its ratio of the mean steps, and of the median steps), then the median
# and the range of the rounds' ratios, the same for the rounds of each placement, the ratio
# of the minima, how many rounds reached TARGET (default 1.8), and the ratio of the fastest
# steps: the runs at both thread counts take the same steps (the same state at every step),
# so each step's fastest time over the rounds is its time on an undisturbed host, and their
# sum, rebuilds and time-step estimates included, that of an undisturbed run. NEAR_NS
# (default 150) is the round trip that tells the two placements apart.
#
#   bench/scaling.sh BIN ROUNDS BENCH_ARGS...
#   bench/scaling.sh target/release/flexdem 10 --scene packing --sizes 100000 --steps 137
#
# Give --steps: every run then ends in the same state, and the script checks it (one checksum).
set -euo pipefail
[ $# -ge 3 ] || { sed -n '2,19p' "$0" >&2; exit 2; }
bin=$1 rounds=$2
shift 2
[ -x "$bin" ] || { echo "not an executable: $bin" >&2; exit 2; }
target=${TARGET:-1.8}
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
here=$(cd "$(dirname "$0")" && pwd)
cc -O2 -pthread "$here/membw.c" -o "$out/membw"
cc -O2 -pthread "$here/pingpong.c" -o "$out/pingpong"
near=${NEAR_NS:-150}
printf '%5s %12s %12s %6s %10s %10s %7s %9s\n' round 'membw_1 GB/s' 'membw_2 GB/s' rt_ns ms_1thr \
    ms_2thr ratio med_ratio
for r in $(seq 1 "$rounds"); do
    bw1=$("$out/membw" 256 1 | awk '{ print $(NF - 4) }')
    bw2=$("$out/membw" 256 2 | awk '{ print $(NF - 4) }')
    rt=$("$out/pingpong" | awk '{ print $(NF - 4) }')
    "$bin" bench "$@" --threads 1,2 --csv "$out/r$r.csv" --step-times "$out/s$r.csv" \
        >"$out/r$r.log" 2>&1 ||
        { cat "$out/r$r.log" >&2; echo "round $r failed" >&2; exit 1; }
    # threads, ms/step, checksum, median step
    awk -F, 'NR > 1 { print $7, $14, $32, $35 }' "$out/r$r.csv" >"$out/r$r.txt"
    # threads, step, ms
    awk -F, 'NR > 1 { print $3, $4, $5 }' "$out/s$r.csv" >>"$out/steps.txt"
    t1=$(awk '$1 == 1 { print $2 }' "$out/r$r.txt")
    t2=$(awk '$1 == 2 { print $2 }' "$out/r$r.txt")
    awk '{ print $3 }' "$out/r$r.txt" >>"$out/sums.txt"
    ratio=$(awk -v a="$t1" -v b="$t2" 'BEGIN { printf "%.3f", a / b }')
    m1=$(awk '$1 == 1 { print $4 }' "$out/r$r.txt")
    m2=$(awk '$1 == 2 { print $4 }' "$out/r$r.txt")
    med_ratio=$(awk -v a="$m1" -v b="$m2" 'BEGIN { printf "%.3f", a / b }')
    echo "$t1 $t2 $ratio $rt" >>"$out/all.txt"
    printf '%5d %12s %12s %6s %10.3f %10.3f %7s %9s\n' "$r" "$bw1" "$bw2" "$rt" "$t1" "$t2" \
        "$ratio" "$med_ratio"
done
sort -g -k3,3 "$out/all.txt" | awk -v t="$target" '
    { r[NR] = $3; if ($3 >= t) hit++ }
    END {
        printf "ratio over %d rounds: median %.3f, range %.3f-%.3f; %d of %d rounds >= %s\n",
            NR, r[int((NR + 1) / 2)], r[1], r[NR], hit, NR, t
    }'
for side in shared apart; do
    sort -g -k3,3 "$out/all.txt" | awk -v t="$target" -v near="$near" -v side="$side" '
        (side == "shared") == ($4 < near) { r[++n] = $3; if ($3 >= t) hit++ }
        END {
            what = side == "shared" ? "sharing a cache" : "on two core complexes"
            if (n == 0) { printf "rounds with the CPUs %s: none\n", what; exit }
            printf "rounds with the CPUs %s (round trip %s %d ns): %d, median %.3f, %d >= %s\n",
                what, side == "shared" ? "<" : ">=", near, n, r[int((n + 1) / 2)], hit, t
        }'
done
awk 'NR == 1 || $1 < m1 { m1 = $1 } NR == 1 || $2 < m2 { m2 = $2 }
    END { printf "minima: 1 thread %.3f ms, 2 threads %.3f ms, ratio %.3f\n", m1, m2, m1 / m2 }' \
    "$out/all.txt"
awk '{ k = $1 " " $2; if (!(k in m) || $3 < m[k]) m[k] = $3 }
    END {
        for (k in m) { split(k, f, " "); s[f[1]] += m[k]; n[f[1]]++ }
        printf "fastest steps (every step at its fastest over the rounds, summed): 1 thread %.3f ms, ", \
            s[1] / n[1]
        printf "2 threads %.3f ms per step, ratio %.3f\n", s[2] / n[2], s[1] / s[2]
    }' "$out/steps.txt"
if [ "$(sort -u "$out/sums.txt" | wc -l)" -ne 1 ]; then
    echo "the runs ended in different states (checksums differ)" >&2
    exit 1
fi
echo "every run ended in the same state (checksum $(head -1 "$out/sums.txt"))"
