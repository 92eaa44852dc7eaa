#!/usr/bin/env bash
# Two flexdem binaries (a commit's and the one before it) timed alternately on the same scene:
# A, B, A, B, ... ROUNDS times each, every run `flexdem bench ARGS` with its CSV kept; then,
# per binary and thread count, the minimum and the median ms/step and contact-stage ms/step
# over the runs, and whether every run's final state has the same checksum. On a shared host
# a run is only ever slowed, so the minimum is the least disturbed figure and the median the
# typical one; runs of one binary are never compared with runs made at another time.
#
#   bench/alternate.sh BIN_A BIN_B ROUNDS BENCH_ARGS...
#   bench/alternate.sh /tmp/flexdem_before target/release/flexdem 8 \
#       --scene packing --sizes 100000 --steps 137 --threads 1,2,2
#
# Give --steps: without it each run picks its own step count from its first timing, and the
# runs then end in different states (different checksums, different contact counts).
set -euo pipefail
[ $# -ge 4 ] || { sed -n '2,13p' "$0" >&2; exit 2; }
a=$1 b=$2 rounds=$3
shift 3
for bin in "$a" "$b"; do
    [ -x "$bin" ] || { echo "not an executable: $bin" >&2; exit 2; }
done
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
for r in $(seq 1 "$rounds"); do
    for side in A B; do
        bin=$a
        [ "$side" = B ] && bin=$b
        "$bin" bench "$@" --csv "$out/$side$r.csv" >"$out/$side$r.log" 2>&1 ||
            { cat "$out/$side$r.log" >&2; echo "run $side $r failed" >&2; exit 1; }
        # side, scene, size, threads, ms/step, contacts ms/step, checksum
        awk -F, -v s="$side" 'NR > 1 { print s, $1, $2, $7, $14, $19, $32 }' \
            "$out/$side$r.csv" >>"$out/all.txt"
    done
done
echo "A = $a"
echo "B = $b"
echo "$rounds rounds, flexdem bench $*"
printf '%-4s %-12s %8s %4s %4s %10s %10s %10s %10s\n' bin scene size thr runs \
    min_ms med_ms cont_min cont_med
# the minimum and the median (the lower middle for an even count) of a column of numbers
stats() { sort -g | awk '{ v[NR] = $1 } END { printf "%10.3f %10.3f", v[1], v[int((NR + 1) / 2)] }'; }
awk '{ print $1, $2, $3, $4 }' "$out/all.txt" | sort -u -k2,2 -k3,3n -k4,4n -k1,1 |
    while read -r side scene size thr; do
        rows=$(awk -v k="$side $scene $size $thr" '$1 " " $2 " " $3 " " $4 == k' "$out/all.txt")
        n=$(printf '%s\n' "$rows" | wc -l)
        ms=$(printf '%s\n' "$rows" | awk '{ print $5 }' | stats)
        cont=$(printf '%s\n' "$rows" | awk '{ print $6 }' | stats)
        printf '%-4s %-12s %8s %4s %4d %s %s\n' "$side" "$scene" "$size" "$thr" "$n" "$ms" "$cont"
    done
sums=$(awk '{ print $2, $3, $7 }' "$out/all.txt" | sort -u | awk '{ print $1, $2 }' | uniq -d)
if [ -n "$sums" ]; then
    echo "checksums differ between runs of: $sums" >&2
    exit 1
fi
echo "every run of a scene ended in the same state (one checksum per scene and size)"
