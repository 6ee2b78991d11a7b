#include "coupling/studies/ExactThermalReference.h"

#include <unsupported/Eigen/MatrixFunctions>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "thermal/modes/ModeRegistry.h"

namespace tmdem::coupling {

namespace {
bool has(const std::vector<std::string>& names, const char* name) {
  return std::find(names.begin(), names.end(), name) != names.end();
}
}  // namespace

std::optional<AffineThermalSystem> affine_thermal_system(const thermal::ThermalNetwork& net,
                                                         const std::vector<std::string>& mode_names,
                                                         const thermal::ModeSettings& s) {
  for (const auto& m : mode_names)
    if (m != "contact_conduction" && m != "wall_conduction" && m != "convection" &&
        m != "heat_source")
      return std::nullopt;
  // Wall temperatures that follow a table make the system time-dependent: not affine-constant.
  if (!net.wall_temperature_tables.empty()) return std::nullopt;
  // Conductivities or heat capacities that follow T make it nonlinear.
  if (net.temperature_dependent()) return std::nullopt;
  const auto n = Eigen::Index(net.node_count());
  Eigen::MatrixXd K = Eigen::MatrixXd::Zero(n, n);  // d q / d T, W/K
  Eigen::VectorXd f = Eigen::VectorXd::Zero(n);     // q at T = 0, W
  if (has(mode_names, "contact_conduction"))
    for (std::size_t e = 0; e < net.edge_count(); ++e) {
      const Eigen::Index a = net.edge_a[e], b = net.edge_b[e];
      const double h = net.edge_conductance_W_per_K[e];
      K(a, b) += h;
      K(b, a) += h;
      K(a, a) -= h;
      K(b, b) -= h;
    }
  if (has(mode_names, "wall_conduction"))
    for (std::size_t w = 0; w < net.wall_edge_count(); ++w) {
      const Eigen::Index i = net.wall_node[w];
      K(i, i) -= net.wall_conductance_W_per_K[w];
      f(i) += net.wall_conductance_W_per_K[w] * net.wall_temperature_K[w];
    }
  if (has(mode_names, "convection")) {
    const auto p = thermal::resolve_mode_parameters(*thermal::find_heat_transfer_mode("convection"), s);
    for (Eigen::Index i = 0; i < n; ++i) {
      const double hA = p["coefficient"] * net.surface_area_m2[std::size_t(i)];
      K(i, i) -= hA;
      f(i) += hA * p["fluid_temperature"];
    }
  }
  if (has(mode_names, "heat_source"))
    for (Eigen::Index i = 0; i < n; ++i) f(i) += net.heat_source_W[std::size_t(i)];

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

std::optional<AffineThermalSystem> affine_thermal_system(const thermal::ThermalSystem& system,
                                                         const thermal::ModeSettings& settings) {
  std::vector<std::string> names;
  for (const auto& m : system.modes()) names.emplace_back(m->name());
  return affine_thermal_system(system.network(), names, settings);
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
