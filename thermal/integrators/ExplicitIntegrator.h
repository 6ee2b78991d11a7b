#pragma once
// Forward Euler, the MULTICOR update: T += h C^-1 q(T). First order, stable only below
// 2 / lambda_max; kept for accuracy studies against the implicit integrators.
#include <vector>

#include "thermal/integrators/ThermalIntegrator.h"
#include "thermal/system/ThermalSystem.h"

namespace tmdem::thermal {

class ExplicitIntegrator final : public ThermalIntegrator {
 public:
  ExplicitIntegrator(ThermalSystem& system, const IntegratorSettings& settings);

  IntegratorKind kind() const override { return IntegratorKind::Explicit; }
  // Throws std::invalid_argument, naming the bound, when explicit_step_s exceeds it.
  void initialize(double t0_s, std::span<const double> T0_K, double boundary_heat0_J) override;
  void advance_to(double t_s) override;
  void restart() override {}
  double time_s() const override { return t_; }
  std::span<const double> temperatures_K() const override { return T_; }
  double boundary_heat_J() const override { return boundary_heat_J_; }
  double dissipation_heat_J() const override { return dissipation_heat_J_; }
  IntegratorStats stats() const override { return stats_; }
  void restore_stats(const IntegratorStats& earlier) override { stats_ = earlier; }

  double stability_bound_s() const { return bound_s_; }
  double step_s() const { return step_s_; }

 private:
  void choose_step(bool at_start);

  ThermalSystem& system_;
  IntegratorSettings settings_;
  std::vector<double> T_, dTdt_;
  double t_ = 0.0;
  double boundary_heat_J_ = 0.0;
  double dissipation_heat_J_ = 0.0;  // since initialize()
  double max_temperature_K_ = 0.0;
  double bound_s_ = 0.0;
  double step_s_ = 0.0;
  std::uint64_t values_seen_ = 0;
  IntegratorStats stats_;
};

}  // namespace tmdem::thermal
