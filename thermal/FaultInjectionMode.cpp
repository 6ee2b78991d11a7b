// A testing aid, not physics: adds no heat, but after a set number of right-hand-side
// evaluations every evaluation reports failure. Lets the stability suite check that a solver
// failure stops a run cleanly (exit 3, frames kept, status "failed"). The coupling builds it
// only when the environment variable TMDEM_FAULT_AFTER_RHS_EVALS is set.
#include <memory>

#include "thermal/HeatTransferMode.h"

namespace tmdem::thermal {
namespace {

class FaultInjectionMode final : public HeatTransferMode {
 public:
  explicit FaultInjectionMode(const ModeSettings& s) : fail_after_(s.fault_after_evaluations) {}

  std::string_view name() const override { return "fault_injection"; }

  bool add_heat_flow(const ThermalNetwork&, std::span<const double>, std::span<double>,
                     double&) const override {
    return ++evaluations_ <= fail_after_;
  }

  void add_jacobian(const ThermalNetwork&, std::span<const double>, JacobianView) const override {}

 private:
  long fail_after_;
  mutable long evaluations_ = 0;
};

}  // namespace

std::unique_ptr<HeatTransferMode> make_fault_injection_mode(const ModeSettings& s) {
  return std::make_unique<FaultInjectionMode>(s);
}

}  // namespace tmdem::thermal
