#pragma once
// Helpers for thermal tests: small networks, systems built from mode names, and the exact
// solution of the linear (affine) thermal ODE by matrix exponential, assembled here from the
// network arrays independently of ThermalSystem's own assembly.
#include <Eigen/Dense>
#include <unsupported/Eigen/MatrixFunctions>

#include <memory>
#include <string>
#include <vector>

#include "thermal/IntegratorRegistry.h"
#include "thermal/ModeRegistry.h"
#include "thermal/ThermalNetwork.h"
#include "thermal/ThermalSystem.h"

namespace tmdem::thermal::testing {

inline ThermalNetwork chain_network(int n, double C_J_per_K, double H_W_per_K) {
  ThermalNetwork net;
  net.resize_nodes(std::size_t(n));
  for (int i = 0; i < n; ++i) net.heat_capacity_J_per_K[i] = C_J_per_K;
  for (int i = 0; i + 1 < n; ++i) net.add_edge(i, i + 1, H_W_per_K);
  return net;
}

inline std::unique_ptr<ThermalSystem> make_system(const ThermalNetwork& net,
                                                  const std::vector<std::string>& modes,
                                                  const ModeSettings& settings = {}) {
  std::vector<std::unique_ptr<HeatTransferMode>> built;
  for (const auto& m : modes) built.push_back(make_heat_transfer_mode(m, settings));
  return std::make_unique<ThermalSystem>(net, std::move(built));
}

// dT/dt = A T + b for the linear modes (contact and wall conduction, convection, sources);
// held rows are zero.
struct AffineSystem {
  Eigen::MatrixXd A;
  Eigen::VectorXd b;
};

inline AffineSystem affine_system(const ThermalNetwork& net, const ModeSettings& s,
                                  bool convection) {
  const int n = int(net.node_count());
  Eigen::MatrixXd K = Eigen::MatrixXd::Zero(n, n);  // W/K
  Eigen::VectorXd f = Eigen::VectorXd::Zero(n);     // W
  for (std::size_t e = 0; e < net.edge_count(); ++e) {
    const int a = net.edge_a[e], b = net.edge_b[e];
    const double h = net.edge_conductance_W_per_K[e];
    K(a, b) += h; K(b, a) += h; K(a, a) -= h; K(b, b) -= h;
  }
  for (std::size_t w = 0; w < net.wall_edge_count(); ++w) {
    const int i = net.wall_node[w];
    K(i, i) -= net.wall_conductance_W_per_K[w];
    f(i) += net.wall_conductance_W_per_K[w] * net.wall_temperature_K[w];
  }
  for (int i = 0; i < n; ++i) {
    if (convection) {
      const double hA = s.convection_coefficient_W_per_m2K * net.surface_area_m2[i];
      K(i, i) -= hA;
      f(i) += hA * s.fluid_temperature_K;
    }
    f(i) += net.heat_source_W[i];
  }
  AffineSystem out{Eigen::MatrixXd::Zero(n, n), Eigen::VectorXd::Zero(n)};
  for (int i = 0; i < n; ++i) {
    if (net.held[i]) continue;
    out.A.row(i) = K.row(i) / net.heat_capacity_J_per_K[i];
    out.b(i) = f(i) / net.heat_capacity_J_per_K[i];
  }
  return out;
}

// T(t) = exp(t M) [T0; 1] with M = [[A, b], [0, 0]].
inline Eigen::VectorXd exact_temperatures(const AffineSystem& sys, const std::vector<double>& T0,
                                          double t_s) {
  const int n = int(T0.size());
  Eigen::MatrixXd M = Eigen::MatrixXd::Zero(n + 1, n + 1);
  M.topLeftCorner(n, n) = sys.A * t_s;
  M.topRightCorner(n, 1) = sys.b * t_s;
  Eigen::VectorXd x(n + 1);
  for (int i = 0; i < n; ++i) x(i) = T0[i];
  x(n) = 1.0;
  const Eigen::MatrixXd E = M.exp();
  return (E * x).head(n);
}

inline double max_abs_error(std::span<const double> T, const Eigen::VectorXd& exact) {
  double e = 0.0;
  for (std::size_t i = 0; i < T.size(); ++i) e = std::max(e, std::abs(T[i] - exact(Eigen::Index(i))));
  return e;
}

struct RunResult {
  std::vector<double> T;
  double boundary_heat_J;
  IntegratorStats stats;
};

inline RunResult run(ThermalSystem& system, const std::string& integrator, IntegratorSettings s,
                     const std::vector<double>& T0, double t_end_s) {
  auto integ = make_thermal_integrator(integrator, system, s);
  integ->initialize(0.0, T0, 0.0);
  integ->advance_to(t_end_s);
  auto T = integ->temperatures_K();
  return {std::vector<double>(T.begin(), T.end()), integ->boundary_heat_J(), integ->stats()};
}

}  // namespace tmdem::thermal::testing
