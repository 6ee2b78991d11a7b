#include "coupling/studies/ExactThermalReference.h"

#include <unsupported/Eigen/MatrixFunctions>

#include <cmath>
#include <memory>
#include <stdexcept>

#include "thermal/modes/ModeRegistry.h"

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
  const auto n = Eigen::Index(net.node_count());
  Eigen::MatrixXd K = Eigen::MatrixXd::Zero(n, n);  // d q / d T, W/K
  for (std::size_t k = 0; k < flow.value_W_per_K.size(); ++k)
    K(Eigen::Index(flow.row[k]), Eigen::Index(flow.column[k])) += flow.value_W_per_K[k];
  const Eigen::Map<const Eigen::VectorXd> f(flow.constant_W.data(), n);  // q at T = 0, W

  AffineThermalSystem out{Eigen::MatrixXd::Zero(n, n), Eigen::VectorXd::Zero(n),
                          Eigen::VectorXd::Zero(n)};
  for (Eigen::Index i = 0; i < n; ++i) {
    const double C = net.heat_capacity_J_per_K[std::size_t(i)];
    out.scale(i) = std::sqrt(C);
    if (net.held[std::size_t(i)]) continue;
    out.A.row(i) = K.row(i) / C;
    out.b(i) = f(i) / C;
  }
  return out;
}
}  // namespace

std::optional<AffineThermalSystem> affine_thermal_system(const thermal::ThermalNetwork& net,
                                                         const std::vector<std::string>& mode_names,
                                                         const thermal::ModeSettings& s,
                                                         std::string* why_not) {
  std::vector<std::unique_ptr<thermal::HeatTransferMode>> built;
  std::vector<const thermal::HeatTransferMode*> modes;
  for (const auto& name : mode_names) {
    built.push_back(thermal::make_heat_transfer_mode(name, s));
    modes.push_back(built.back().get());
  }
  return affine_system_of_modes(net, modes, why_not);
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
  if (sys.A.rows() != n) throw std::invalid_argument("exact reference: T0 has the wrong size");
  const Eigen::VectorXd s = sys.scale.size() == n ? sys.scale : Eigen::VectorXd::Ones(n);
  // y = S T: dy/dt = (S A S^-1) y + S b.
  Eigen::MatrixXd M = Eigen::MatrixXd::Zero(n + 1, n + 1);
  M.topLeftCorner(n, n) = s.asDiagonal() * sys.A * s.cwiseInverse().asDiagonal() * t_s;
  M.topRightCorner(n, 1) = s.cwiseProduct(sys.b) * t_s;
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
