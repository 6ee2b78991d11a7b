// A testing aid, not physics, registered only by the test program tmdem_testing (never by
// tmdem): adds no heat, but after a set number of right-hand-side evaluations every evaluation
// reports failure. Lets the stability suite check that a solver failure stops a run cleanly
// (exit 3, frames kept, status "failed"). With crash = 1 the process instead dies on the spot
// (SIGKILL, no cleanup) at that evaluation: a crash at a known point, for the files' crash
// consistency. A scene switches it on like any mode:
//   [effects] fault_injection = true      [fault_injection] after_rhs_evaluations = 40
#include "FaultInjectionMode.h"

#include <csignal>
#include <memory>

namespace tmdem::testing {
namespace {

using namespace tmdem::thermal;

class FaultInjectionMode final : public HeatTransferMode {
 public:
  explicit FaultInjectionMode(const ModeParameters& p)
      : fail_after_(static_cast<long>(p["after_rhs_evaluations"])), crash_(p["crash"] != 0.0) {}

  std::string_view name() const override { return "fault_injection"; }

  bool add_heat_flow(const ThermalNetwork&, std::span<const double>, std::span<double>,
                     double&) const override {
    if (++evaluations_ <= fail_after_) return true;
    if (crash_) std::raise(SIGKILL);
    return false;
  }

  void add_jacobian(const ThermalNetwork&, std::span<const double>, JacobianView) const override {}

 private:
  long fail_after_;
  bool crash_;
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
                      .description = "evaluations that succeed before every further one fails"},
                     {.key = "crash",
                      .unit = "",
                      .default_value = 0.0,
                      .range = ParameterRange::closed(0.0, 1.0),
                      .description = "1: the process is killed (SIGKILL) at the failing evaluation "
                                     "instead of reporting the failure"}},
      .check = [](const ModeParameters& p) -> std::optional<ParameterProblem> {
        const double n = p["after_rhs_evaluations"];
        if (n != static_cast<double>(static_cast<long>(n)))
          return ParameterProblem{"after_rhs_evaluations",
                                  "must be a whole number (got " + parameter_text(n) + ")"};
        if (p["crash"] != 0.0 && p["crash"] != 1.0)
          return ParameterProblem{"crash", "must be 0 or 1 (got " + parameter_text(p["crash"]) + ")"};
        return std::nullopt;
      },
      .make = [](const ModeParameters& p) -> std::unique_ptr<HeatTransferMode> {
        return std::make_unique<FaultInjectionMode>(p);
      },
  };
  return mode;
}

}  // namespace tmdem::testing
