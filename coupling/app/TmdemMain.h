#pragma once
// The tmdem program (contract section 1) as a library function: `tmdem` calls it from main();
// the test program tmdem_testing registers its test-only heat-transfer modes first and then
// calls it, so tests run the very same command line with extra modes.

namespace tmdem::coupling {

// Parses the command line, runs the command, returns the exit code (contract section 1).
int tmdem_main(int argc, char** argv);

}  // namespace tmdem::coupling
