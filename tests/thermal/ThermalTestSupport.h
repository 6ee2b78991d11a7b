#pragma once
// Helpers for thermal tests: small networks, systems built from mode names, and the exact
// solution of the linear (affine) thermal ODE by matrix exponential, assembled here from the
// network arrays independently of ThermalSystem's own assembly.
#include <Eigen/Dense>
#include <unsupported/Eigen/MatrixFunctions>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <numbers>
#include <span>
#include <string>
#include <tuple>
#include <vector>

#include "thermal/integrators/IntegratorRegistry.h"
#include "thermal/modes/ModeRegistry.h"
#include "thermal/network/ThermalNetwork.h"
#include "thermal/system/ThermalSystem.h"

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

// J = d(dT/dt)/dT at 300 K in y = sqrt(C) T (the symmetric form the conjugate-gradient linear
// solvers see), in pattern order.
inline std::vector<double> scaled_jacobian(const ThermalSystem& sys) {
  std::vector<double> v(sys.pattern().nonzeros());
  std::vector<double> T(sys.size(), 300.0), scale(sys.size());
  JacobianEvaluation J;
  sys.evaluate_jacobian(T, J);
  for (std::size_t i = 0; i < scale.size(); ++i) scale[i] = std::sqrt(sys.network().heat_capacity_J_per_K[i]);
  sys.jacobian_values(J, v, scale);
  return v;
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
  const auto convection_parameters = resolve_mode_parameters(*find_heat_transfer_mode("convection"), s);
  for (int i = 0; i < n; ++i) {
    if (convection) {
      const double hA = convection_parameters["coefficient"] * net.surface_area_m2[i];
      K(i, i) -= hA;
      f(i) += hA * convection_parameters["fluid_temperature"];
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

// ---- energy balance ----------------------------------------------------------------------

// The contract's figure: |E_final - E_initial - Q| / max(|E_initial|, |Q|), E = sum C_i T_i over
// every particle (held ones included: their term is constant).
inline double balance_error_rel(double E_initial_J, double E_final_J, double boundary_heat_J) {
  const double scale = std::max(std::abs(E_initial_J), std::abs(boundary_heat_J));
  return std::abs(E_final_J - E_initial_J - boundary_heat_J) / scale;
}

inline double balance_error_rel(const ThermalSystem& system, std::span<const double> T0_K,
                                const ThermalIntegrator& integrator) {
  return balance_error_rel(system.thermal_energy_J(T0_K),
                           system.thermal_energy_J(integrator.temperatures_K()),
                           integrator.boundary_heat_J());
}

// Every integrator / linear-solver pair (the explicit update ignores the linear solver).
using IntegratorCase = std::tuple<std::string, std::string>;
inline std::vector<IntegratorCase> all_integrator_cases() {
  return {{"cvode", "klu"}, {"cvode", "pcg"}, {"cvode", "amg"}, {"ida", "klu"},
          {"ida", "pcg"},   {"ida", "amg"},   {"explicit", "klu"}};
}
// The linear solver of a case, named as the scene names it.
inline LinearSolverKind solver_kind(const std::string& name) { return parse_linear_solver_kind(name); }

inline std::string case_name(const IntegratorCase& c) {
  return std::get<0>(c) == "explicit" ? "explicit" : std::get<0>(c) + "_" + std::get<1>(c);
}

// Tight tolerances for exact-answer and balance checks.
inline IntegratorSettings tight_settings(const std::string& linear_solver, double tol = 1e-10) {
  IntegratorSettings s;
  s.linear_solver = solver_kind(linear_solver);
  s.relative_tolerance = tol;
  s.absolute_tolerance_K = tol;
  return s;
}

// ---- single particle -----------------------------------------------------------------------

inline ThermalNetwork single_particle(double C_J_per_K, double area_m2, double emissivity = 0.0) {
  ThermalNetwork net;
  net.resize_nodes(1);
  net.heat_capacity_J_per_K[0] = C_J_per_K;
  net.surface_area_m2[0] = area_m2;
  net.emissivity[0] = emissivity;
  return net;
}

inline double sphere_area(double radius_m) { return 4.0 * std::numbers::pi * radius_m * radius_m; }

// ---- radiation of one particle: dT/dt = -k (T^4 - Ta^4), k = eps sigma A / C -----------------
//
// 1/(T^4 - a^4) = (1/(2a^2)) [1/(T^2 - a^2) - 1/(T^2 + a^2)], so
//   int dT / (T^4 - a^4) = (1/(4a^3)) [ln|(T - a)/(T + a)| - 2 atan(T/a)] =: -G(T) / (4a^3),
//   G(T) = ln|(T + a)/(T - a)| + 2 atan(T/a),  G'(T) = -4a^3 / (T^4 - a^4),
// and k t = int_T^T0 dT' / (T'^4 - a^4) gives
//   t(T) = [G(T) - G(T0)] / (4 k a^3).
// Valid for cooling (T0 > T > a) and heating (T0 < T < a) alike. For a = 0:
//   1/T^3 = 1/T0^3 + 3 k t.

constexpr double kStefanBoltzmann = 5.670374419e-8;

inline double radiation_time_to_reach(double T0, double T, double k, double Ta) {
  if (Ta == 0.0) return (1.0 / (T * T * T) - 1.0 / (T0 * T0 * T0)) / (3.0 * k);
  auto G = [Ta](double x) { return std::log(std::abs((x + Ta) / (x - Ta))) + 2.0 * std::atan(x / Ta); };
  return (G(T) - G(T0)) / (4.0 * k * Ta * Ta * Ta);
}

// T(t) from the implicit closed form above, by bisection on the monotone t(T) between T0 and
// the ambient temperature (closed form for Ta = 0).
inline double radiation_temperature(double T0, double t, double k, double Ta) {
  if (Ta == 0.0) return std::cbrt(1.0 / (1.0 / (T0 * T0 * T0) + 3.0 * k * t));
  if (t <= 0.0 || T0 == Ta) return T0;
  double near = T0, far = Ta;  // t(near) <= t, t(far) = infinity
  for (int it = 0; it < 200; ++it) {
    const double mid = 0.5 * (near + far);
    if (mid == near || mid == far) break;
    (radiation_time_to_reach(T0, mid, k, Ta) <= t ? near : far) = mid;
  }
  return 0.5 * (near + far);
}

// t(T) = int_T^T0 dT' / (k (T'^4 - a^4)) by composite Simpson: checks the closed form itself.
inline double radiation_time_by_quadrature(double T0, double T, double k, double Ta, int intervals) {
  auto f = [&](double x) { return 1.0 / (k * (x * x * x * x - Ta * Ta * Ta * Ta)); };
  const double h = (T0 - T) / intervals;
  double sum = f(T) + f(T0);
  for (int i = 1; i < intervals; ++i) sum += (i % 2 ? 4.0 : 2.0) * f(T + i * h);
  return sum * h / 3.0;
}

}  // namespace tmdem::thermal::testing
