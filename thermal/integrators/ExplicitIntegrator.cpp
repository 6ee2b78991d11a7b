#include "thermal/integrators/ExplicitIntegrator.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "thermal/integrators/ThermalSolverError.h"

namespace tmdem::thermal {

ExplicitIntegrator::ExplicitIntegrator(ThermalSystem& system, const IntegratorSettings& settings)
    : system_(system), settings_(settings) {
  // Its stability bound (Gershgorin at the largest temperature, constant C) does not bound a
  // network whose k and C change with T; the implicit integrators have the exact Jacobian.
  if (system_.network().temperature_dependent())
    throw std::invalid_argument(
        "thermal.integrator = \"explicit\" does not support temperature-dependent material "
        "properties (a conductivity or heat_capacity table); use \"cvode\" or \"ida\"");
}

void ExplicitIntegrator::choose_step(bool at_start) {
  bound_s_ = system_.explicit_stability_bound_s(max_temperature_K_);
  values_seen_ = system_.values_version();
  if (settings_.explicit_step_s <= 0.0) {
    step_s_ = 0.9 * bound_s_;
    return;
  }
  step_s_ = settings_.explicit_step_s;
  if (step_s_ > bound_s_) {
    std::ostringstream msg;
    msg.precision(6);
    msg << "thermal.explicit_step = " << step_s_
        << " s is above the stability bound of the explicit update, " << bound_s_
        << " s (2 / lambda_max, Gershgorin bound of C^-1 dq/dT); use a step of at most "
        << bound_s_ << " s, or explicit_step = 0 for 0.9 of the bound";
    if (at_start) throw std::invalid_argument(msg.str());
    throw ThermalSolverError(msg.str() + " (the network changed during the run)", 0, t_);
  }
}

void ExplicitIntegrator::initialize(double t0_s, std::span<const double> T0_K,
                                    double boundary_heat0_J) {
  if (T0_K.size() != system_.size())
    throw std::invalid_argument("explicit: initial temperatures have the wrong size");
  T_.assign(T0_K.begin(), T0_K.end());
  dTdt_.assign(T_.size(), 0.0);
  t_ = t0_s;
  boundary_heat_J_ = boundary_heat0_J;
  dissipation_heat_J_ = 0.0;
  stats_ = {};
  max_temperature_K_ = settings_.max_temperature_K;
  for (double T : T_) max_temperature_K_ = std::max(max_temperature_K_, T);
  choose_step(true);
}

void ExplicitIntegrator::advance_to(double t_s) {
  if (system_.values_version() != values_seen_) choose_step(false);
  while (t_ < t_s) {
    const double remaining = t_s - t_;
    // Take the last partial step exactly to t_s rather than leaving a sliver behind.
    const bool last = remaining <= step_s_ * (1.0 + 1e-12);
    const double h = last ? remaining : step_s_;
    double boundary_W = 0.0;
    system_.set_time(t_);
    if (!system_.time_derivative(T_, dTdt_, boundary_W)) {
      std::ostringstream msg;
      msg << "explicit update: heat flow undefined at t = " << t_
          << " s (a temperature left the domain of a heat-transfer mode, e.g. T <= 0 K for "
             "radiation); the step "
          << h << " s is too large for this nonlinear case";
      throw ThermalSolverError(msg.str(), 0, t_);
    }
    ++stats_.rhs_evals;
    for (std::size_t i = 0; i < T_.size(); ++i) T_[i] += h * dTdt_[i];
    boundary_heat_J_ += h * boundary_W;
    dissipation_heat_J_ += h * system_.dissipation_boundary_W();
    t_ = last ? t_s : t_ + h;
    ++stats_.steps;
  }
}

}  // namespace tmdem::thermal
