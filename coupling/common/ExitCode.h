#pragma once
// The program's exit codes (contract section 1), in one place. Everything that returns a code
// for `tmdem` to exit with (the run, the studies, main) uses these names, never the numbers.
namespace tmdem::coupling {

enum ExitCode : int {
  kExitOk = 0,
  kExitInvalid = 2,         // invalid scene or arguments; nothing is written
  kExitSolverFailed = 3,    // a solver failed; the result holds the frames before the failure
  kExitIo = 4,              // input/output error
  kExitSigint = 130,        // interrupted by SIGINT (128 + 2): last frame and checkpoint written
  kExitSigterm = 143,       // interrupted by SIGTERM (128 + 15)
};

}  // namespace tmdem::coupling
