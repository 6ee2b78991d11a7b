#pragma once
// A file could not be written or read (result file, XDMF, run summary, checkpoint). The program
// maps it to exit code 4. The message always names the file, e.g.
//   cannot create result file 'out/r.h5': folder 'out' does not exist
#include <stdexcept>

namespace tmdem::coupling {

struct OutputError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// An existing file that must not be touched: a result that exists without --overwrite, or a
// result file that belongs to another scene than the restarted checkpoint. The file is left
// unchanged; the program maps it to exit code 2 (invalid arguments).
struct ResultMismatch : OutputError {
  using OutputError::OutputError;
};

}  // namespace tmdem::coupling
