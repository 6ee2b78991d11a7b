#pragma once
// An invalid scene or invalid --set override. The program maps it to exit code 2.
// The message always names what is wrong: file, line and column for TOML syntax; the key path
// (e.g. material[1].young_modulus) and the allowed values or range for a bad value; the two
// particle ids for overlapping particles.
#include <stdexcept>

namespace tmdem::coupling {

struct SceneError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

}  // namespace tmdem::coupling
