#pragma once
// How many OpenMP threads a run takes and how idle threads wait, when the user has not said.
//
// The parallel loops of the mechanics meet at a barrier a few times per Gauss-Seidel sweep
// (ContactSlabs.h): a 10^4 bed's sweep is a few milliseconds, so a thread's wait at a barrier
// is tens to hundreds of microseconds. Threads that sleep at once (OMP_WAIT_POLICY=passive)
// then spend more time being woken than working: on the 2-core development machine the first
// 30 steps of a 10^4 pour took 6.4 s at 2 passive threads against 3.8 s at 1 and 2.4 s at 2
// spinning ones (docs/mechanics.md "Threads"). Threads that spin take the core a busy machine's
// other job needs, and a barrier then waits for a thread the scheduler put aside (2.2x slower
// than 1 thread with one core busy). So, when unset:
//   - the threads: one per idle core, the cores less the 1-minute load average (at least 1);
//   - the wait: libgomp's spin then sleep, its spin bounded to kSpinCount (libgomp's own
//     default, 300,000 spins, is milliseconds).
// libgomp reads OMP_WAIT_POLICY and GOMP_SPINCOUNT once, when it is loaded, so the program
// sets GOMP_SPINCOUNT and starts itself again before doing anything else.

namespace tmdem::coupling {

inline constexpr const char* kSpinCount = "10000";

// When OMP_WAIT_POLICY and GOMP_SPINCOUNT are both unset: sets GOMP_SPINCOUNT to kSpinCount and
// re-executes this program with the same arguments (the file /proc/self/exe names; same
// process id); then, when OMP_NUM_THREADS is unset, takes one thread per idle core
// (idle_cores()). Returns when nothing more is to be done or the re-execution failed (the run
// goes on with libgomp's defaults, which is only slower). A user's own settings are kept.
// Under mpirun: no re-execution (the re-executed process could not join the MPI job; mpirun's
// -x GOMP_SPINCOUNT=10000 sets the spin) and one thread per process unless OMP_NUM_THREADS.
void settle_openmp_defaults(char** argv);

// The cores less the 1-minute load average (/proc/loadavg), rounded; at least 1.
int idle_cores();
// The same from given figures: cores - round(load), within [1, cores]; cores when the load is
// not a number >= 0.
int idle_cores(int cores, double load);

}  // namespace tmdem::coupling
