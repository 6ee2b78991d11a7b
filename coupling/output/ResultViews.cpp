#include "coupling/output/ResultViews.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <numeric>
#include <string>

#include "coupling/output/Hdf5Io.h"

namespace tmdem::coupling {
namespace {

std::string frame_group(std::size_t frame) { return "/xdmf/frame_" + std::to_string(frame); }

Hdf5Handle simple_space(const std::vector<hsize_t>& dims, bool unlimited_rows = false) {
  std::vector<hsize_t> max_dims = dims;
  if (unlimited_rows) max_dims[0] = H5S_UNLIMITED;
  return Hdf5Handle(hdf5::check_id(H5Screate_simple(int(dims.size()), dims.data(),
                                                    max_dims.data()),
                                   "H5Screate_simple"),
                    H5Sclose);
}

// Selects rows [first, first + count) of a space of shape dims (all other dimensions whole).
void select_rows(hid_t space, const std::vector<hsize_t>& dims, hsize_t first, hsize_t count) {
  std::vector<hsize_t> start(dims.size(), 0), block = dims;
  start[0] = first;
  block[0] = count;
  hdf5::check_ok(H5Sselect_hyperslab(space, H5S_SELECT_SET, start.data(), nullptr,
                                     block.data(), nullptr),
                 "H5Sselect_hyperslab");
}

// One mapping of a virtual dataset: its rows [virtual_first, +virtual_rows) are rows
// [source_first, +source_rows) of `source` (a dataset of this file, shape source_dims with
// unlimited rows). Both selections hold the same number of values: one frame row [1, N, 3] of
// /frames/position fills the N rows of a view [N, 3].
struct Mapping {
  hsize_t virtual_first = 0;
  hsize_t virtual_rows = 0;
  std::string source;
  std::vector<hsize_t> source_dims;
  hsize_t source_first = 0;
  hsize_t source_rows = 0;
};

void create_virtual(hid_t group, const char* name, const std::vector<hsize_t>& dims,
                    const std::vector<Mapping>& mappings, const char* units) {
  const std::string what = std::string("virtual dataset ") + name;
  Hdf5Handle properties(hdf5::check_id(H5Pcreate(H5P_DATASET_CREATE), what), H5Pclose);
  Hdf5Handle space = simple_space(dims);
  for (const Mapping& m : mappings) {
    if (m.virtual_rows == 0) continue;
    Hdf5Handle virtual_space = simple_space(dims);
    select_rows(virtual_space.get(), dims, m.virtual_first, m.virtual_rows);
    Hdf5Handle source_space = simple_space(m.source_dims, true);
    select_rows(source_space.get(), m.source_dims, m.source_first, m.source_rows);
    hdf5::check_ok(H5Pset_virtual(properties.get(), virtual_space.get(), ".", m.source.c_str(),
                                  source_space.get()),
                   what);
  }
  Hdf5Handle dataset(hdf5::check_id(H5Dcreate2(group, name, H5T_IEEE_F64LE, space.get(),
                                               H5P_DEFAULT, properties.get(), H5P_DEFAULT),
                                    what),
                     H5Dclose);
  hdf5::write_string_attribute(dataset.get(), "units", units);
}

// Unit vectors u, v with (u, v, n) right-handed and orthonormal.
void tangents(const double* n, std::array<double, 3>& u, std::array<double, 3>& v) {
  const std::array<double, 3> a = std::abs(n[0]) < 0.9 ? std::array<double, 3>{1, 0, 0}
                                                       : std::array<double, 3>{0, 1, 0};
  u = {a[1] * n[2] - a[2] * n[1], a[2] * n[0] - a[0] * n[2], a[0] * n[1] - a[1] * n[0]};
  const double length = std::sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
  for (double& c : u) c /= length;
  v = {n[1] * u[2] - n[2] * u[1], n[2] * u[0] - n[0] * u[2], n[0] * u[1] - n[1] * u[0]};
}

// The point of `wall` nearest to x: its projection on a plane; on a cylinder, the point at the
// cylinder's radius straight out from the axis through x (any one if x lies on the axis).
std::array<double, 3> foot(const WallPlane& wall, const double* x) {
  const auto& p = wall.point_m;
  const auto& n = wall.normal;
  const double d = (x[0] - p[0]) * n[0] + (x[1] - p[1]) * n[1] + (x[2] - p[2]) * n[2];
  if (!(wall.radius_m > 0.0)) return {x[0] - d * n[0], x[1] - d * n[1], x[2] - d * n[2]};
  const std::array<double, 3> axis = {p[0] + d * n[0], p[1] + d * n[1], p[2] + d * n[2]};
  std::array<double, 3> out = {x[0] - axis[0], x[1] - axis[1], x[2] - axis[2]};
  double length = std::sqrt(out[0] * out[0] + out[1] * out[1] + out[2] * out[2]);
  if (!(length > 0.0)) {
    std::array<double, 3> v;
    tangents(n.data(), out, v);
    length = 1.0;
  }
  for (int k = 0; k < 3; ++k) out[k] = axis[k] + wall.radius_m * out[k] / length;
  return out;
}

// Quads a cylindrical wall is drawn with (a plane: one).
constexpr int kStrips = 32;

// The wall of each quad of /xdmf/walls, in the order draw_walls writes them.
std::vector<std::size_t> quad_walls(const std::vector<WallPlane>& walls) {
  std::vector<std::size_t> out;
  for (std::size_t w = 0; w < walls.size(); ++w) out.insert(out.end(), walls[w].radius_m > 0.0 ? kStrips : 1, w);
  return out;
}

// /xdmf/vertices, and the empty datasets of a frame without contacts (ParaView's Xdmf3 readers
// take a line set of 0 lines; an XML DataItem without content makes them abort).
void create_static_views(hid_t file, std::size_t particles) {
  Hdf5Handle xdmf = hdf5::create_group(file, "xdmf");
  std::vector<std::int64_t> ids(particles);
  std::iota(ids.begin(), ids.end(), std::int64_t{0});
  hdf5::write_array(xdmf.get(), "vertices", ids, 0, "1");
  hdf5::write_array(xdmf.get(), "no_lines", std::vector<std::int64_t>{}, 2, "1");
  hdf5::write_array(xdmf.get(), "no_values", std::vector<double>{}, 0, "1");
  hdf5::write_array(xdmf.get(), "no_vectors", std::vector<double>{}, 3, "1");
}

}  // namespace

void ResultViews::create(hid_t file, std::size_t particles, const std::vector<WallPlane>& walls,
                         const PeriodicBounds& periodic) {
  particles_ = particles;
  walls_ = walls;
  periodic_ = periodic;
  if (periodic.any()) {
    Hdf5Handle box = hdf5::create_group(file, "periodic");
    std::vector<std::int64_t> axis;
    for (const bool a : periodic.axis) axis.push_back(a ? 1 : 0);
    hdf5::write_array(box.get(), "axis", axis, 0, "1");
    hdf5::write_array(box.get(), "low", std::vector<double>(periodic.low_m.begin(), periodic.low_m.end()), 0, "m");
    hdf5::write_array(box.get(), "high", std::vector<double>(periodic.high_m.begin(), periodic.high_m.end()), 0, "m");
  }
  Hdf5Handle group = hdf5::create_group(file, "walls");
  std::vector<double> point, normal, radius, temperature;
  for (const WallPlane& w : walls) {
    point.insert(point.end(), w.point_m.begin(), w.point_m.end());
    normal.insert(normal.end(), w.normal.begin(), w.normal.end());
    radius.push_back(w.radius_m);
    temperature.push_back(w.temperature_K);
  }
  hdf5::write_array(group.get(), "point", point, 3, "m");
  hdf5::write_array(group.get(), "normal", normal, 3, "1");
  hdf5::write_array(group.get(), "radius", radius, 0, "m");
  hdf5::write_array(group.get(), "temperature", temperature, 0, "K");
  create_static_views(file, particles);
}

void ResultViews::open(hid_t file, std::size_t particles) {
  particles_ = particles;
  walls_.clear();
  periodic_ = {};
  if (hdf5::exists(file, "periodic")) {
    Hdf5Handle box = hdf5::open_group(file, "periodic");
    const auto low = hdf5::read_double_array(box.get(), "low", 0);
    const auto high = hdf5::read_double_array(box.get(), "high", 0);
    const auto axis = hdf5::read_int64_array(box.get(), "axis", 0);
    for (std::size_t k = 0; k < 3 && k < axis.size() && k < low.size() && k < high.size(); ++k) {
      periodic_.axis[k] = axis[k] != 0;
      periodic_.low_m[k] = low[k];
      periodic_.high_m[k] = high[k];
    }
  }
  if (hdf5::exists(file, "walls")) {
    Hdf5Handle group = hdf5::open_group(file, "walls");
    const auto point = hdf5::read_double_array(group.get(), "point", 3);
    const auto normal = hdf5::read_double_array(group.get(), "normal", 3);
    const auto temperature = hdf5::read_double_array(group.get(), "temperature", 0);
    const auto radius = hdf5::exists(group.get(), "radius")
                            ? hdf5::read_double_array(group.get(), "radius", 0)
                            : std::vector<double>(temperature.size(), 0.0);
    for (std::size_t w = 0; w < temperature.size(); ++w) {
      WallPlane plane;
      for (int k = 0; k < 3; ++k) {
        plane.point_m[k] = point[3 * w + k];
        plane.normal[k] = normal[3 * w + k];
      }
      plane.radius_m = radius[w];
      plane.temperature_K = temperature[w];
      walls_.push_back(plane);
    }
  }
  if (!hdf5::exists(file, "xdmf")) create_static_views(file, particles);
  wall_quads_ = 0;
  wall_corners_.clear();
  quad_wall_.clear();
  if (hdf5::exists(file, "/xdmf/walls")) {
    Hdf5Handle walls = hdf5::open_group(file, "/xdmf/walls");
    Hdf5Handle quads = hdf5::open_dataset(walls.get(), "quads");
    wall_quads_ = hdf5::dataset_rows(quads.get());
  }
}

bool ResultViews::has_frame(hid_t file, std::size_t frame) const {
  Hdf5Handle xdmf = hdf5::open_group(file, "xdmf");
  return hdf5::exists(xdmf.get(), ("frame_" + std::to_string(frame)).c_str());
}

void ResultViews::draw_walls(hid_t file, std::span<const double> position_m) {
  // Around the particles of this (the first) frame, large enough to hold the whole bed.
  const std::size_t n = particles_;
  std::array<double, 3> lo, hi;
  lo.fill(std::numeric_limits<double>::infinity());
  hi.fill(-std::numeric_limits<double>::infinity());
  for (std::size_t i = 0; i < n; ++i)
    for (int k = 0; k < 3; ++k) {
      lo[k] = std::min(lo[k], position_m[3 * i + k]);
      hi[k] = std::max(hi[k], position_m[3 * i + k]);
    }
  const std::array<double, 3> centre = {(lo[0] + hi[0]) / 2, (lo[1] + hi[1]) / 2,
                                        (lo[2] + hi[2]) / 2};
  const double half = 0.5 * std::sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) +
                                      (hi[1] - lo[1]) * (hi[1] - lo[1]) +
                                      (hi[2] - lo[2]) * (hi[2] - lo[2]));
  double r_max = 0.0;
  if (hdf5::exists(file, "/particles/radius")) {
    Hdf5Handle particles = hdf5::open_group(file, "particles");
    for (double r : hdf5::read_double_array(particles.get(), "radius", 0)) r_max = std::max(r_max, r);
  }
  const double side = std::max(half + 2.0 * r_max, 1e-12);
  std::vector<double> points, temperature;
  std::vector<std::int64_t> quads;
  auto corner = [&](const std::array<double, 3>& x) {
    points.insert(points.end(), x.begin(), x.end());
    quads.push_back(std::int64_t(quads.size()));
  };
  for (const WallPlane& wall : walls_) {
    std::array<double, 3> u, v;
    tangents(wall.normal.data(), u, v);
    const auto& a = wall.normal;
    if (!(wall.radius_m > 0.0)) {
      const auto c = foot(wall, centre.data());
      for (const auto& [s, t] : {std::pair{-1.0, -1.0}, {1.0, -1.0}, {1.0, 1.0}, {-1.0, 1.0}})
        corner({c[0] + side * (s * u[0] + t * v[0]), c[1] + side * (s * u[1] + t * v[1]),
                c[2] + side * (s * u[2] + t * v[2])});
      temperature.push_back(wall.temperature_K);
      continue;
    }
    // A cylinder: 32 strips between the particles' lowest and highest reach along the axis.
    double below = std::numeric_limits<double>::infinity(), above = -below;
    for (std::size_t i = 0; i < n; ++i) {
      double along = 0.0;
      for (int k = 0; k < 3; ++k) along += (position_m[3 * i + k] - wall.point_m[k]) * a[k];
      below = std::min(below, along - 2.0 * r_max);
      above = std::max(above, along + 2.0 * r_max);
    }
    auto at = [&](int strip, double along) {
      const double angle = 2.0 * std::numbers::pi * strip / kStrips;
      const double cu = wall.radius_m * std::cos(angle), cv = wall.radius_m * std::sin(angle);
      return std::array<double, 3>{wall.point_m[0] + along * a[0] + cu * u[0] + cv * v[0],
                                   wall.point_m[1] + along * a[1] + cu * u[1] + cv * v[1],
                                   wall.point_m[2] + along * a[2] + cu * u[2] + cv * v[2]};
    };
    for (int strip = 0; strip < kStrips; ++strip) {
      corner(at(strip, below));
      corner(at(strip + 1, below));
      corner(at(strip + 1, above));
      corner(at(strip, above));
      temperature.push_back(wall.temperature_K);
    }
  }
  Hdf5Handle group = hdf5::create_group(file, "/xdmf/walls");
  hdf5::write_array(group.get(), "points", points, 3, "m");
  hdf5::write_array(group.get(), "quads", quads, 4, "1");
  hdf5::write_array(group.get(), "temperature", temperature, 0, "K");
  wall_quads_ = temperature.size();
  wall_corners_ = std::move(points);
}

bool ResultViews::write_moved_walls(hid_t file, hid_t frame_group, std::span<const double> wall_point_m) {
  if (wall_quads_ == 0 || wall_point_m.size() != 3 * walls_.size()) return false;
  bool moved = false;
  for (std::size_t w = 0; w < walls_.size(); ++w)
    for (int k = 0; k < 3; ++k) moved = moved || wall_point_m[3 * w + k] != walls_[w].point_m[k];
  if (!moved) return false;
  if (quad_wall_.empty()) quad_wall_ = quad_walls(walls_);
  if (wall_corners_.empty()) {
    Hdf5Handle group = hdf5::open_group(file, "/xdmf/walls");
    wall_corners_ = hdf5::read_double_array(group.get(), "points", 3);
  }
  if (quad_wall_.size() != wall_quads_ || wall_corners_.size() != 12 * wall_quads_) return false;
  std::vector<double> corners = wall_corners_;
  for (std::size_t q = 0; q < wall_quads_; ++q) {
    const std::size_t w = quad_wall_[q];
    for (std::size_t c = 4 * q; c < 4 * q + 4; ++c)
      for (int k = 0; k < 3; ++k) corners[3 * c + k] += wall_point_m[3 * w + k] - walls_[w].point_m[k];
  }
  hdf5::write_array(frame_group, "wall_points", corners, 3, "m");
  return true;
}

FrameViewCounts ResultViews::add_frame(hid_t file, std::size_t frame, const FrameView& data,
                                       bool contacts_stored, std::int64_t first_contact) {
  const hsize_t n = particles_;
  const hsize_t f = frame;
  const std::span<const double> position_m = data.position_m;
  const std::span<const std::int64_t> pair =
      contacts_stored ? data.contact_pair : std::span<const std::int64_t>{};
  if (!walls_.empty() && !hdf5::exists(file, "/xdmf/walls")) draw_walls(file, position_m);

  Hdf5Handle group = hdf5::create_group(file, frame_group(frame).c_str());
  const hid_t g = group.get();
  const std::string here = frame_group(frame) + "/";
  auto link = [&](std::size_t source_frame, const char* name) {
    const std::string source = frame_group(source_frame) + "/" + name;
    hdf5::check_ok(H5Lcreate_hard(file, source.c_str(), file, (here + name).c_str(),
                                  H5P_DEFAULT, H5P_DEFAULT),
                   "H5Lcreate_hard " + here + name);
  };
  auto same = [](const auto& kept, const auto& now) {
    return kept.size() == now.size() && std::equal(now.begin(), now.end(), kept.begin());
  };
  // A frozen bed's blocks (BlockSeries.h): the view is the block itself, a hard link.
  auto block = [&](const char* group, const char* name) {
    const std::string path = std::string(group) + "/" + name + "_" + std::to_string(frame);
    return hdf5::exists(file, path.c_str()) ? path : std::string();
  };
  auto link_block = [&](const std::string& source, const char* name) {
    hdf5::check_ok(H5Lcreate_hard(file, source.c_str(), file, (here + name).c_str(), H5P_DEFAULT,
                                  H5P_DEFAULT),
                   "H5Lcreate_hard " + here + name);
  };
  const std::string position_block = block("/frames/blocks", "position");
  const bool complete = data.velocity_m_per_s.size() == 3 * n;  // not a rebuilt view
  const bool geometry_same = previous_.valid && complete &&
                             same(previous_.position, position_m) &&
                             same(previous_.velocity, data.velocity_m_per_s);
  const hsize_t frames = f + 1;
  if (!position_block.empty()) {
    link_block(position_block, "position");
    link_block(block("/frames/blocks", "velocity"), "velocity");
  } else if (geometry_same) {
    link(previous_.geometry_frame, "position");
    link(previous_.geometry_frame, "velocity");
  } else {
    create_virtual(g, "position", {n, 3}, {{0, n, "/frames/position", {frames, n, 3}, f, 1}},
                   "m");
    create_virtual(g, "velocity", {n, 3}, {{0, n, "/frames/velocity", {frames, n, 3}, f, 1}},
                   "m/s");
  }
  create_virtual(g, "temperature", {n}, {{0, n, "/frames/temperature", {frames, n}, f, 1}}, "K");

  FrameViewCounts counts;
  counts.moved_walls = write_moved_walls(file, g, data.wall_point_m);
  counts.contacts = pair.size() / 2;
  const hsize_t c = counts.contacts;
  const hsize_t first = hsize_t(first_contact), rows = first + c;
  const bool contacts_same = geometry_same && c > 0 && same(previous_.pair, pair) &&
                             same(previous_.force, data.normal_force_N) &&
                             same(previous_.conductance, data.conductance_W_per_K) &&
                             same(previous_.tangential, data.tangential_force_N);
  const std::string force_block = block("/contacts/blocks", "normal_force");
  if (contacts_same) {
    counts.wall_contacts = previous_.counts.wall_contacts;
    counts.image_ends = previous_.counts.image_ends;
    for (const char* name : {"contact_lines", "contact_points", "normal_force", "conductance",
                             "tangential_force"})
      link(previous_.contacts_frame, name);
    if (counts.wall_contacts > 0) link(previous_.contacts_frame, "wall_feet");
    if (counts.image_ends > 0) link(previous_.contacts_frame, "image_ends");
  } else if (c > 0) {
    std::vector<std::int64_t> lines(pair.begin(), pair.end());
    std::vector<double> feet;
    for (std::size_t k = 0; k < counts.contacts; ++k) {
      const std::int64_t j = pair[2 * k + 1];
      if (j >= 0) continue;
      const std::size_t i = std::size_t(pair[2 * k]);
      const std::size_t wall = std::size_t(-1 - j);
      // A wall the file does not describe (written before /walls existed): a zero-length line.
      // The foot lies on the wall where it stands in this frame (a piston moves).
      WallPlane here_now = wall < walls_.size() ? walls_[wall] : WallPlane{};
      if (data.wall_point_m.size() == 3 * walls_.size() && wall < walls_.size())
        for (int k = 0; k < 3; ++k) here_now.point_m[k] = data.wall_point_m[3 * wall + k];
      const auto end = wall < walls_.size() ? foot(here_now, &position_m[3 * i])
                                            : std::array<double, 3>{position_m[3 * i],
                                                                    position_m[3 * i + 1],
                                                                    position_m[3 * i + 2]};
      feet.insert(feet.end(), end.begin(), end.end());
      lines[2 * k + 1] = std::int64_t(n + counts.wall_contacts);
      ++counts.wall_contacts;
    }
    // A contact round a periodic boundary ends at the image of j beside i, so that no line
    // spans the box.
    std::vector<double> images;
    if (periodic_.any()) {
      for (std::size_t k = 0; k < counts.contacts; ++k) {
        const std::int64_t j = pair[2 * k + 1];
        if (j < 0) continue;
        const std::size_t i = std::size_t(pair[2 * k]);
        std::array<double, 3> end{};
        bool across = false;
        for (int a = 0; a < 3; ++a) {
          end[a] = position_m[3 * std::size_t(j) + a];
          if (!periodic_.axis[a]) continue;
          const double L = periodic_.high_m[a] - periodic_.low_m[a];
          const double shift = L * std::round((position_m[3 * i + a] - end[a]) / L);
          across = across || shift != 0.0;
          end[a] += shift;
        }
        if (!across) continue;
        images.insert(images.end(), end.begin(), end.end());
        lines[2 * k + 1] = std::int64_t(n + counts.wall_contacts + counts.image_ends);
        ++counts.image_ends;
      }
    }
    hdf5::write_array(g, "contact_lines", lines, 2, "1");
    const hsize_t w = counts.wall_contacts;
    std::vector<Mapping> points = {
        position_block.empty() ? Mapping{0, n, "/frames/position", {frames, n, 3}, f, 1}
                               : Mapping{0, n, position_block, {n, 3}, 0, n}};
    if (w > 0) {
      hdf5::write_array(g, "wall_feet", feet, 3, "m");
      points.push_back({n, w, here + "wall_feet", {w, 3}, 0, w});
    }
    const hsize_t m = counts.image_ends;
    if (m > 0) {
      hdf5::write_array(g, "image_ends", images, 3, "m");
      points.push_back({n + w, m, here + "image_ends", {m, 3}, 0, m});
    }
    create_virtual(g, "contact_points", {n + w + m, 3}, points, "m");
    if (!force_block.empty()) {
      link_block(force_block, "normal_force");
      link_block(block("/contacts/blocks", "conductance"), "conductance");
      link_block(block("/contacts/blocks", "tangential_force"), "tangential_force");
    } else {
      create_virtual(g, "normal_force", {c}, {{0, c, "/contacts/normal_force", {rows}, first, c}},
                     "N");
      create_virtual(g, "conductance", {c}, {{0, c, "/contacts/conductance", {rows}, first, c}},
                     "W/K");
      create_virtual(g, "tangential_force", {c, 3},
                     {{0, c, "/contacts/tangential_force", {rows, 3}, first, c}}, "N");
    }
  }
  if (c > 0)
    create_virtual(g, "heat_flow", {c}, {{0, c, "/contacts/heat_flow", {rows}, first, c}}, "W");

  // Kept for the next frame (no allocation once the vectors have their size).
  previous_.valid = complete;
  if (!geometry_same) previous_.geometry_frame = frame;
  if (!contacts_same) previous_.contacts_frame = frame;
  previous_.counts = counts;
  previous_.position.assign(position_m.begin(), position_m.end());
  previous_.velocity.assign(data.velocity_m_per_s.begin(), data.velocity_m_per_s.end());
  previous_.pair.assign(pair.begin(), pair.end());
  previous_.force.assign(data.normal_force_N.begin(), data.normal_force_N.end());
  previous_.conductance.assign(data.conductance_W_per_K.begin(), data.conductance_W_per_K.end());
  previous_.tangential.assign(data.tangential_force_N.begin(), data.tangential_force_N.end());
  return counts;
}

FrameViewCounts ResultViews::counts(hid_t file, std::size_t frame) const {
  FrameViewCounts counts;
  Hdf5Handle group = hdf5::open_group(file, frame_group(frame).c_str());
  counts.moved_walls = hdf5::exists(group.get(), "wall_points");
  if (!hdf5::exists(group.get(), "contact_lines")) return counts;
  Hdf5Handle lines = hdf5::open_dataset(group.get(), "contact_lines");
  counts.contacts = hdf5::dataset_rows(lines.get());
  if (hdf5::exists(group.get(), "wall_feet")) {
    Hdf5Handle feet = hdf5::open_dataset(group.get(), "wall_feet");
    counts.wall_contacts = hdf5::dataset_rows(feet.get());
  }
  if (hdf5::exists(group.get(), "image_ends")) {
    Hdf5Handle ends = hdf5::open_dataset(group.get(), "image_ends");
    counts.image_ends = hdf5::dataset_rows(ends.get());
  }
  return counts;
}

void ResultViews::cut_back(hid_t file, std::size_t frames) {
  previous_.valid = false;
  for (std::size_t f = frames;; ++f) {
    const std::string name = frame_group(f);
    if (!hdf5::exists(file, name.c_str())) break;
    hdf5::check_ok(H5Ldelete(file, name.c_str(), H5P_DEFAULT), "H5Ldelete " + name);
  }
}

}  // namespace tmdem::coupling
