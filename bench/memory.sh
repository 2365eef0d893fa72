#!/bin/bash
# Memory per particle from the peak resident set of two runs of bench/memory_per_particle.lua that
# differ only in their particle count (same grid, same program).
#   bench/memory.sh [SEISMPM] [HEIGHT_SMALL] [HEIGHT_LARGE]
set -euo pipefail
bin=${1:-build/seismpm}
small=${2:-0.2}
large=${3:-0.8}
run() {  # prints "particles peak_kB"
  local log
  log=$(/usr/bin/time -f "peak %M" "$bin" "$(dirname "$0")/memory_per_particle.lua" --set height="$1" 2>&1)
  echo "$(grep -o 'particles [0-9]*' <<<"$log" | cut -d' ' -f2) $(grep -o 'peak [0-9]*' <<<"$log" | cut -d' ' -f2)"
}
read -r n1 k1 < <(run "$small")
read -r n2 k2 < <(run "$large")
echo "height $small m: $n1 particles, peak resident set $k1 kB"
echo "height $large m: $n2 particles, peak resident set $k2 kB"
awk -v n1="$n1" -v k1="$k1" -v n2="$n2" -v k2="$k2" \
  'BEGIN { printf "memory per particle: %.0f bytes (peak resident set difference over particle difference)\n",
           (k2 - k1) * 1024 / (n2 - n1) }'
