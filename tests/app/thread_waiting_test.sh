#!/bin/sh
# How the program's OpenMP threads wait when the user did not say: libgomp's spin on free cores
# (nothing set) or passive waiting on busy ones (set, and the program started again); a variable the
# user set is kept.
#   thread_waiting_test.sh SEISMPM
set -u
seismpm=$1
policy() { "$@" "$seismpm" -e 'print(os.getenv("OMP_WAIT_POLICY"), os.getenv("GOMP_SPINCOUNT"))'; }
fail() {
  echo "FAIL: $1"
  exit 1
}
# Free or busy (other tests may run beside this one): either default.
got=$(policy env -u OMP_WAIT_POLICY -u GOMP_SPINCOUNT)
echo "$got" | grep -Eqx 'passive.nil|nil.nil' || fail "default policy: $got"
# One core kept busy while a thread for every core is asked for: passive.
sh -c 'while :; do :; done' &
busy=$!
sleep 0.5
got=$(policy env -u OMP_WAIT_POLICY -u GOMP_SPINCOUNT OMP_NUM_THREADS="$(nproc)")
kill "$busy"
[ "$(nproc)" -lt 2 ] || echo "$got" | grep -qx 'passive.nil' || fail "a busy core: $got"
got=$(policy env -u GOMP_SPINCOUNT OMP_WAIT_POLICY=active)
echo "$got" | grep -qx 'active.nil' || fail "the user's OMP_WAIT_POLICY: $got"
got=$(policy env -u OMP_WAIT_POLICY GOMP_SPINCOUNT=5)
echo "$got" | grep -qx 'nil.5' || fail "the user's GOMP_SPINCOUNT: $got"
echo "thread waiting as expected"
