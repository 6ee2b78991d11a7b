#pragma once
// OpenMP threads that wait at a barrier spin by default (libgomp: up to 300,000 spins before
// sleeping). On a machine whose cores are shared with other jobs, a spinning thread takes the
// core its partner needs to reach the barrier: on the 2-core development machine under load,
// 2-thread contact solves cost 10x the CPU of 1-thread ones (docs/mechanics.md "Threads"). Passive waiting
// (sleep at once) removes that. libgomp reads OMP_WAIT_POLICY once, when it is loaded, so the
// program sets it and starts itself again before doing anything else.

namespace tmdem::coupling {

// When OMP_WAIT_POLICY is unset: sets it to "passive" and re-executes this program with the same
// arguments (/proc/self/exe; same process id). Returns only when nothing was to be done or the
// re-execution failed (the run then goes on with libgomp's default, which is only slower).
// A user's own OMP_WAIT_POLICY is always kept. Not under mpirun (the re-executed process cannot
// join the MPI job): there mpirun's -x OMP_WAIT_POLICY=passive does it.
void prefer_passive_openmp_wait(char** argv);

}  // namespace tmdem::coupling
