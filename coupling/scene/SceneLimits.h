#pragma once
// Bounded resources: a scene whose frame count, step count, particle count or estimated output
// is absurd, or whose particles are so small that mass or heat capacity underflow to 0, is a
// scene error (exit 2, nothing written) that names the key, instead of a run that allocates until
// std::bad_alloc or dies later on "heat capacity 0".
#include <cstdint>
#include <string>
#include <vector>

#include "coupling/scene/Scene.h"

namespace tmdem::coupling {

// What a run of the scene will roughly need: exact frame count, estimated sizes.
struct SceneResources {
  double frames = 0;              // frames in the result file (first at t = 0, last at the end)
  double mechanics_steps = 0;     // dynamic runs: duration / time_step; else 0
  double output_bytes = 0;        // result file + XDMF, contacts estimated at 3 per particle
  double memory_bytes = 0;        // rough peak of the run
};

inline constexpr double kMaxFrames = 1.0e7;
inline constexpr double kMaxMechanicsSteps = 1.0e12;
inline constexpr double kMaxOutputBytes = 1.0e12;  // 1 TB

SceneResources estimate_resources(const Scene& scene);

// Past this estimated output (result file and XDMF) loading adds a warning to Scene::warnings,
// which tmdem check and tmdem run print: legal, but likely unmeant (an hour of heating at the
// default output.interval of 0.1 s writes 36,002 frames: 21 GB for 20,000 spheres).
inline constexpr double kWarnOutputBytes = 1.0e10;  // 10 GB
inline constexpr double kTargetOutputBytes = 1.0e9;  // 1 GB: what the warning's interval gives
// That warning (one sentence, no "warning: " prefix), with the output.interval (1, 2 or 5
// times a power of ten) that brings the estimate to at most target_bytes, or, where the first
// and last frames alone pass it, saying so; empty up to warn_bytes (arguments: for tests).
std::string large_output_warning(const Scene& scene, double warn_bytes = kWarnOutputBytes,
                                 double target_bytes = kTargetOutputBytes);

// Throws SceneError ("SOURCE: KEY: ...") for the first limit the scene exceeds. `origins` names
// each particle's entry ("particle[3]", "generate[0]") for the underflow message; may be empty.
void check_scene_limits(const Scene& scene, const std::vector<std::string>& origins,
                        const std::string& source);

}  // namespace tmdem::coupling
