// How OpenMP threads wait for work between the parallel loops of a step. Spinning (libgomp's default)
// is fastest on an idle machine and ruinous on a busy one: a thread spinning at a barrier takes the
// core that the thread it waits for, or another program, needs. Sleeping at once (passive) is never
// slower than one thread but gives up most of a second thread's gain on an idle machine. A short spin
// (GOMP_SPINCOUNT=1000, about 30 us) sleeps at every wait longer than that, and on a virtual machine
// each sleep and wake-up cost 50-90 us: the 2-core VM ran the shaking table about a fifth slower
// with it than with libgomp's spin (docs/kernel.md). The program therefore picks by the machine's
// load when it starts: libgomp's default on free cores, passive on busy ones, unless the user chose
// (OMP_WAIT_POLICY or GOMP_SPINCOUNT).
#pragma once

#include <string>

namespace seismpm::app {

// The policy for `threads` threads on `cpus` cores while other programs keep `load` cores busy:
// true for passive waiting (the cores are taken), false for libgomp's spin.
bool wait_passively(double load, int cpus, int threads);

// The share of all cores' time that was taken (not idle) between two first lines of /proc/stat;
// negative when either line is not one.
double busy_fraction(const std::string& before, const std::string& after);

// The cores other programs keep busy now: /proc/stat looked at twice, 150 ms apart, while this
// program is still starting (it takes none of them). Not the load average, which counts a run that
// has just ended for a minute or more: a study of runs one after another would find its own last
// run there and wait passively (20 % slower on two idle cores). The load average where /proc/stat
// cannot be read.
double busy_cores();

// libgomp reads its settings once, when it is loaded, before main() runs: setting them now needs a new
// start of the program. When neither variable is set and the cores are busy, this sets
// OMP_WAIT_POLICY=passive and re-executes the program with the same arguments (once: the variable is
// set the second time). Returns normally when nothing was needed or the re-execution failed (the run
// then goes on with libgomp's default).
void use_default_thread_waiting(char** argv);

}  // namespace seismpm::app
