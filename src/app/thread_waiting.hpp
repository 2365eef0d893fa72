// How OpenMP threads wait for work between the parallel loops of a step. libgomp's default spins for a
// while first, which is fastest on an idle machine and ruinous on a busy one: a thread spinning at a
// barrier takes the core that the thread it waits for needs (measured: see docs/performance.md). The
// program therefore picks its own default unless the user chose one (OMP_WAIT_POLICY or GOMP_SPINCOUNT).
#pragma once

namespace seismpm::app {

// libgomp reads its settings once, when it is loaded, before main() runs: setting them now needs a new
// start of the program. When neither variable is set, this sets the default and re-executes the
// program with the same arguments (once: the variable is set the second time). Returns normally when
// nothing was needed or the re-execution failed (the run then goes on with libgomp's default).
void use_default_thread_waiting(char** argv);

}  // namespace seismpm::app
