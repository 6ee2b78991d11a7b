#include "coupling/run/BedPiece.h"

#include <algorithm>
#include <limits>

#include "coupling/bridge/RestingContacts.h"
#include "coupling/bridge/SceneToMechanics.h"
#include "coupling/bridge/ThermalNetworkBuilder.h"
#include "coupling/run/PieceDiagnostics.h"
#include "coupling/scene/HeatModes.h"

namespace tmdem::coupling {
namespace {

// The scene without its particles and imported forces (the piece brings its own): the members
// the contact detection and the network builder read (not the import reports, the warnings,
// the TOML text). Member by member: copying the whole scene would hold its particles twice.
Scene settings_of(const Scene& s) {
  Scene out;
  out.duration_s = s.duration_s;
  out.dimension = s.dimension;
  out.gravity_m_per_s2 = s.gravity_m_per_s2;
  out.seed = s.seed;
  out.effects = s.effects;
  out.materials = s.materials;
  out.walls = s.walls;
  out.periodic = s.periodic;
  out.heat_modes = s.heat_modes;
  out.mechanics = s.mechanics;
  out.thermal = s.thermal;
  out.output = s.output;
  out.probes = s.probes;
  out.source = s.source;
  return out;
}

// Distance along the slab axis from x to [lo, hi], m, through the nearest periodic image when
// the axis is periodic (period_m > 0).
double distance_to_slab_m(double x, double lo, double hi, double period_m) {
  const auto plain = [&](double y) { return std::max({lo - y, y - hi, 0.0}); };
  if (period_m <= 0.0) return plain(x);
  return std::min({plain(x), plain(x - period_m), plain(x + period_m)});
}

}  // namespace

double detection_halo_m(const Scene& scene) {
  double r_max_m = 0.0;
  for (const auto& p : scene.particles) r_max_m = std::max(r_max_m, p.radius_m);
  // (1 + 1e-6): the touching test's own tolerance (a gap of 1e-9 r) and round-off, with room.
  return (3.0 + near_pair_reach(scene)) * r_max_m * (1.0 + 1e-6);
}

BedPiece BedPiece::build(const Scene& scene, std::span<const double> centre_m,
                         const thermal::NetworkPartition& p, int rank) {
  const std::size_t n = scene.particles.size();
  const int axis = p.axis();
  // The slab: its own centres' range along the cut axis.
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (std::int32_t row = p.first_row(rank); row < p.first_row(rank + 1); ++row) {
    const double x = centre_m[3 * std::size_t(p.node_at_row(row)) + std::size_t(axis)];
    lo = std::min(lo, x);
    hi = std::max(hi, x);
  }
  const double halo_m = detection_halo_m(scene);
  const double period_m =
      scene.periodic.axis[std::size_t(axis)] ? scene.periodic.length_m(axis) : 0.0;
  const auto owned = [&](std::size_t i) { return p.owner(std::int32_t(i)) == rank; };
  std::vector<std::uint8_t> keep(n, 0);
  for (std::size_t i = 0; i < n; ++i)
    keep[i] = owned(i) ||
              distance_to_slab_m(centre_m[3 * i + std::size_t(axis)], lo, hi, period_m) <= halo_m;
  // An owned particle's imported contacts, whatever their length: its wall force balances them.
  const auto& imported = scene.imported_forces;
  for (const auto& c : imported.pairs) {
    if (owned(c.i)) keep[c.j] = 1;
    if (owned(c.j)) keep[c.i] = 1;
  }

  BedPiece out;
  Scene piece = settings_of(scene);
  std::vector<std::int32_t> piece_of(n, -1);
  for (std::size_t i = 0; i < n; ++i) {
    if (!keep[i]) continue;
    piece_of[i] = std::int32_t(out.particle.size());
    out.particle.push_back(std::int32_t(i));
    piece.particles.push_back(scene.particles[i]);
    for (std::size_t k = 0; k < 3; ++k) piece.particles.back().position_m[k] = centre_m[3 * i + k];
    if (!imported.wall_gap.empty()) piece.imported_forces.wall_gap.push_back(imported.wall_gap[i]);
  }
  for (const auto& c : imported.pairs) {
    if (piece_of[c.i] < 0 || piece_of[c.j] < 0) continue;
    auto local = c;
    local.i = std::size_t(piece_of[c.i]);
    local.j = std::size_t(piece_of[c.j]);
    piece.imported_forces.pairs.push_back(local);
  }

  const auto particles = make_particle_set(piece);
  auto contacts = resting_contacts(piece, particles);
  out.contacts = contacts.size();
  ThermalNetworkBuilder builder(piece);
  out.network = builder.nodes();
  builder.build_edges(contacts, out.network, nullptr, &particles);
  out.diagnostics = diagnose_piece(scene, contacts, out.particle,
                                   out.network.heat_capacity_J_per_K, p, rank);
  return out;
}

}  // namespace tmdem::coupling
