#include "coupling/studies/ExactThermalReference.h"

#include <unsupported/Eigen/MatrixFunctions>

#include <cfloat>
#include <cmath>
#include <memory>
#include <stdexcept>

#include "thermal/modes/ModeRegistry.h"
#include "thermal/modes/ParticleResistance.h"

namespace tmdem::coupling {

namespace {
std::optional<AffineThermalSystem> affine_system_of_modes(
    const thermal::ThermalNetwork& net, std::span<const thermal::HeatTransferMode* const> modes,
    std::string* why_not) {
  // Wall temperatures that follow a table make the system time-dependent: not affine-constant.
  if (!net.wall_temperature_tables.empty()) {
    if (why_not) *why_not = "wall temperatures follow a table (time-dependent)";
    return std::nullopt;
  }
  // Conductivities or heat capacities that follow T make it nonlinear.
  if (net.temperature_dependent()) {
    if (why_not) *why_not = "the network is nonlinear (properties that follow T)";
    return std::nullopt;
  }
  // Each mode states its own K and f (HeatTransferMode::add_affine_heat_flow), in the order the
  // system sums the modes; a mode that cannot is named.
  thermal::AffineHeatFlow flow(net.node_count());
  std::string not_affine;
  for (const thermal::HeatTransferMode* m : modes)
    if (!m->add_affine_heat_flow(net, flow))
      not_affine += (not_affine.empty() ? "" : ", ") + std::string(m->name());
  if (!not_affine.empty()) {
    if (why_not) *why_not = "the network is nonlinear (" + not_affine + ")";
    return std::nullopt;
  }
  // Sum the entries in long double, with the bound of that rounding: an entry written n times
  // is off by at most gamma_(n-1) times the sum of its |terms| (u = long double unit roundoff;
  // an entry written once is exact). The two helper matrices hold, per entry, those sums of
  // |terms| and the counts.
  const std::size_t n = net.node_count();
  std::vector<Eigen::Triplet<long double>> entries, magnitudes, counts;
  for (std::size_t k = 0; k < flow.value_W_per_K.size(); ++k) {
    const auto i = std::size_t(flow.row[k]);
    if (net.held[i]) continue;
    const auto r = Eigen::Index(i), c = Eigen::Index(flow.column[k]);
    entries.emplace_back(r, c, flow.value_W_per_K[k]);
    magnitudes.emplace_back(r, c, std::abs(flow.value_W_per_K[k]));
    counts.emplace_back(r, c, 1.0L);
  }
  AffineThermalSystem out;
  const auto size = Eigen::Index(n);
  Eigen::SparseMatrix<long double, Eigen::RowMajor> magnitude(size, size), count(size, size);
  out.K_W_per_K.resize(size, size);
  out.K_W_per_K.setFromTriplets(entries.begin(), entries.end());
  magnitude.setFromTriplets(magnitudes.begin(), magnitudes.end());
  count.setFromTriplets(counts.begin(), counts.end());
  out.K_rounding_W_per_K.assign(n, 0.0L);
  constexpr long double u = LDBL_EPSILON / 2.0L;
  for (Eigen::Index i = 0; i < size; ++i) {
    Eigen::SparseMatrix<long double, Eigen::RowMajor>::InnerIterator m(magnitude, i), c(count, i);
    for (; m; ++m, ++c) {
      const long double nu = (c.value() - 1.0L) * u;
      out.K_rounding_W_per_K[std::size_t(i)] += nu / (1.0L - nu) * m.value() * (1.0L + 4.0L * u);
    }
  }
  out.C_J_per_K = net.heat_capacity_J_per_K;
  out.held = net.held;
  out.f_W.assign(n, 0.0);
  for (std::size_t i = 0; i < n; ++i)
    if (!net.held[i]) out.f_W[i] = flow.constant_W[i];  // q at T = 0, W
  return out;
}
}  // namespace

std::optional<AffineThermalSystem> affine_thermal_system(const thermal::ThermalNetwork& net,
                                                         const std::vector<std::string>& mode_names,
                                                         const thermal::ModeSettings& s,
                                                         std::string* why_not) {
  std::vector<std::unique_ptr<thermal::HeatTransferMode>> built;
  std::vector<const thermal::HeatTransferMode*> modes;
  thermal::ThermalNetwork prepared = net;
  for (const auto& name : mode_names) {
    built.push_back(thermal::make_heat_transfer_mode(name, s));
    built.back()->update_geometry(prepared);
    modes.push_back(built.back().get());
  }
  // The particle's own resistance, as a ThermalSystem of these modes would put it in series.
  thermal::update_series_factors(prepared, modes);
  return affine_system_of_modes(prepared, modes, why_not);
}

std::optional<AffineThermalSystem> affine_thermal_system(const thermal::ThermalSystem& system,
                                                         std::string* why_not) {
  std::vector<const thermal::HeatTransferMode*> modes;
  for (const auto& m : system.modes()) modes.push_back(m.get());
  return affine_system_of_modes(system.network(), modes, why_not);
}

std::vector<double> exact_affine_temperatures(const AffineThermalSystem& sys,
                                              std::span<const double> T0_K, double t_s) {
  const auto n = Eigen::Index(T0_K.size());
  if (Eigen::Index(sys.size()) != n)
    throw std::invalid_argument("exact reference: T0 has the wrong size");
  Eigen::VectorXd s(n);
  for (Eigen::Index i = 0; i < n; ++i) s(i) = std::sqrt(sys.C_J_per_K[std::size_t(i)]);
  // y = S T with S = diag(sqrt(C)): dy/dt = (S C^-1 K S^-1) y + S C^-1 f, symmetric on the free
  // particles instead of the far from normal C^-1 K of a bed whose heat capacities differ by
  // orders of magnitude; scaling and squaring loses much less there.
  const Eigen::MatrixXd K = Eigen::MatrixXd(sys.K_W_per_K.cast<double>());
  Eigen::MatrixXd M = Eigen::MatrixXd::Zero(n + 1, n + 1);
  for (Eigen::Index i = 0; i < n; ++i) {
    const double C = sys.C_J_per_K[std::size_t(i)];
    M.block(i, 0, 1, n) = K.row(i) / C * s(i) * t_s;
    M.row(i).head(n) = M.row(i).head(n).cwiseQuotient(s.transpose());
    M(i, n) = s(i) * sys.f_W[std::size_t(i)] / C * t_s;
  }
  Eigen::VectorXd x(n + 1);
  for (Eigen::Index i = 0; i < n; ++i) x(i) = s(i) * T0_K[std::size_t(i)];
  x(n) = 1.0;
  const Eigen::MatrixXd E = M.exp();
  const Eigen::VectorXd T = (E * x).head(n).cwiseQuotient(s);
  if (!T.allFinite())
    throw std::runtime_error("exact reference: the matrix exponential is not finite");
  return {T.data(), T.data() + n};
}

}  // namespace tmdem::coupling
