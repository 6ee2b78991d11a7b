// A testing aid, not physics, registered only by the test program tmdem_testing (never by
// tmdem): adds no heat, but after a set number of right-hand-side evaluations every evaluation
// reports failure. Lets the stability suite check that a solver failure stops a run cleanly
// (exit 3, frames kept, status "failed"). A scene switches it on like any mode:
//   [effects] fault_injection = true      [fault_injection] after_rhs_evaluations = 40
#include "FaultInjectionMode.h"

#include <memory>

namespace tmdem::testing {
namespace {

using namespace tmdem::thermal;

class FaultInjectionMode final : public HeatTransferMode {
 public:
  explicit FaultInjectionMode(const ModeParameters& p)
      : fail_after_(static_cast<long>(p["after_rhs_evaluations"])) {}

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

const ModeDescription& fault_injection_mode() {
  static const ModeDescription mode{
      .name = "fault_injection",
      .summary = "testing aid: refuses every right-hand-side evaluation after a set number",
      .effect = "fault_injection",
      .effect_description = "testing aid (tmdem_testing only): make the thermal solver fail",
      .section = "fault_injection",
      .section_description = "testing aid; used when effects.fault_injection = true",
      .parameters = {{.key = "after_rhs_evaluations",
                      .unit = "",
                      .default_value = 40.0,
                      .range = ParameterRange::at_least(0.0),
                      .description = "evaluations that succeed before every further one fails"}},
      .check = [](const ModeParameters& p) -> std::optional<ParameterProblem> {
        const double n = p["after_rhs_evaluations"];
        if (n != static_cast<double>(static_cast<long>(n)))
          return ParameterProblem{"after_rhs_evaluations",
                                  "must be a whole number (got " + parameter_text(n) + ")"};
        return std::nullopt;
      },
      .make = [](const ModeParameters& p) -> std::unique_ptr<HeatTransferMode> {
        return std::make_unique<FaultInjectionMode>(p);
      },
  };
  return mode;
}

}  // namespace tmdem::testing
