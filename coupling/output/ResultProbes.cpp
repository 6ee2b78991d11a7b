#include "coupling/output/ResultProbes.h"

#include <algorithm>
#include <cmath>

#include "coupling/output/Hdf5ErrorSilence.h"
#include "coupling/output/Hdf5Io.h"
#include "coupling/output/OutputError.h"

namespace tmdem::coupling {
namespace {

// Rows per chunk of the [F, P] datasets; unfiltered like /frames/time (ResultFrames.cpp), so
// that rewriting the last chunk each frame keeps it in place.
constexpr hsize_t kProbeChunk = 256;

Hdf5Handle string_type() {
  Hdf5Handle type(hdf5::check_id(H5Tcopy(H5T_C_S1), "H5Tcopy"), H5Tclose);
  hdf5::check_ok(H5Tset_size(type.get(), H5T_VARIABLE), "H5Tset_size");
  hdf5::check_ok(H5Tset_cset(type.get(), H5T_CSET_UTF8), "H5Tset_cset");
  return type;
}

void write_names(hid_t group, const std::vector<ProbeRegion>& probes) {
  const Hdf5Handle type = string_type();
  Hdf5Handle names = hdf5::create_dataset(group, "names", type.get(), {hsize_t(probes.size())}, 0, "");
  std::vector<const char*> text;
  for (const auto& p : probes) text.push_back(p.name.c_str());
  hdf5::check_ok(H5Dwrite(names.get(), type.get(), H5S_ALL, H5S_ALL, H5P_DEFAULT, text.data()),
                 "dataset /probes/names");
}

std::vector<std::string> read_names(hid_t file) {
  Hdf5Handle names = hdf5::open_dataset(file, "/probes/names");
  const Hdf5Handle type = string_type();
  std::vector<char*> text(hdf5::dataset_rows(names.get()), nullptr);
  hdf5::check_ok(H5Dread(names.get(), type.get(), H5S_ALL, H5S_ALL, H5P_DEFAULT, text.data()),
                 "dataset /probes/names");
  std::vector<std::string> out;
  for (const char* t : text) out.emplace_back(t != nullptr ? t : "");
  Hdf5Handle space(hdf5::check_id(H5Dget_space(names.get()), "/probes/names"), H5Sclose);
  H5Dvlen_reclaim(type.get(), space.get(), H5P_DEFAULT, text.data());
  return out;
}

}  // namespace

bool probe_contains(const ProbeRegion& probe, const double* x) {
  if (probe.radius_m > 0.0) {
    double d2 = 0.0;
    for (int k = 0; k < 3; ++k) d2 += (x[k] - probe.point_m[k]) * (x[k] - probe.point_m[k]);
    return d2 <= probe.radius_m * probe.radius_m;
  }
  for (int k = 0; k < 3; ++k)
    if (std::abs(x[k] - probe.point_m[k]) > 0.5 * probe.box_m[k]) return false;
  return true;
}

ProbeReadings read_probes_of_frame(const std::vector<ProbeRegion>& probes,
                                   std::span<const double> position_m,
                                   std::span<const double> temperature_K) {
  const std::size_t p_count = probes.size();
  ProbeReadings r;
  r.count.assign(p_count, 0);
  r.mean_K.assign(p_count, 0.0);
  r.min_K.assign(p_count, 0.0);
  r.max_K.assign(p_count, 0.0);
  for (std::size_t p = 0; p < p_count; ++p) {
    double sum = 0.0;
    for (std::size_t i = 0; i < temperature_K.size(); ++i) {
      if (!probe_contains(probes[p], &position_m[3 * i])) continue;
      const double t = temperature_K[i];
      if (r.count[p] == 0) {
        r.min_K[p] = r.max_K[p] = t;
      } else {
        r.min_K[p] = std::min(r.min_K[p], t);
        r.max_K[p] = std::max(r.max_K[p], t);
      }
      sum += t;
      ++r.count[p];
    }
    if (r.count[p] > 0) r.mean_K[p] = sum / double(r.count[p]);
  }
  return r;
}

void ResultProbes::create(hid_t file, const std::vector<ProbeRegion>& probes) {
  probes_ = probes;
  if (probes_.empty()) return;
  const hsize_t n = probes_.size();
  Hdf5Handle group = hdf5::create_group(file, "probes");
  const hid_t g = group.get();
  write_names(g, probes_);
  std::vector<double> point, radius, box;
  for (const auto& p : probes_) {
    point.insert(point.end(), p.point_m.begin(), p.point_m.end());
    radius.push_back(p.radius_m);
    box.insert(box.end(), p.box_m.begin(), p.box_m.end());
  }
  hdf5::write_array(g, "point", point, 3, "m");
  hdf5::write_array(g, "radius", radius, 0, "m");
  hdf5::write_array(g, "box", box, 3, "m");
  count_ = hdf5::create_dataset(g, "count", H5T_STD_I64LE, {0, n}, kProbeChunk, "1", false);
  mean_ = hdf5::create_dataset(g, "mean_K", H5T_IEEE_F64LE, {0, n}, kProbeChunk, "K", false);
  min_ = hdf5::create_dataset(g, "min_K", H5T_IEEE_F64LE, {0, n}, kProbeChunk, "K", false);
  max_ = hdf5::create_dataset(g, "max_K", H5T_IEEE_F64LE, {0, n}, kProbeChunk, "K", false);
}

void ResultProbes::open(hid_t file) {
  close();
  probes_.clear();
  if (!hdf5::exists(file, "probes")) return;
  const std::vector<std::string> names = read_names(file);
  const auto point = hdf5::read_double_array(file, "/probes/point", 3);
  const auto radius = hdf5::read_double_array(file, "/probes/radius", 0);
  const auto box = hdf5::read_double_array(file, "/probes/box", 3);
  if (point.size() != 3 * names.size() || radius.size() != names.size() ||
      box.size() != 3 * names.size())
    hdf5::fail("/probes: names, point, radius and box describe different probe counts");
  for (std::size_t p = 0; p < names.size(); ++p) {
    ProbeRegion region;
    region.name = names[p];
    region.radius_m = radius[p];
    for (std::size_t k = 0; k < 3; ++k) {
      region.point_m[k] = point[3 * p + k];
      region.box_m[k] = box[3 * p + k];
    }
    probes_.push_back(region);
  }
  count_ = hdf5::open_dataset(file, "/probes/count");
  mean_ = hdf5::open_dataset(file, "/probes/mean_K");
  min_ = hdf5::open_dataset(file, "/probes/min_K");
  max_ = hdf5::open_dataset(file, "/probes/max_K");
}

void ResultProbes::append(std::size_t index, const FrameView& frame) {
  if (!active()) return;
  const ProbeReadings r = read_probes_of_frame(probes_, frame.position_m, frame.temperature_K);
  const hsize_t f = index;
  hdf5::write_rows(count_.get(), f, 1, r.count.data(), H5T_NATIVE_INT64);
  hdf5::write_rows(mean_.get(), f, 1, r.mean_K.data(), H5T_NATIVE_DOUBLE);
  hdf5::write_rows(min_.get(), f, 1, r.min_K.data(), H5T_NATIVE_DOUBLE);
  hdf5::write_rows(max_.get(), f, 1, r.max_K.data(), H5T_NATIVE_DOUBLE);
}

void ResultProbes::cut_back(std::size_t frames) {
  if (!active()) return;
  for (const Hdf5Handle* d : {&count_, &mean_, &min_, &max_}) hdf5::set_rows(d->get(), frames);
}

void ResultProbes::close() {
  for (Hdf5Handle* d : {&count_, &mean_, &min_, &max_}) d->reset();
}

ProbeSeries read_probe_series(const std::string& path, bool& has_probes) {
  ProbeSeries s;
  has_probes = false;
  try {
    Hdf5ErrorSilence silence;
    Hdf5Handle file = hdf5::open_file(path, false, false);
    if (!hdf5::exists(file.get(), "probes")) return s;
    has_probes = true;
    s.names = read_names(file.get());
    const std::size_t n = s.names.size();
    Hdf5Handle time = hdf5::open_dataset(file.get(), "/frames/time");
    Hdf5Handle count = hdf5::open_dataset(file.get(), "/probes/count");
    Hdf5Handle mean = hdf5::open_dataset(file.get(), "/probes/mean_K");
    Hdf5Handle min = hdf5::open_dataset(file.get(), "/probes/min_K");
    Hdf5Handle max = hdf5::open_dataset(file.get(), "/probes/max_K");
    // The frames complete in /frames/time (written last in each frame; a file still being
    // written may hold probe rows of a frame not yet committed).
    hsize_t frames = hdf5::dataset_rows(time.get());
    for (const Hdf5Handle* d : {&count, &mean, &min, &max})
      frames = std::min(frames, hdf5::dataset_rows(d->get()));
    s.time_s.resize(frames);
    s.count.resize(frames * n);
    s.mean_K.resize(frames * n);
    s.min_K.resize(frames * n);
    s.max_K.resize(frames * n);
    if (frames > 0 && n > 0) {
      hdf5::read_rows(time.get(), 0, frames, s.time_s.data(), H5T_NATIVE_DOUBLE);
      hdf5::read_rows(count.get(), 0, frames, s.count.data(), H5T_NATIVE_INT64);
      hdf5::read_rows(mean.get(), 0, frames, s.mean_K.data(), H5T_NATIVE_DOUBLE);
      hdf5::read_rows(min.get(), 0, frames, s.min_K.data(), H5T_NATIVE_DOUBLE);
      hdf5::read_rows(max.get(), 0, frames, s.max_K.data(), H5T_NATIVE_DOUBLE);
    }
  } catch (const Hdf5Failure& e) {
    throw OutputError("cannot read the probes of result file '" + path + "': " + e.what());
  }
  return s;
}

}  // namespace tmdem::coupling
