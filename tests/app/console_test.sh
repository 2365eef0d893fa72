#!/usr/bin/env bash
# Drives the console through a pipe: multi-line input, expression printing, recovery after an
# error, help; then Ctrl-C during a long run returns to the prompt with the model intact.
#   console_test.sh path/to/seismpm
set -u
bin=$1
fail() { echo "FAIL: $1"; echo "--- output ---"; echo "$out"; exit 1; }
has_line() { grep -qxF -- "$1" <<<"$out" || fail "no line '$1'"; }
has() { grep -qF -- "$1" <<<"$out" || fail "no text '$1'"; }

out=$(printf '%s\n' \
  'x = 1 +' '  2' 'x * 3' \
  'print("hello")' \
  'error("boom")' \
  'x + 1' \
  'for i = 1, 2 do' '  print("loop", i)' 'end' \
  '{1, 2, a = "b"}' \
  'mpm.model{ domain = {{0, 0}, {1, 1}}, cel = 0.1 }' \
  'help(mpm.model)' \
  'm = mpm.model{ domain = {{0, 0}, {1, 1}}, cell = 0.1 }' \
  'm' \
  | "$bin" 2>&1)
status=$?
[ $status -eq 0 ] || fail "exit status $status"
has_line "9"
has_line "hello"
has "stdin:1: boom"
has_line "4"
has_line "loop	1"
has_line "loop	2"
has_line '{1, 2, a = "b"}'
has "unknown key 'cel' (allowed: domain, cell"
has "example: local m = mpm.model{"
has "model: 10 x 10 cells of 0.1 m"

# Ctrl-C during a run: stops at a step boundary, the console goes on, the model is intact.
dir=$(mktemp -d)
mkfifo "$dir/in"
"$bin" <"$dir/in" >"$dir/out" 2>&1 &
pid=$!
exec 3>"$dir/in"
echo 'm = mpm.model{ domain = {{0, 0}, {1, 1}}, cell = 0.01 }' >&3
echo 'mat = mpm.material.linear_elastic{ density = 1000, young = 1e6, poisson = 0.3 }' >&3
echo 'b = m:body{ material = mat, shape = mpm.shape.rectangle{ 0, 0, 1, 0.5 } }' >&3
echo 'm:fix{ side = "bottom" }' >&3
echo 'm:run{ duration = 1000 }' >&3
sleep 2
kill -INT $pid
sleep 1
echo 'print("after", m:steps() > 0, b:count(), m:time() < 1000)' >&3
exec 3>&-
wait $pid
status=$?
out=$(cat "$dir/out")
rm -rf "$dir"
[ $status -eq 0 ] || fail "exit status $status after Ctrl-C"
has "interrupted (Ctrl-C) at t ="
has "the model is intact"
has_line "after	true	20000	true"
# -i: the script's top-level locals are globals at the prompt, those defined before an error when it
# stops on one; a line names them.
dir=$(mktemp -d)
printf 'local m = mpm.model{ domain = {{0, 0}, {1, 1}}, cell = 0.1 }\nlocal k = 2\nerror("half-way")\nlocal late = 1\n' \
  >"$dir/stops.lua"
out=$(printf '%s\n' 'print("kept", k, m:steps(), late)' | "$bin" -i "$dir/stops.lua" 2>&1)
status=$?
[ $status -eq 0 ] || fail "exit status $status with -i"
has "half-way"
has_line "locals kept for the console (those defined before the error): m, k"
has_line "kept	2	0	nil"
rm -rf "$dir"
# Options written after the script (as the scenario headers show them) are options; other words, and
# everything after a lone "--", reach the script in `arg`.
dir=$(mktemp -d)
cat >"$dir/args.lua" <<'LUA'
print("cell", mpm.param("cell", 1), "mode", mpm.param("mode", "none"), "args", table.concat(arg, " "))
LUA
out=$("$bin" "$dir/args.lua" --set cell=0.5 word --set=mode=fast --quiet -- --set x=1 2>&1)
status=$?
[ $status -eq 0 ] || fail "exit status $status with trailing options"
has_line "cell	0.5	mode	fast	args	word --set x=1"
out=$("$bin" "$dir/args.lua" --threads zero 2>&1)
status=$?
[ $status -eq 2 ] || fail "a bad trailing --threads gave exit status $status, not 2"
has "--threads expects a whole number"
rm -rf "$dir"
echo "console test passed"
