#pragma once
// Restart checkpoints (HDF5, root attribute format = "tmdem-checkpoint-1").
//
// Layout: root attributes format, version, scene (TOML text), time_s, boundary_heat_J,
// frames_written; datasets (each with a "units" attribute) /position [N,3] m,
// /velocity [N,3] m/s, /angular_velocity [N,3] rad/s, /temperature [N] K,
// /contacts/pair [C,2] int64, /contacts/impulse [C,3] N s, /contacts/tangential_force [C,3] N,
// /contacts/normal_force [C] N, /extra/<name> scalar double; for a bitwise restart (docs/restart-and-files.md
// "Restart, interruption and files") also /mechanics (attributes margin_m, wall_margin_m
// (absent in checkpoints older than it: margin_m), rebuilds; datasets
// reference_position [N,3] or [0,3] m, candidate_pair [K,2], candidate_force [K,3] N,
// candidate_rolling_torque [K,3] N m (only with rolling resistance), candidate_held_overlap [K] m
// (only while an imported overlap is held),
// solver_state [S], wall_point [W,3] m, wall_velocity [W] m/s, reference_wall_point [W,3] m:
// the mechanics' MechanicsState; the wall datasets may be absent: walls as built) when the packing moves, and /thermal/pattern_pair [P,2] (a dynamic
// run's sticky edge set), /settle (a settle checkpoint: datasets window_contacts [S],
// window_pair [P,2], window_normal_force [P] N), /settled_wall_point [W,3] m (a settled run: the walls where settling
// left them; absent: where the scene puts them), /result_contact_tail (attributes start, rows;
// datasets pair [T,2], normal_force, tangential_force [T,3], conductance, heat_flow, each
// present when the result file stores it as a plain dataset: ContactTail.h). The integrators' and the mechanics' counters
// are /extra scalars.
// A checkpoint without tangential_force or normal_force (written before they existed) reads as
// tangential force 0 and normal force impulse / time step; without /mechanics or /thermal it
// reads with has_mechanics = false and no pattern.
//
// write_checkpoint writes PATH.tmp, flushes it to disk and renames it to PATH: PATH is either the
// previous checkpoint or the new one, never a partial file. On failure PATH.tmp is removed.
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "coupling/output/ContactTail.h"
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
  std::vector<double> contact_impulse_N_s;           // C*3, normal impulse over one mechanics
                                                     // step, then 0, 0 (older layout; the warm
                                                     // start is candidate_force_N below)
  std::vector<double> contact_tangential_force_N;    // C*3, xyz on i, as in the result file
  std::vector<double> contact_normal_force_N;        // C, as in the result file (a file
                                                     // without it: impulse / time step)
  // The moving mechanics' state (mechanics/integrator/MechanicsState.h), flat.
  bool has_mechanics = false;
  double detector_margin_m = 0.0;
  double detector_wall_margin_m = 0.0;               // 0: detector_margin_m
  std::int64_t detector_rebuilds = 0;
  std::vector<double> detector_reference_position_m; // N*3, or empty: no candidate table yet
  std::vector<std::int64_t> candidate_pair;          // K*2
  std::vector<double> candidate_force_N;             // K*3, global frame, on i
  std::vector<double> candidate_rolling_torque_Nm;   // K*3 or none (no rolling resistance)
  std::vector<double> candidate_held_overlap_m;      // K or none (no overlap held)
  std::vector<double> contact_solver_state;          // the contact solver's carried numbers
  std::vector<double> wall_point_m;                  // W*3, walls' points (pistons move), or empty
  std::vector<double> wall_velocity_m_per_s;         // W, along each wall's normal
  std::vector<double> detector_reference_wall_point_m;  // W*3 at the last rebuild, or empty
  std::vector<std::int64_t> thermal_pattern_pair;    // P*2, dynamic runs
  // W*3, a settled run's walls where settling left them (pistons move), or empty: the scene's.
  std::vector<double> settled_wall_point_m;
  // N, the particles' radii, m: a coupled run's (grown by thermal expansion), or empty: the scene's.
  std::vector<double> radius_m;
  // A settle checkpoint (written when a settle is interrupted, before any frame; group /settle):
  // the packing still settling, with the settle's rest-test window, one snapshot per step,
  // oldest first: snapshot s has settle_window_contacts[s] contacts, whose pairs (2 each) and
  // normal forces (N) follow those of the snapshots before it. The settle's counters are
  // /extra scalars.
  bool settling = false;
  std::vector<std::int64_t> settle_window_contacts;  // S
  std::vector<std::int64_t> settle_window_pair;      // sum * 2
  std::vector<double> settle_window_normal_force_N;  // sum
  // The result file's contacts in their last chunk (ContactTail.h), or empty: a restart writes
  // them again, whatever a crash left of that chunk.
  ContactTail result_contact_tail;
  std::map<std::string, double> extra;               // free-form named scalars for the run loop
};

// Throws std::invalid_argument if the vector lengths disagree, OutputError naming the path if
// the file cannot be written.
void write_checkpoint(const std::string& path, const CheckpointState& state);

// Throws OutputError naming the path if the file is missing, unreadable, not a
// tmdem-checkpoint-1 file or inconsistent.
CheckpointState read_checkpoint(const std::string& path);

}  // namespace tmdem::coupling
