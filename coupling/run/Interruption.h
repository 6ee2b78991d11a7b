#pragma once
// SIGINT / SIGTERM during a run (contract section 1): the first signal only raises a flag; the
// time loop finishes its current step, writes a last frame and a checkpoint, marks the result
// "interrupted" and exits 130 / 143. A second signal aborts at once (the default action), for a
// user who does not want to wait for the step to end; one within a second of the first is the
// same request (`timeout` sends SIGTERM to the command, then to its process group). With give_up_mechanics_step, a mechanics
// step still being solved when the first signal comes is given up instead of finished
// (mechanics/model/StepInterrupt.h): NscdIntegrator::step returns it `interrupted`, with the
// state at its start, and the caller stops there (a step can last minutes).
namespace tmdem::coupling {

class Interruption {
 public:
  // Installs the handlers for the lifetime of this object (one at a time); `quiet` keeps the
  // handler from printing its one-line notice on stderr. `notice`: that line (a string literal,
  // which outlives the handler), or null for a run's.
  explicit Interruption(bool quiet, const char* notice = nullptr, bool give_up_mechanics_step = false);
  ~Interruption();
  Interruption(const Interruption&) = delete;
  Interruption& operator=(const Interruption&) = delete;

  // The signal received (SIGINT or SIGTERM), or 0.
  static int pending();
  // Whether one was: the `stop` a long loop asks after each step (settle_packing, the studies).
  static bool requested() { return pending() != 0; }
};

// "SIGINT" / "SIGTERM".
const char* signal_name(int signal);

}  // namespace tmdem::coupling
