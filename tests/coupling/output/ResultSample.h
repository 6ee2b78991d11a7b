#pragma once
// What the result-writer tests share (test_output_result_layout.cpp and
// test_output_result_lifecycle.cpp): a sample header and frames of three particles, writing them,
// and reading datasets and attributes back with the HDF5 C++ API.
#include <H5Cpp.h>
#include <gtest/gtest.h>

#include <cstdint>
#include <string>
#include <vector>

#include "coupling/output/ResultWriter.h"

namespace tmdem::coupling::test::result_sample {

using tmdem::coupling::FrameView;
using tmdem::coupling::ResultHeader;
using tmdem::coupling::ResultWriter;

inline constexpr std::size_t kParticles = 3;

inline ResultHeader sample_header() {
  ResultHeader h;
  // Larger than the 64 KiB limit of compact attribute storage, to show the TOML always fits.
  h.scene_toml = "format = \"tmdem-scene-1\"\n# " + std::string(100000, 'x') + "\n";
  h.radius_m = {1e-3, 2e-3, 1.5e-3};
  h.mass_kg = {3.3e-5, 2.6e-4, 1.1e-4};
  h.heat_capacity_J_per_K = {0.015, 0.12, 0.05};
  h.material = {0, 1, 0};
  h.material_names = {"steel", "glass"};
  return h;
}

// Frame f: 2, 3 and 0 contacts; frame 1 has a contact with wall 0 (j = -1).
struct SampleFrame {
  double time_s;
  std::vector<double> position, velocity, temperature;
  std::vector<std::int64_t> pair;
  std::vector<double> force, conductance, tangential;

  FrameView view() const {
    // No heat flows (stored as NaN) and no wall positions (the walls stay where they are).
    return FrameView{.time_s = time_s,
                     .position_m = position,
                     .velocity_m_per_s = velocity,
                     .temperature_K = temperature,
                     .thermal_energy_J = 10.0 * time_s + 1.0,
                     .boundary_heat_J = -0.5 * time_s,
                     .contact_pair = pair,
                     .normal_force_N = force,
                     .conductance_W_per_K = conductance,
                     .tangential_force_N = tangential,
                     .heat_flow_W = {},
                     .wall_point_m = {}};
  }
};

inline SampleFrame sample_frame(std::size_t f) {
  SampleFrame s;
  s.time_s = 0.25 * static_cast<double>(f);
  for (std::size_t i = 0; i < kParticles; ++i) {
    for (std::size_t k = 0; k < 3; ++k) {
      s.position.push_back(static_cast<double>(f) + 0.1 * static_cast<double>(i) +
                           0.01 * static_cast<double>(k));
      s.velocity.push_back(-static_cast<double>(f) - 0.1 * static_cast<double>(i) -
                           0.01 * static_cast<double>(k));
    }
    s.temperature.push_back(300.0 + 10.0 * static_cast<double>(f) + static_cast<double>(i));
  }
  if (f == 0) s.pair = {0, 1, 1, 2};
  if (f == 1) s.pair = {0, 1, 1, 2, 0, -1};
  for (std::size_t c = 0; c < s.pair.size() / 2; ++c) {
    s.force.push_back(100.0 * static_cast<double>(f) + static_cast<double>(c));
    s.conductance.push_back(1e-4 * static_cast<double>(c + 1));
    for (int k = 0; k < 3; ++k) s.tangential.push_back(0.5 * static_cast<double>(f) - k - 0.1 * c);
  }
  return s;
}

// ---- reading helpers (HDF5 C++ API) ----

inline std::vector<hsize_t> dims_of(const H5::DataSet& d) {
  H5::DataSpace space = d.getSpace();
  std::vector<hsize_t> dims(static_cast<std::size_t>(space.getSimpleExtentNdims()));
  space.getSimpleExtentDims(dims.data());
  return dims;
}

inline std::vector<double> read_doubles(const H5::H5File& file, const std::string& name) {
  H5::DataSet d = file.openDataSet(name);
  hsize_t count = 1;
  for (hsize_t n : dims_of(d)) count *= n;
  std::vector<double> values(count);
  if (count > 0) d.read(values.data(), H5::PredType::NATIVE_DOUBLE);
  return values;
}

inline std::vector<std::int64_t> read_int64(const H5::H5File& file, const std::string& name) {
  H5::DataSet d = file.openDataSet(name);
  hsize_t count = 1;
  for (hsize_t n : dims_of(d)) count *= n;
  std::vector<std::int64_t> values(count);
  if (count > 0) d.read(values.data(), H5::PredType::NATIVE_INT64);
  return values;
}

inline std::string string_attribute(const H5::H5Object& object, const std::string& name) {
  H5::Attribute a = object.openAttribute(name);
  std::string value;
  a.read(a.getStrType(), value);
  return value;
}

// In the writing process itself, a second open of a file the ResultWriter holds must use the
// writer's file locking setting (off), else HDF5 refuses with "file locking flag values don't
// match". Other processes need no special setting (see OtherProcessReadsFileWhileRunning).
inline std::string root_attribute(const std::string& path, const std::string& name) {
  H5::FileAccPropList access;
  H5Pset_file_locking(access.getId(), false, true);
  H5::H5File file(path, H5F_ACC_RDONLY, H5::FileCreatPropList::DEFAULT, access);
  return string_attribute(file, name);
}

using Dims = std::vector<hsize_t>;

inline void write_sample(ResultWriter& writer, std::size_t frames) {
  for (std::size_t f = 0; f < frames; ++f) writer.write_frame(sample_frame(f).view());
}

}  // namespace tmdem::coupling::test::result_sample
