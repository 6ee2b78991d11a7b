#pragma once
// Variable-order BDF through IDAS on the DAE form: F = y' - f(y) = 0 for free particles and
// F = y - y_held = 0 (algebraic) for held ones. Same linear solvers and scaling as
// CvodeIntegrator (KLU on the sparse Jacobian cj I - J, or Jacobi-preconditioned CG in
// y = sqrt(C) T); the boundary heat is an IDAS quadrature.
#include <nvector/nvector_serial.h>
#include <sundials/sundials_linearsolver.h>
#include <sundials/sundials_matrix.h>

#include <string>
#include <vector>

#include "thermal/SundialsContext.h"
#include "thermal/ThermalIntegrator.h"
#include "thermal/ThermalSystem.h"

namespace tmdem::thermal {

class IdaIntegrator final : public ThermalIntegrator {
 public:
  IdaIntegrator(ThermalSystem& system, const IntegratorSettings& settings);
  ~IdaIntegrator() override;
  IdaIntegrator(const IdaIntegrator&) = delete;
  IdaIntegrator& operator=(const IdaIntegrator&) = delete;

  std::string_view name() const override { return "ida"; }
  void initialize(double t0_s, std::span<const double> T0_K, double boundary_heat0_J) override;
  void advance_to(double t_s) override;
  void restart() override;
  double time_s() const override { return t_; }
  std::span<const double> temperatures_K() const override { return T_out_; }
  double boundary_heat_J() const override;
  IntegratorStats stats() const override;

 private:
  static int residual(sunrealtype t, N_Vector y, N_Vector yp, N_Vector r, void* self);
  static int boundary_rhs(sunrealtype t, N_Vector y, N_Vector yp, N_Vector qdot, void* self);
  static int jacobian(sunrealtype t, sunrealtype cj, N_Vector y, N_Vector yp, N_Vector r,
                      SUNMatrix J, void* self, N_Vector, N_Vector, N_Vector);
  static int jtimes_setup(sunrealtype t, N_Vector y, N_Vector yp, N_Vector r, sunrealtype cj,
                          void* self);
  static int jtimes(sunrealtype t, N_Vector y, N_Vector yp, N_Vector r, N_Vector v, N_Vector Jv,
                    sunrealtype cj, void* self, N_Vector, N_Vector);
  static int precond_setup(sunrealtype t, N_Vector y, N_Vector yp, N_Vector r, sunrealtype cj,
                           void* self);
  static int precond_solve(sunrealtype t, N_Vector y, N_Vector yp, N_Vector r, N_Vector rv,
                           N_Vector z, sunrealtype cj, sunrealtype delta, void* self);
  static void error_handler(int code, const char* module, const char* function, char* msg,
                            void* self);

  void unscale(N_Vector y);
  void consistent_derivative();         // yp = f(y) for free particles, 0 for held ones
  void reinit_at_current_state();
  void check(int flag, const char* call) const;
  [[noreturn]] void fail(int flag, const char* call) const;

  ThermalSystem& system_;
  IntegratorSettings settings_;
  bool pcg_ = false;
  SundialsContext ctx_;
  void* mem_ = nullptr;
  N_Vector y_ = nullptr, yp_ = nullptr, yQ_ = nullptr, abstol_ = nullptr, id_ = nullptr;
  SUNMatrix A_ = nullptr;
  SUNLinearSolver LS_ = nullptr;
  std::vector<double> scale_;
  std::vector<double> held_value_;      // scaled held temperatures
  std::vector<double> T_work_, dT_work_, precond_diag_;
  std::vector<double> T_out_;
  double t_ = 0.0;
  double boundary_heat0_J_ = 0.0;
  std::uint64_t topology_seen_ = 0;
  IntegratorStats before_reinit_;
  long reinitializations_ = 0;
  std::string last_error_;
};

}  // namespace tmdem::thermal
