#!/usr/bin/env bash
# `seismpm plot DIR` with the phase options, as a user runs it after a run: --phase dynamic --x
# phase_time draws the shaking's rows on the shaking's clock; a phase the run did not have, a bad axis
# and an unknown option are refused (exit status not 0) with a message naming them; probes.csv holds
# the phase columns and the relative probe's columns.
#   plot_phases_test.sh path/to/seismpm
set -u
bin=$(realpath "$1")
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
failures=0
fail() {
  echo "FAIL $*"
  failures=$((failures + 1))
}

cat > "$dir/run.lua" <<'EOF'
local m = mpm.model{ domain = {{0, 0}, {1, 1}}, cell = 0.1 }
local mat = mpm.material.linear_elastic{ density = 2000, young = 1e6, poisson = 0.3 }
local b = m:body{ name = "soil", material = mat, shape = mpm.shape.rectangle{ 0, 0, 1, 0.5 } }
m:fix{ side = "bottom" }
local base = m:probe{ name = "base", body = b, at = { 0.5, 0.0 } }
m:probe{ name = "crest", body = b, at = { 0.5, 0.5 }, relative_to = base }
m:output{ dir = mpm.out_dir("out/unused"), every = 0.1 }
m:gravity_phase{ damping = 0.7, tolerance = 0.01, max_time = 2 }
m:dynamic_phase{ duration = 0.1 }
EOF
"$bin" --quiet --out "$dir/out" "$dir/run.lua" || fail "the run failed"
head -1 "$dir/out/probes.csv" | grep -q '^time (s),phase,phase_time (s),base.id,' || fail "probes.csv header: $(head -c 80 "$dir/out/probes.csv")"
head -1 "$dir/out/probes.csv" | grep -q 'crest.ux_rel,crest.uy_rel' || fail "no relative columns"
tail -1 "$dir/out/probes.csv" | grep -q '^[0-9.e-]*,dynamic,0.1,' || fail "last row: $(tail -1 "$dir/out/probes.csv" | head -c 60)"

"$bin" plot "$dir/out" uy uy_rel --phase dynamic --x phase_time > "$dir/plot.out" 2>&1 || fail "plot: $(cat "$dir/plot.out")"
grep -q 'probe_uy_rel.png' "$dir/plot.out" || fail "plot output: $(cat "$dir/plot.out")"
grep -q 'time since the dynamic phase began' "$dir/out/probe_uy.svg" || fail "no phase-time axis in probe_uy.svg"
"$bin" plot "$dir/out" ux --x=phase_time > /dev/null 2>&1 || fail "--x=phase_time (the current phase)"

if "$bin" plot "$dir/out" --phase shaking 2> "$dir/err"; then fail "--phase shaking accepted"; fi
grep -q "phase 'shaking'" "$dir/err" || fail "--phase shaking: $(cat "$dir/err")"
if "$bin" plot "$dir/out" --x 2> "$dir/err"; then fail "--x without a value accepted"; fi
grep -q -- "--x needs a value" "$dir/err" || fail "--x: $(cat "$dir/err")"
if "$bin" plot "$dir/out" --y 2 2> "$dir/err"; then fail "--y accepted"; fi
grep -q "unknown option --y" "$dir/err" || fail "--y: $(cat "$dir/err")"

[ "$failures" -eq 0 ] && echo "plot phase options: all checks passed"
exit "$failures"
