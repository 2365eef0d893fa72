#!/bin/sh
# A run killed with SIGKILL after a periodic checkpoint, restarted from that checkpoint, ends with the
# same files, byte for byte, as the run that was never interrupted: every particle and rigid-body .vtu,
# the .pvd lists, probes.csv and reactions.csv.
#   restart_after_kill_test.sh SEISMPM MODEL.lua WORKDIR OUTPUTS
# OUTPUTS: the output files (particles.pvd entries) the run must also have written before the kill
# (0: kill as soon as the first checkpoint appears). Counted, not timed: a delay in seconds let a fast
# machine finish the run before the kill.
set -u
seismpm=$1
model=$2
work=$3
outputs=$4
full="$work/full"
killed="$work/killed"
rm -rf "$work"
mkdir -p "$work"
export OMP_NUM_THREADS=1

fail() {
  echo "restart_after_kill: $*" >&2
  exit 1
}

"$seismpm" --quiet --set dir="$full" "$model" || fail "the uninterrupted run failed"

"$seismpm" --quiet --set dir="$killed" --set checkpoint_every=0.3 "$model" &
pid=$!
waited=0
while [ ! -e "$killed/checkpoint.chk" ]; do
  kill -0 "$pid" 2>/dev/null || fail "the run ended before its first checkpoint"
  sleep 0.05
  waited=$((waited + 1))
  [ "$waited" -lt 1200 ] || { kill -9 "$pid"; fail "no checkpoint within 60 s"; }
done
written() {
  n=$(grep -c DataSet "$killed/particles.pvd" 2>/dev/null)
  echo "${n:-0}"
}
while [ "$(written)" -lt "$outputs" ]; do
  kill -0 "$pid" 2>/dev/null || fail "the run ended before $outputs output files"
  sleep 0.02
done
kill -0 "$pid" 2>/dev/null || fail "the run ended before the kill: nothing was interrupted (a longer model?)"
kill -9 "$pid"
wait "$pid" 2>/dev/null
echo "killed the run after $(grep -c DataSet "$killed/particles.pvd") of $(grep -c DataSet "$full/particles.pvd") output files"

"$seismpm" --set dir="$killed" --set mode=restart "$model" || fail "the restart failed"

count=0
for f in "$full"/*; do
  name=$(basename "$f")
  cmp -s "$f" "$killed/$name" || fail "$name differs from the uninterrupted run's (or is missing)"
  count=$((count + 1))
done
# A file the killed run was writing when the signal came stays as its temporary (NAME.tmp.PID.N, renamed
# into place only once whole): SIGKILL leaves no chance to remove it, and the kill lands inside a write
# now and then. Those of the killed run's PID are its own; any other extra file is the restart's.
for f in "$killed"/*; do
  name=$(basename "$f")
  case "$name" in *.tmp."$pid".*) continue ;; esac
  [ "$name" = checkpoint.chk ] || [ -e "$full/$name" ] || fail "the restarted run wrote $name, which the uninterrupted one did not"
done
echo "restart_after_kill: $count files identical to the uninterrupted run"
