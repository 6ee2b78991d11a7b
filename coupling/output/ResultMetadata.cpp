#include "coupling/output/ResultMetadata.h"

#include "coupling/output/Hdf5Io.h"

#ifndef TMDEM_VERSION
#define TMDEM_VERSION "0.1.0"
#endif

namespace tmdem::coupling {

void write_result_metadata(hid_t file, const ResultHeader& header) {
  hdf5::write_string_attribute(file, "format", kResultFormat);
  hdf5::write_string_attribute(file, "version", TMDEM_VERSION);
  hdf5::write_string_attribute(file, "scene", header.scene_toml);
  hdf5::write_string_attribute(file, "status", "running");

  Hdf5Handle particles = hdf5::create_group(file, "particles");
  const hid_t p = particles.get();
  hdf5::write_array(p, "radius", header.radius_m, 0, "m");
  hdf5::write_array(p, "mass", header.mass_kg, 0, "kg");
  hdf5::write_array(p, "heat_capacity", header.heat_capacity_J_per_K, 0, "J/K");
  const hsize_t n = header.material.size();
  Hdf5Handle material = hdf5::create_dataset(p, "material", H5T_STD_I32LE, {n}, 0, "1");
  hdf5::write_rows(material.get(), 0, n, header.material.data(), H5T_NATIVE_INT, false);
  if (!header.material_names.empty()) {
    hdf5::write_string_array_attribute(material.get(), "names", header.material_names);
  }
}

void write_result_status(hid_t file, std::string_view status) {
  hdf5::write_string_attribute(file, "status", std::string(status));
}

void write_result_scene(hid_t file, const std::string& scene_toml) {
  hdf5::write_string_attribute(file, "scene", scene_toml);
}

void append_result_restart(hid_t file, double checkpoint_time_s) {
  std::vector<double> times = hdf5::read_double_array_attribute(file, "restart_times");
  times.push_back(checkpoint_time_s);
  hdf5::write_double_array_attribute(file, "restart_times", times);
}

ResultIdentity read_result_identity(hid_t file) {
  ResultIdentity identity;
  hdf5::read_string_attribute(file, "format", identity.format);
  if (identity.format != kResultFormat) return identity;
  hdf5::read_string_attribute(file, "scene", identity.scene_toml);
  Hdf5Handle radius = hdf5::open_dataset(file, "/particles/radius");
  identity.particles = hdf5::dataset_rows(radius.get());
  return identity;
}

}  // namespace tmdem::coupling
