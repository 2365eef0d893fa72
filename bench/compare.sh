#!/bin/bash
# Old binary beside new, in one sitting: ROUNDS interleaved rounds of both benches (each its own
# medians), then the median over rounds per case, and the new/old ratio.
#   bench/compare.sh OLD_BENCH NEW_BENCH [ROUNDS] [-- seismpm_bench options]
# Writes the old medians to bench/baseline.txt's format in $OUT (default /tmp/seismpm_compare).
set -euo pipefail
export LC_ALL=C  # sort and join agree on the order of the keys
old=$1 new=$2
shift 2
rounds=3
if [[ ${1:-} =~ ^[0-9]+$ ]]; then
  rounds=$1
  shift
fi
[ "${1:-}" = "--" ] && shift
out=${OUT:-/tmp/seismpm_compare}
mkdir -p "$out"
rm -f "$out"/old_* "$out"/new_*  # an earlier comparison's rounds must not count
for r in $(seq 1 "$rounds"); do
  "$old" "$@" --save "$out/old_$r.txt" >"$out/old_$r.log"
  "$new" "$@" --save "$out/new_$r.txt" >"$out/new_$r.log"
  echo "round $r of $rounds done" >&2
done
# Median and best over rounds of each "case particles threads" key: the median is the figure; the
# best shows what the machine gives when nothing else runs (a shared VM can halve a 2-thread run).
medians() {
  grep -hv '^#' "$@" | sort -k1,1 -k2,2n -k3,3n -k4,4g |
    awk '{ k = $1 " " $2 " " $3; n[k]++; v[k, n[k]] = $4 }
         END { for (k in n) print k, v[k, int((n[k] + 1) / 2)], v[k, n[k]] }' | sort
}
medians "$out"/old_*.txt >"$out/old_stats.txt"
medians "$out"/new_*.txt >"$out/new_stats.txt"
cut -d' ' -f1-4 "$out/old_stats.txt" >"$out/old.txt"
printf '%-14s %10s %8s %12s %12s %7s %12s %12s %7s\n' case particles threads "old M/s" "new M/s" ratio \
  "old best" "new best" ratio
join <(awk '{print $1"/"$2"/"$3, $4, $5}' "$out/old_stats.txt") \
  <(awk '{print $1"/"$2"/"$3, $4, $5}' "$out/new_stats.txt") |
  awk '{ split($1, k, "/");
         printf "%-14s %10s %8s %12.3f %12.3f %6.2fx %12.3f %12.3f %6.2fx\n", k[1], k[2], k[3],
                $2 / 1e6, $4 / 1e6, $4 / $2, $3 / 1e6, $5 / 1e6, $5 / $3 }'
echo "old medians (a baseline for --baseline): $out/old.txt"
