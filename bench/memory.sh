#!/bin/bash
# Memory per particle from the peak resident set of two runs of bench/memory_per_particle.lua that
# differ only in their particle count (same grid, same program).
#   bench/memory.sh [SEISMPM] [HEIGHT_SMALL] [HEIGHT_LARGE]
set -euo pipefail
bin=${1:-build/seismpm}
small=${2:-0.2}
large=${3:-0.8}
command -v /usr/bin/time >/dev/null || { echo "memory.sh: needs /usr/bin/time (Debian package time)" >&2; exit 1; }
run() {  # prints "particles peak_kB", or the run's output and fails
  local log n k
  log=$(/usr/bin/time -f "peak %M" "$bin" "$(dirname "$0")/memory_per_particle.lua" --set height="$1" 2>&1) || {
    echo "$log" >&2
    return 1
  }
  n=$(grep -o 'particles [0-9]*' <<<"$log" | cut -d' ' -f2 || true)
  k=$(grep -o 'peak [0-9]*' <<<"$log" | cut -d' ' -f2 || true)
  if [ -z "$n" ] || [ -z "$k" ]; then
    echo "$log" >&2
    return 1
  fi
  echo "$n $k"
}
r1=$(run "$small")
r2=$(run "$large")
read -r n1 k1 <<<"$r1"
read -r n2 k2 <<<"$r2"
echo "height $small m: $n1 particles, peak resident set $k1 kB"
echo "height $large m: $n2 particles, peak resident set $k2 kB"
awk -v n1="$n1" -v k1="$k1" -v n2="$n2" -v k2="$k2" \
  'BEGIN { printf "memory per particle: %.0f bytes (peak resident set difference over particle difference)\n",
           (k2 - k1) * 1024 / (n2 - n1) }'
