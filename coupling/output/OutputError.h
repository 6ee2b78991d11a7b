#pragma once
// A file could not be written or read (result file, XDMF, run summary, checkpoint). The program
// maps it to exit code 4. The message always names the file, e.g.
//   cannot create result file 'out/r.h5': folder 'out' does not exist
#include <stdexcept>

namespace tmdem::coupling {

struct OutputError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

}  // namespace tmdem::coupling
