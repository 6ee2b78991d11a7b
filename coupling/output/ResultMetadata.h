#pragma once
// The static part of a result file: root attributes (format, version, scene, status) and the
// /particles group. Also what a restart checks before it touches a byte: that the file is a
// tmdem result of the same scene.
#include <hdf5.h>

#include <cstddef>
#include <string>
#include <string_view>

#include "coupling/output/ResultWriter.h"

namespace tmdem::coupling {

inline constexpr const char* kResultFormat = "tmdem-result-1";

// Root attributes with status "running", and /particles/{radius, mass, heat_capacity, material}.
void write_result_metadata(hid_t file, const ResultHeader& header);

// Root attribute "status": "running", "ok", "failed" or "interrupted".
void write_result_status(hid_t file, std::string_view status);

// What an existing result file says about itself.
struct ResultIdentity {
  std::string format;
  std::string scene_toml;
  std::size_t particles = 0;
};
ResultIdentity read_result_identity(hid_t file);

// Replaces the root attribute "scene" (a restart may extend duration and output.*).
void write_result_scene(hid_t file, const std::string& scene_toml);

// Appends a restart's checkpoint time to the root attribute "restart_times" [s] (1-D, one entry
// per restart segment, in order; absent in a run that was never restarted).
void append_result_restart(hid_t file, double checkpoint_time_s);

}  // namespace tmdem::coupling
