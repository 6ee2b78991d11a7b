#include "coupling/output/ResultFrames.h"

#include <algorithm>

#include "coupling/output/Hdf5Io.h"
#include "coupling/output/WallForces.h"

namespace tmdem::coupling {
namespace {

// Rows per chunk of the [F] datasets. Every frame rewrites their last chunk, so they are stored
// unfiltered: a compressed chunk changes size and moves on each rewrite, and a run killed
// mid-rewrite (SIGKILL, power loss) left frames/time unreadable ("inflate() failed") for the
// restart from its last checkpoint. An unfiltered chunk is rewritten in place, its earlier rows
// with the same bytes. 8 kB per chunk, so compression saved little.
constexpr hsize_t kFrameChunk = 1024;
constexpr const char* kGeometryBlocks = "/frames/blocks";  // BlockSeries of shared geometry

}  // namespace

void ResultFrames::create(hid_t file, std::size_t particles, std::size_t walls,
                          bool shared_geometry) {
  const hsize_t n = particles;
  file_ = file;
  Hdf5Handle frames = hdf5::create_group(file, "frames");
  const hid_t g = frames.get();
  time_ = hdf5::create_dataset(g, "time", H5T_IEEE_F64LE, {0}, kFrameChunk, "s", false);
  if (shared_geometry && n > 0) {
    constexpr auto kRow = BlockSeries::Rows::OnePerBlock;
    position_blocks_.create(file, "/frames/position", kGeometryBlocks, H5T_IEEE_F64LE, {n, 3},
                            kRow, "m");
    velocity_blocks_.create(file, "/frames/velocity", kGeometryBlocks, H5T_IEEE_F64LE, {n, 3},
                            kRow, "m/s");
    position_ = hdf5::open_dataset(g, "position");
    velocity_ = hdf5::open_dataset(g, "velocity");
  } else {
    position_ = hdf5::create_dataset(g, "position", H5T_IEEE_F64LE, {0, n, 3}, 1, "m");
    velocity_ = hdf5::create_dataset(g, "velocity", H5T_IEEE_F64LE, {0, n, 3}, 1, "m/s");
  }
  temperature_ = hdf5::create_dataset(g, "temperature", H5T_IEEE_F64LE, {0, n}, 1, "K");
  thermal_energy_ = hdf5::create_dataset(g, "thermal_energy", H5T_IEEE_F64LE, {0}, kFrameChunk, "J", false);
  boundary_heat_ = hdf5::create_dataset(g, "boundary_heat", H5T_IEEE_F64LE, {0}, kFrameChunk, "J", false);
  contact_offset_ =
      hdf5::create_dataset(g, "contact_offset", H5T_STD_I64LE, {0}, kFrameChunk, "1", false);
  if (walls > 0) {
    wall_position_ =
        hdf5::create_dataset(g, "wall_position", H5T_IEEE_F64LE, {0, hsize_t(walls), 3}, 1, "m");
    wall_force_ = hdf5::create_dataset(g, "wall_force", H5T_IEEE_F64LE, {0, hsize_t(walls)}, 1, "N");
  }
  wall_force_N_.assign(walls, 0.0);
  const std::int64_t zero = 0;
  hdf5::write_rows(contact_offset_.get(), 0, 1, &zero, H5T_NATIVE_INT64);
}

void ResultFrames::open(hid_t file) {
  file_ = file;
  position_blocks_.open(file, "/frames/position", kGeometryBlocks, BlockSeries::Rows::OnePerBlock);
  velocity_blocks_.open(file, "/frames/velocity", kGeometryBlocks, BlockSeries::Rows::OnePerBlock);
  time_ = hdf5::open_dataset(file, "/frames/time");
  position_ = hdf5::open_dataset(file, "/frames/position");
  velocity_ = hdf5::open_dataset(file, "/frames/velocity");
  temperature_ = hdf5::open_dataset(file, "/frames/temperature");
  thermal_energy_ = hdf5::open_dataset(file, "/frames/thermal_energy");
  boundary_heat_ = hdf5::open_dataset(file, "/frames/boundary_heat");
  contact_offset_ = hdf5::open_dataset(file, "/frames/contact_offset");
  wall_position_.reset();
  if (hdf5::exists(file, "/frames/wall_position"))
    wall_position_ = hdf5::open_dataset(file, "/frames/wall_position");
  wall_force_.reset();
  if (hdf5::exists(file, "/frames/wall_force")) {
    wall_force_ = hdf5::open_dataset(file, "/frames/wall_force");
    wall_force_N_.assign(hdf5::dataset_dims(wall_force_.get()).at(1), 0.0);
  }
}

std::vector<const Hdf5Handle*> ResultFrames::row_datasets() const {
  std::vector<const Hdf5Handle*> out{&time_,           &position_,      &velocity_,
                                     &temperature_,    &thermal_energy_, &boundary_heat_};
  if (wall_position_.valid()) out.push_back(&wall_position_);
  if (wall_force_.valid()) out.push_back(&wall_force_);
  return out;
}

std::size_t ResultFrames::complete_frames() const {
  hsize_t complete = hdf5::dataset_rows(contact_offset_.get());
  complete = complete == 0 ? 0 : complete - 1;
  for (const Hdf5Handle* d : row_datasets()) complete = std::min(complete, hdf5::dataset_rows(d->get()));
  return complete;
}

std::int64_t ResultFrames::contact_offset(std::size_t frame) const {
  std::int64_t offset = 0;
  hdf5::read_rows(contact_offset_.get(), frame, 1, &offset, H5T_NATIVE_INT64);
  return offset;
}

std::vector<double> ResultFrames::times(std::size_t frames) const {
  std::vector<double> values(frames);
  hdf5::read_rows(time_.get(), 0, frames, values.data(), H5T_NATIVE_DOUBLE);
  return values;
}

void ResultFrames::append(std::size_t index, const FrameView& frame, std::int64_t contact_end) {
  const hsize_t f = index;
  if (position_blocks_.active()) {
    position_blocks_.append(file_, index, frame.position_m.data(), H5T_NATIVE_DOUBLE);
    velocity_blocks_.append(file_, index, frame.velocity_m_per_s.data(), H5T_NATIVE_DOUBLE);
  } else {
    hdf5::write_rows(position_.get(), f, 1, frame.position_m.data(), H5T_NATIVE_DOUBLE);
    hdf5::write_rows(velocity_.get(), f, 1, frame.velocity_m_per_s.data(), H5T_NATIVE_DOUBLE);
  }
  hdf5::write_rows(temperature_.get(), f, 1, frame.temperature_K.data(), H5T_NATIVE_DOUBLE);
  hdf5::write_rows(thermal_energy_.get(), f, 1, &frame.thermal_energy_J, H5T_NATIVE_DOUBLE);
  hdf5::write_rows(boundary_heat_.get(), f, 1, &frame.boundary_heat_J, H5T_NATIVE_DOUBLE);
  hdf5::write_rows(contact_offset_.get(), f + 1, 1, &contact_end, H5T_NATIVE_INT64);
  if (wall_position_.valid())
    hdf5::write_rows(wall_position_.get(), f, 1, frame.wall_point_m.data(), H5T_NATIVE_DOUBLE);
  if (wall_force_.valid()) {
    sum_wall_forces(frame.contact_pair, frame.normal_force_N, wall_force_N_);
    hdf5::write_rows(wall_force_.get(), f, 1, wall_force_N_.data(), H5T_NATIVE_DOUBLE);
  }
  hdf5::write_rows(time_.get(), f, 1, &frame.time_s, H5T_NATIVE_DOUBLE);  // last: commits
}

void ResultFrames::cut_back(std::size_t frames) {
  for (const Hdf5Handle* d : {&time_, &temperature_, &thermal_energy_, &boundary_heat_})
    hdf5::set_rows(d->get(), frames);
  if (wall_position_.valid()) hdf5::set_rows(wall_position_.get(), frames);
  if (wall_force_.valid()) hdf5::set_rows(wall_force_.get(), frames);
  for (BlockSeries* blocks : {&position_blocks_, &velocity_blocks_})
    if (blocks->active()) blocks->cut_back(file_, frames);
  for (const Hdf5Handle* d : {&position_, &velocity_})
    if (!position_blocks_.active()) hdf5::set_rows(d->get(), frames);
  hdf5::set_rows(contact_offset_.get(), frames + 1);
}

void ResultFrames::close() {
  for (Hdf5Handle* d : {&time_, &position_, &velocity_, &temperature_, &thermal_energy_,
                        &boundary_heat_, &contact_offset_, &wall_position_, &wall_force_}) {
    d->reset();
  }
}

}  // namespace tmdem::coupling
