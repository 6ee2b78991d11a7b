#include "coupling/bridge/LineOfSight.h"

namespace tmdem::coupling {

std::vector<std::uint8_t> shadowed_edges(const thermal::ThermalNetwork& edges,
                                         const mechanics::ParticleSet& geometry) {
  const std::size_t n = geometry.size(), count = edges.edge_count();
  // Each node's neighbours in the network (CSR).
  std::vector<std::int32_t> start(n + 1, 0), neighbour(2 * count);
  for (std::size_t e = 0; e < count; ++e) {
    ++start[std::size_t(edges.edge_a[e]) + 1];
    ++start[std::size_t(edges.edge_b[e]) + 1];
  }
  for (std::size_t i = 0; i < n; ++i) start[i + 1] += start[i];
  std::vector<std::int32_t> fill(start.begin(), start.end() - 1);
  for (std::size_t e = 0; e < count; ++e) {
    neighbour[std::size_t(fill[std::size_t(edges.edge_a[e])]++)] = edges.edge_b[e];
    neighbour[std::size_t(fill[std::size_t(edges.edge_b[e])]++)] = edges.edge_a[e];
  }
  std::vector<std::uint8_t> shadowed(count, 0);
  for (std::size_t e = 0; e < count; ++e) {
    if (edges.edge_in_contact[e]) continue;
    const auto a = std::size_t(edges.edge_a[e]), b = std::size_t(edges.edge_b[e]);
    const Eigen::Vector3d d = geometry.branch(b, a);  // x_b - x_a, m
    const double length2 = d.squaredNorm();
    // k's centre relative to a, through the image nearest the end it neighbours.
    auto crosses = [&](std::size_t k, const Eigen::Vector3d& p) {
      const double t = p.dot(d) / length2;
      if (!(t > 0.0 && t < 1.0)) return false;
      const double r = geometry.radius[k];
      return (p - t * d).squaredNorm() < r * r;
    };
    for (const std::size_t end : {a, b}) {
      for (auto q = start[end]; q < start[end + 1] && !shadowed[e]; ++q) {
        const auto k = std::size_t(neighbour[std::size_t(q)]);
        if (k == a || k == b) continue;
        const Eigen::Vector3d p = end == a ? geometry.branch(k, a) : Eigen::Vector3d(geometry.branch(k, b) + d);
        if (crosses(k, p)) shadowed[e] = 1;
      }
    }
  }
  return shadowed;
}

}  // namespace tmdem::coupling
