#!/usr/bin/env bash
# Hostile and broken scenario files through the program, as a user would run them: each must end with a
# Lua error (exit status 1) whose message names the problem, never a crash (a signal, or the sanitizer's
# report in the sanitizer build), never success.
#   hostile_scripts_test.sh path/to/seismpm
set -u
bin=$(realpath "$1")
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
failures=0
# expect NAME PATTERN SCRIPT: runs SCRIPT, wants exit status 1 and PATTERN (grep -E) in its stderr.
expect() {
  local name=$1 pattern=$2 script=$3
  printf '%s\n' "$script" > "$dir/$name.lua"
  (cd "$dir" && timeout 60 "$bin" --quiet "$name.lua") > "$dir/$name.out" 2> "$dir/$name.err"
  local status=$?
  if [ $status -ne 1 ] || ! grep -qE -- "$pattern" "$dir/$name.err"; then
    echo "FAIL $name: exit status $status (want 1), message:"; head -c 2000 "$dir/$name.err"; echo
    failures=$((failures + 1))
  else
    echo "ok   $name: $(grep -E -m1 -- "$pattern" "$dir/$name.err" | head -c 200)"
  fi
}
model='local m = mpm.model{ domain = {{0, 0}, {1, 1}}, cell = 0.1 }'
soil='local soil = mpm.material.linear_elastic{ density = 2000, young = 1e7, poisson = 0.3 }'

expect manual_gc_wrong_type 'model' "$model
getmetatable(m).__gc(42)"
expect manual_gc_then_use 'collected|closed|no longer' "$model
getmetatable(m).__gc(m)
print(m:count())"
expect body_in_history 'during a step|inside a run|while .*step' "$model
$soil
m:body{ name = 'a', shape = mpm.shape.rectangle{ 0.2, 0.2, 0.4, 0.4 }, material = soil }
m:rigid{ name = 'r', shape = mpm.shape.rectangle{ 0.5, 0.5, 0.7, 0.7 },
  velocity = { mpm.history.fn(function(t) m:body{ name = 'b', shape = mpm.shape.rectangle{ 0, 0, 0.1, 0.1 }, material = soil }; return 0 end), 0 } }
m:run{ duration = 0.01 }"
expect history_error 'history|boom' "$model
$soil
m:rigid{ name = 'r', shape = mpm.shape.rectangle{ 0.5, 0.5, 0.7, 0.7 },
  velocity = { mpm.history.fn(function(t) error('boom') end), 0 } }
m:body{ name = 'a', shape = mpm.shape.rectangle{ 0.2, 0.2, 0.4, 0.4 }, material = soil }
m:run{ duration = 0.01 }"
expect coroutine_history 'finished|dead|boom|coroutine|ok-run' "$model
$soil
local h
coroutine.wrap(function() h = mpm.history.fn(function(t) return 0.1 end) end)()
collectgarbage(); collectgarbage()
m:rigid{ name = 'r', shape = mpm.shape.rectangle{ 0.5, 0.5, 0.7, 0.7 }, velocity = { h, 0 } }
m:body{ name = 'a', shape = mpm.shape.rectangle{ 0.2, 0.2, 0.4, 0.4 }, material = soil }
m:run{ duration = 0.01 }
error('ok-run')"
expect bytecode_load "binary chunk" "local f = assert(load(string.dump(function() return 1 end)))"
exit $failures
