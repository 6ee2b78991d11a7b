#include "coupling/output/Checkpoint.h"

#include <fcntl.h>
#include <unistd.h>

#include <filesystem>
#include <stdexcept>
#include <system_error>

#include "coupling/output/Hdf5ErrorSilence.h"
#include "coupling/output/Hdf5Io.h"

#ifndef TMDEM_VERSION
#define TMDEM_VERSION "0.1.0"
#endif

namespace tmdem::coupling {
namespace {

constexpr const char* kCheckpointFormat = "tmdem-checkpoint-1";

// Makes the written bytes durable before the rename (best effort).
void sync_file(const std::string& path) {
  const int fd = ::open(path.c_str(), O_RDONLY);
  if (fd < 0) return;
  ::fsync(fd);
  ::close(fd);
}

// The candidate datasets hold one entry per candidate pair (K): candidate_pair 2 K values,
// candidate_force_N 3 K, candidate_rolling_torque_Nm 3 K or none, candidate_held_overlap_m K or
// none; and detector_reference_position_m 3 N values (n particles) or none. Checked on writing
// and on reading alike.
bool candidate_counts_agree(const CheckpointState& s, std::size_t n) {
  const std::size_t k = s.candidate_pair.size() / 2;
  return s.candidate_pair.size() % 2 == 0 && s.candidate_force_N.size() == 3 * k &&
         (s.candidate_rolling_torque_Nm.empty() || s.candidate_rolling_torque_Nm.size() == 3 * k) &&
         (s.candidate_held_overlap_m.empty() || s.candidate_held_overlap_m.size() == k) &&
         (s.detector_reference_position_m.empty() || s.detector_reference_position_m.size() == 3 * n);
}

// A settle checkpoint's window: as many pairs (2 values each) and forces as its snapshots'
// counts add up to, none of them negative.
bool settle_window_agrees(const CheckpointState& s) {
  std::int64_t contacts = 0;
  for (const std::int64_t k : s.settle_window_contacts) {
    if (k < 0) return false;
    contacts += k;
  }
  return s.settle_window_pair.size() == 2 * std::size_t(contacts) &&
         s.settle_window_normal_force_N.size() == std::size_t(contacts);
}

void write_contents(hid_t file, const CheckpointState& s) {
  hdf5::write_string_attribute(file, "format", kCheckpointFormat);
  hdf5::write_string_attribute(file, "version", TMDEM_VERSION);
  hdf5::write_string_attribute(file, "scene", s.scene_toml);
  hdf5::write_double_attribute(file, "time_s", s.time_s);
  hdf5::write_double_attribute(file, "boundary_heat_J", s.boundary_heat_J);
  hdf5::write_int64_attribute(file, "frames_written", s.frames_written);
  hdf5::write_array(file, "position", s.position_m, 3, "m");
  hdf5::write_array(file, "velocity", s.velocity_m_per_s, 3, "m/s");
  hdf5::write_array(file, "angular_velocity", s.angular_velocity_rad_per_s, 3, "rad/s");
  hdf5::write_array(file, "temperature", s.temperature_K, 0, "K");
  Hdf5Handle contacts = hdf5::create_group(file, "contacts");
  hdf5::write_array(contacts.get(), "pair", s.contact_pair, 2, "1");
  hdf5::write_array(contacts.get(), "impulse", s.contact_impulse_N_s, 3, "N s");
  std::vector<double> tangential = s.contact_tangential_force_N;
  tangential.resize(3 * (s.contact_pair.size() / 2), 0.0);
  hdf5::write_array(contacts.get(), "tangential_force", tangential, 3, "N");
  if (!s.contact_normal_force_N.empty())
    hdf5::write_array(contacts.get(), "normal_force", s.contact_normal_force_N, 0, "N");
  if (s.has_mechanics) {
    Hdf5Handle mechanics = hdf5::create_group(file, "mechanics");
    hdf5::write_double_attribute(mechanics.get(), "margin_m", s.detector_margin_m);
    hdf5::write_double_attribute(mechanics.get(), "wall_margin_m", s.detector_wall_margin_m);
    hdf5::write_int64_attribute(mechanics.get(), "rebuilds", s.detector_rebuilds);
    hdf5::write_array(mechanics.get(), "reference_position", s.detector_reference_position_m, 3, "m");
    hdf5::write_array(mechanics.get(), "candidate_pair", s.candidate_pair, 2, "1");
    hdf5::write_array(mechanics.get(), "candidate_force", s.candidate_force_N, 3, "N");
    hdf5::write_array(mechanics.get(), "solver_state", s.contact_solver_state, 0, "1");
    if (!s.candidate_rolling_torque_Nm.empty())
      hdf5::write_array(mechanics.get(), "candidate_rolling_torque", s.candidate_rolling_torque_Nm, 3, "N m");
    if (!s.candidate_held_overlap_m.empty())
      hdf5::write_array(mechanics.get(), "candidate_held_overlap", s.candidate_held_overlap_m, 0, "m");
    if (!s.wall_point_m.empty()) {
      hdf5::write_array(mechanics.get(), "wall_point", s.wall_point_m, 3, "m");
      hdf5::write_array(mechanics.get(), "wall_velocity", s.wall_velocity_m_per_s, 0, "m/s");
      hdf5::write_array(mechanics.get(), "reference_wall_point", s.detector_reference_wall_point_m, 3, "m");
    }
  }
  if (s.settling) {
    Hdf5Handle settle = hdf5::create_group(file, "settle");
    hdf5::write_array(settle.get(), "window_contacts", s.settle_window_contacts, 0, "1");
    hdf5::write_array(settle.get(), "window_pair", s.settle_window_pair, 2, "1");
    hdf5::write_array(settle.get(), "window_normal_force", s.settle_window_normal_force_N, 0, "N");
  }
  if (!s.settled_wall_point_m.empty())
    hdf5::write_array(file, "settled_wall_point", s.settled_wall_point_m, 3, "m");
  if (!s.radius_m.empty()) hdf5::write_array(file, "radius", s.radius_m, 0, "m");
  if (!s.thermal_pattern_pair.empty()) {
    Hdf5Handle thermal = hdf5::create_group(file, "thermal");
    hdf5::write_array(thermal.get(), "pattern_pair", s.thermal_pattern_pair, 2, "1");
  }
  if (!s.result_contact_tail.empty()) {
    const ContactTail& t = s.result_contact_tail;
    Hdf5Handle tail = hdf5::create_group(file, "result_contact_tail");
    hdf5::write_int64_attribute(tail.get(), "start", t.start);
    hdf5::write_int64_attribute(tail.get(), "rows", t.rows);
    if (!t.pair.empty()) hdf5::write_array(tail.get(), "pair", t.pair, 2, "1");
    if (!t.normal_force_N.empty()) hdf5::write_array(tail.get(), "normal_force", t.normal_force_N, 0, "N");
    if (!t.tangential_force_N.empty())
      hdf5::write_array(tail.get(), "tangential_force", t.tangential_force_N, 3, "N");
    if (!t.conductance_W_per_K.empty())
      hdf5::write_array(tail.get(), "conductance", t.conductance_W_per_K, 0, "W/K");
    if (!t.heat_flow_W.empty()) hdf5::write_array(tail.get(), "heat_flow", t.heat_flow_W, 0, "W");
  }
  Hdf5Handle extra = hdf5::create_group(file, "extra");
  for (const auto& [name, value] : s.extra) {
    Hdf5Handle space(hdf5::check_id(H5Screate(H5S_SCALAR), name), H5Sclose);
    Hdf5Handle d(hdf5::check_id(H5Dcreate2(extra.get(), name.c_str(), H5T_IEEE_F64LE,
                                           space.get(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
                                name),
                 H5Dclose);
    hdf5::check_ok(H5Dwrite(d.get(), H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, &value),
                   name);
  }
}

herr_t collect_name(hid_t, const char* name, const H5L_info_t*, void* data) {
  static_cast<std::vector<std::string>*>(data)->push_back(name);
  return 0;
}

CheckpointState read_contents(hid_t file) {
  CheckpointState s;
  std::string format;
  if (!hdf5::read_string_attribute(file, "format", format) || format != kCheckpointFormat) {
    throw Hdf5Failure(std::string("not a ") + kCheckpointFormat + " file");
  }
  auto require = [](bool present, const char* name) {
    if (!present) throw Hdf5Failure(std::string("attribute '") + name + "' is missing");
  };
  require(hdf5::read_string_attribute(file, "scene", s.scene_toml), "scene");
  require(hdf5::read_double_attribute(file, "time_s", s.time_s), "time_s");
  require(hdf5::read_double_attribute(file, "boundary_heat_J", s.boundary_heat_J),
          "boundary_heat_J");
  require(hdf5::read_int64_attribute(file, "frames_written", s.frames_written), "frames_written");
  s.position_m = hdf5::read_double_array(file, "position", 3);
  s.velocity_m_per_s = hdf5::read_double_array(file, "velocity", 3);
  s.angular_velocity_rad_per_s = hdf5::read_double_array(file, "angular_velocity", 3);
  s.temperature_K = hdf5::read_double_array(file, "temperature", 0);
  Hdf5Handle contacts = hdf5::open_group(file, "contacts");
  s.contact_pair = hdf5::read_int64_array(contacts.get(), "pair", 2);
  s.contact_impulse_N_s = hdf5::read_double_array(contacts.get(), "impulse", 3);
  if (hdf5::exists(contacts.get(), "tangential_force")) {
    s.contact_tangential_force_N = hdf5::read_double_array(contacts.get(), "tangential_force", 3);
  } else {
    s.contact_tangential_force_N.assign(3 * (s.contact_pair.size() / 2), 0.0);
  }
  if (hdf5::exists(contacts.get(), "normal_force"))
    s.contact_normal_force_N = hdf5::read_double_array(contacts.get(), "normal_force", 0);
  if (hdf5::exists(file, "mechanics")) {
    Hdf5Handle mechanics = hdf5::open_group(file, "mechanics");
    s.has_mechanics = true;
    auto require_attribute = [](bool present, const char* name) {
      if (!present) throw Hdf5Failure(std::string("attribute 'mechanics/") + name + "' is missing");
    };
    require_attribute(hdf5::read_double_attribute(mechanics.get(), "margin_m", s.detector_margin_m),
                      "margin_m");
    // Absent in checkpoints older than it: 0, read as margin_m (ContactDetector::restore).
    if (!hdf5::read_double_attribute(mechanics.get(), "wall_margin_m", s.detector_wall_margin_m))
      s.detector_wall_margin_m = 0.0;
    require_attribute(hdf5::read_int64_attribute(mechanics.get(), "rebuilds", s.detector_rebuilds),
                      "rebuilds");
    s.detector_reference_position_m = hdf5::read_double_array(mechanics.get(), "reference_position", 3);
    s.candidate_pair = hdf5::read_int64_array(mechanics.get(), "candidate_pair", 2);
    s.candidate_force_N = hdf5::read_double_array(mechanics.get(), "candidate_force", 3);
    if (hdf5::exists(mechanics.get(), "candidate_rolling_torque"))
      s.candidate_rolling_torque_Nm = hdf5::read_double_array(mechanics.get(), "candidate_rolling_torque", 3);
    if (hdf5::exists(mechanics.get(), "candidate_held_overlap"))
      s.candidate_held_overlap_m = hdf5::read_double_array(mechanics.get(), "candidate_held_overlap", 0);
    if (hdf5::exists(mechanics.get(), "solver_state"))
      s.contact_solver_state = hdf5::read_double_array(mechanics.get(), "solver_state", 0);
    if (hdf5::exists(mechanics.get(), "wall_point")) {
      s.wall_point_m = hdf5::read_double_array(mechanics.get(), "wall_point", 3);
      s.wall_velocity_m_per_s = hdf5::read_double_array(mechanics.get(), "wall_velocity", 0);
      s.detector_reference_wall_point_m = hdf5::read_double_array(mechanics.get(), "reference_wall_point", 3);
    }
  }
  if (hdf5::exists(file, "settle")) {
    Hdf5Handle settle = hdf5::open_group(file, "settle");
    s.settling = true;
    s.settle_window_contacts = hdf5::read_int64_array(settle.get(), "window_contacts", 0);
    s.settle_window_pair = hdf5::read_int64_array(settle.get(), "window_pair", 2);
    s.settle_window_normal_force_N = hdf5::read_double_array(settle.get(), "window_normal_force", 0);
  }
  if (hdf5::exists(file, "settled_wall_point"))
    s.settled_wall_point_m = hdf5::read_double_array(file, "settled_wall_point", 3);
  if (hdf5::exists(file, "radius")) s.radius_m = hdf5::read_double_array(file, "radius", 0);
  if (hdf5::exists(file, "thermal")) {
    Hdf5Handle thermal = hdf5::open_group(file, "thermal");
    s.thermal_pattern_pair = hdf5::read_int64_array(thermal.get(), "pattern_pair", 2);
  }
  if (hdf5::exists(file, "result_contact_tail")) {
    Hdf5Handle tail = hdf5::open_group(file, "result_contact_tail");
    ContactTail& t = s.result_contact_tail;
    require(hdf5::read_int64_attribute(tail.get(), "start", t.start), "result_contact_tail/start");
    require(hdf5::read_int64_attribute(tail.get(), "rows", t.rows), "result_contact_tail/rows");
    const hid_t g = tail.get();
    if (hdf5::exists(g, "pair")) t.pair = hdf5::read_int64_array(g, "pair", 2);
    if (hdf5::exists(g, "normal_force")) t.normal_force_N = hdf5::read_double_array(g, "normal_force", 0);
    if (hdf5::exists(g, "tangential_force"))
      t.tangential_force_N = hdf5::read_double_array(g, "tangential_force", 3);
    if (hdf5::exists(g, "conductance")) t.conductance_W_per_K = hdf5::read_double_array(g, "conductance", 0);
    if (hdf5::exists(g, "heat_flow")) t.heat_flow_W = hdf5::read_double_array(g, "heat_flow", 0);
  }
  if (hdf5::exists(file, "extra")) {
    Hdf5Handle extra = hdf5::open_group(file, "extra");
    std::vector<std::string> names;
    hdf5::check_ok(H5Literate(extra.get(), H5_INDEX_NAME, H5_ITER_INC, nullptr, collect_name,
                               &names),
                   "group 'extra'");
    for (const std::string& name : names) {
      Hdf5Handle d = hdf5::open_dataset(extra.get(), name.c_str());
      double value = 0.0;
      hdf5::check_ok(H5Dread(d.get(), H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, &value),
                     name);
      s.extra[name] = value;
    }
  }
  return s;
}

}  // namespace

void write_checkpoint(const std::string& path, const CheckpointState& s) {
  const std::size_t n = s.temperature_K.size();
  const std::size_t c = s.contact_pair.size() / 2;
  if (s.position_m.size() != 3 * n || s.velocity_m_per_s.size() != 3 * n ||
      s.angular_velocity_rad_per_s.size() != 3 * n) {
    throw std::invalid_argument(
        "CheckpointState: position_m, velocity_m_per_s and angular_velocity_rad_per_s need 3 N "
        "values (N = temperature_K.size() = " + std::to_string(n) + ")");
  }
  if (s.contact_pair.size() != 2 * c || s.contact_impulse_N_s.size() != 3 * c ||
      (!s.contact_tangential_force_N.empty() && s.contact_tangential_force_N.size() != 3 * c) ||
      (!s.contact_normal_force_N.empty() && s.contact_normal_force_N.size() != c)) {
    throw std::invalid_argument(
        "CheckpointState: contact_pair needs 2 C values, contact_impulse_N_s 3 C, "
        "contact_tangential_force_N 3 C or none and contact_normal_force_N C or none");
  }
  if (s.has_mechanics && !candidate_counts_agree(s, n)) {
    throw std::invalid_argument(
        "CheckpointState: candidate_pair needs 2 K values, candidate_force_N 3 K, "
        "candidate_rolling_torque_Nm 3 K or none, candidate_held_overlap_m K or none and "
        "detector_reference_position_m 3 N or none");
  }
  if (!settle_window_agrees(s)) {
    throw std::invalid_argument(
        "CheckpointState: settle_window_pair needs 2 values and settle_window_normal_force_N one "
        "for each of the settle_window_contacts");
  }
  const std::string temporary = path + ".tmp";
  const std::filesystem::path folder = std::filesystem::path(path).parent_path();
  std::error_code error;
  if (!folder.empty() && !std::filesystem::is_directory(folder, error)) {
    throw OutputError("cannot write checkpoint '" + path + "': folder '" + folder.string() +
                      "' does not exist");
  }
  std::string problem;
  bool created = false;  // PATH.tmp is ours to remove
  {
    Hdf5ErrorSilence silence;
    try {
      // PATH.tmp is private to this writer; HDF5's lock keeps any other writer off it.
      Hdf5Handle file = hdf5::create_file(temporary, true);
      created = true;
      write_contents(file.get(), s);
      if (!file.reset()) hdf5::fail("H5Fclose");
    } catch (const Hdf5Failure& e) {
      problem = e.what();
    }
  }
  if (problem.empty()) {
    sync_file(temporary);
    std::filesystem::rename(temporary, path, error);
    if (error) problem = "cannot rename '" + temporary + "': " + error.message();
  }
  if (!problem.empty()) {
    if (created) std::filesystem::remove(temporary, error);
    throw OutputError("cannot write checkpoint '" + path + "': " + problem);
  }
  if (!folder.empty()) sync_file(folder.string());
}

CheckpointState read_checkpoint(const std::string& path) {
  std::error_code error;
  if (!std::filesystem::is_regular_file(path, error)) {
    throw OutputError("cannot read checkpoint '" + path + "': no such file");
  }
  CheckpointState s;
  try {
    Hdf5ErrorSilence silence;
    Hdf5Handle file = hdf5::open_file(path, false, true);
    s = read_contents(file.get());
  } catch (const Hdf5Failure& e) {
    throw OutputError("cannot read checkpoint '" + path + "': " + e.what());
  }
  const std::size_t n = s.temperature_K.size();
  const std::size_t c = s.contact_pair.size() / 2;
  if (s.position_m.size() != 3 * n || s.velocity_m_per_s.size() != 3 * n ||
      s.angular_velocity_rad_per_s.size() != 3 * n || s.contact_impulse_N_s.size() != 3 * c ||
      s.contact_tangential_force_N.size() != 3 * c ||
      (!s.contact_normal_force_N.empty() && s.contact_normal_force_N.size() != c) ||
      !candidate_counts_agree(s, n) || !settle_window_agrees(s)) {
    throw OutputError("cannot read checkpoint '" + path +
                      "': particle or contact counts of its datasets disagree");
  }
  return s;
}

}  // namespace tmdem::coupling
