#pragma once
// A request to give up the mechanics step in progress: a first SIGINT/SIGTERM during a run
// (coupling/run/Interruption.h) raises it, the contact solvers stop at their next sweep or
// iteration (GaussSeidelSweep.h, InteriorPointSolver.cpp, ApgdSolver.cpp; nncg_ipm does not
// fall back), and NscdIntegrator::step puts the state back to the step's start and returns a
// report marked `interrupted` (StepReport). The run then writes its last frame and checkpoint
// at the end of the last whole step, so a restart from it is bit for bit the run that never
// stopped.
//
// Why: the signal used to be honoured between steps only, and one step can last minutes (a
// step of 10,000 sweeps retaken in up to 8 parts; an interior-point solve of a piston on
// 1,500 spheres that ran on for 11 minutes after `timeout` sent SIGTERM).
//
// Armed only where the caller handles an interrupted step (the run and the conductivity
// study): elsewhere a request does nothing, and every step is finished.

namespace tmdem::mechanics {

// While disarmed (the default), request_step_interrupt() does nothing.
void arm_step_interrupt(bool armed) noexcept;
// Async-signal-safe (lock-free atomics): called from a signal handler.
void request_step_interrupt() noexcept;
// Drops a request (a new run starts with none).
void clear_step_interrupt() noexcept;
// Whether the step in progress is to be given up.
bool step_interrupt_requested() noexcept;

}  // namespace tmdem::mechanics
