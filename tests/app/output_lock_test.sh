#!/usr/bin/env bash
# Two runs into one output directory, as users start them: the second must stop with an error (exit
# status not 0) that names the lock and the first run's process; the first must finish (exit 0) with
# valid files; once it has ended, the directory is free again.
#   output_lock_test.sh path/to/seismpm
set -u
bin=$(realpath "$1")
dir=$(mktemp -d)
first_pid=
trap '[ -n "$first_pid" ] && kill "$first_pid" 2>/dev/null; rm -rf "$dir"' EXIT
failures=0
fail() {
  echo "FAIL $*"
  failures=$((failures + 1))
}

# The first run: outputs every 0.02 s of model time, a probe and a rigid body whose names need quoting,
# and short runs separated by sleeps, about 4 s in all (sleep, not a busy loop: the cores are shared).
cat > "$dir/first.lua" <<'EOF'
local m = mpm.model{ domain = {{0, 0}, {1, 1}}, cell = 0.05, gravity = {0, 0} }
local soil = mpm.material.linear_elastic{ density = 2000, young = 1e7, poisson = 0.3 }
local b = m:body{ name = "soil", material = soil, shape = mpm.shape.rectangle{ 0.2, 0.2, 0.8, 0.6 } }
m:rigid{ name = 'base "b", 1', shape = mpm.shape.rectangle{ 0.1, 0.05, 0.9, 0.15 } }
m:probe{ name = "crest,1", body = b, at = { 0.5, 0.6 } }
m:output{ dir = mpm.out_dir("out/unused"), every = 0.02 }
for k = 1, 16 do
  m:run{ duration = 0.02 }
  os.execute("sleep 0.25")
end
print("first run done")
EOF
# The second: the same directory named in the script; the third: through --out.
printf 'local m = mpm.model{ domain = {{0, 0}, {1, 1}}, cell = 0.1 }\nm:output{ dir = "%s", every = 0.1 }\nprint("second run got the directory")\n' \
  "$dir/out" > "$dir/second.lua"
printf 'local m = mpm.model{ domain = {{0, 0}, {1, 1}}, cell = 0.1 }\nm:output{ dir = mpm.out_dir("x"), every = 0.1 }\n' > "$dir/third.lua"

"$bin" --quiet --out "$dir/out" "$dir/first.lua" > "$dir/first.out" 2> "$dir/first.err" &
first_pid=$!
for _ in $(seq 1 300); do
  [ -e "$dir/out/particles.pvd" ] && break
  sleep 0.1
done
[ -e "$dir/out/particles.pvd" ] || fail "the first run wrote no particles.pvd in 30 s: $(head -c 500 "$dir/first.err")"

for second in second third; do
  timeout 60 "$bin" --quiet --out "$dir/out" "$dir/$second.lua" > "$dir/$second.out" 2> "$dir/$second.err"
  status=$?
  kill -0 "$first_pid" 2>/dev/null || fail "$second: the first run ended before the check was over (a void check)"
  if [ $status -eq 0 ] || [ $status -ge 124 ]; then
    fail "$second: exit status $status (want an error), output: $(head -c 300 "$dir/$second.out")"
  elif ! grep -q "output directory $dir/out is in use by another seismpm run (process $first_pid, see .*\.seismpm\.lock" \
      "$dir/$second.err"; then
    fail "$second: the message does not name the lock and process $first_pid: $(head -c 500 "$dir/$second.err")"
  else
    echo "ok   $second: exit status $status, $(grep -m1 'in use' "$dir/$second.err" | head -c 300)"
  fi
done

wait "$first_pid"
status=$?
first_pid=
[ $status -eq 0 ] || fail "the first run: exit status $status: $(head -c 500 "$dir/first.err")"
grep -q "first run done" "$dir/first.out" || fail "the first run did not finish its script"

# The first run's files: the .pvd lists every particle file, each one whole; no temporary files left;
# the tables read back by their quoted column names, with a row per output.
out=$dir/out
tail -n 1 "$out/particles.pvd" | grep -q '</VTKFile>' || fail "particles.pvd is not closed"
listed=$(grep -c '<DataSet' "$out/particles.pvd")
on_disk=$(ls "$out" | grep -c '^particles_[0-9]*\.vtu$')
[ "$listed" -eq "$on_disk" ] && [ "$listed" -ge 16 ] || fail "particles.pvd lists $listed files, $on_disk on disk"
for f in "$out"/particles_*.vtu; do
  tail -c 100 "$f" | grep -q '</VTKFile>' || fail "$f is not whole"
done
leftovers=$(ls -A "$out" | grep -c '\.tmp')
[ "$leftovers" -eq 0 ] || fail "temporary files left: $(ls -A "$out" | grep '\.tmp')"
rows=$(( $(wc -l < "$out/reactions.csv") - 1 ))
[ "$rows" -eq "$listed" ] || fail "reactions.csv has $rows rows for $listed outputs"
"$bin" -e "
local p = mpm.history.csv{ file = '$out/probes.csv', time = 'time (s)', value = 'crest,1.uy' }
local r = mpm.history.csv{ file = '$out/reactions.csv', time = 'time (s)', value = 'base \"b\", 1.fy (N/m)' }
assert(p:duration() > 0.3 and r:duration() > 0.3, 'short tables')" > "$dir/read.out" 2>&1 ||
  fail "the tables do not read back: $(head -c 500 "$dir/read.out")"

# The first run has ended: the directory is free.
"$bin" --quiet --out "$out" "$dir/third.lua" > "$dir/again.out" 2> "$dir/again.err" ||
  fail "a run after the first ended was refused: $(head -c 500 "$dir/again.err")"

[ $failures -eq 0 ] && echo "output lock: all checks passed"
exit $failures
