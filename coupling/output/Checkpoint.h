#pragma once
// Restart checkpoints (HDF5, root attribute format = "tmdem-checkpoint-1").
//
// Layout: root attributes format, version, scene (TOML text), time_s, boundary_heat_J,
// frames_written; datasets (each with a "units" attribute) /position [N,3] m,
// /velocity [N,3] m/s, /angular_velocity [N,3] rad/s, /temperature [N] K,
// /contacts/pair [C,2] int64, /contacts/impulse [C,3] N s, /contacts/tangential_force [C,3] N,
// /extra/<name> scalar double. A checkpoint without tangential_force (written before it
// existed) reads as tangential force 0.
//
// write_checkpoint writes PATH.tmp, flushes it to disk and renames it to PATH: PATH is either the
// previous checkpoint or the new one, never a partial file. On failure PATH.tmp is removed.
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "coupling/output/OutputError.h"

namespace tmdem::coupling {

struct CheckpointState {
  double time_s = 0.0;
  std::vector<double> position_m;                    // N*3, xyz interleaved
  std::vector<double> velocity_m_per_s;              // N*3
  std::vector<double> angular_velocity_rad_per_s;    // N*3
  std::vector<double> temperature_K;                 // N
  double boundary_heat_J = 0.0;                      // since t = 0
  std::string scene_toml;                            // resolved scene
  std::int64_t frames_written = 0;                   // frames in the result file so far
  std::vector<std::int64_t> contact_pair;            // C*2, as in the result file
  std::vector<double> contact_impulse_N_s;           // C*3, last reactions (mechanics warm
                                                     // start; frame as the solver stores it)
  std::vector<double> contact_tangential_force_N;    // C*3, xyz on i, as in the result file
  std::map<std::string, double> extra;               // free-form named scalars for the run loop
};

// Throws std::invalid_argument if the vector lengths disagree, OutputError naming the path if
// the file cannot be written.
void write_checkpoint(const std::string& path, const CheckpointState& state);

// Throws OutputError naming the path if the file is missing, unreadable, not a
// tmdem-checkpoint-1 file or inconsistent.
CheckpointState read_checkpoint(const std::string& path);

}  // namespace tmdem::coupling
