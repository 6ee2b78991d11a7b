// Integrator and linear-solver names are parsed once into kinds; every name round-trips and an
// unknown one is refused with the valid names listed.
#include <gtest/gtest.h>

#include "thermal/integrators/IntegratorKind.h"
#include "thermal/integrators/IntegratorRegistry.h"

using namespace tmdem::thermal;

TEST(IntegratorKind, EveryNameRoundTrips) {
  for (auto name : thermal_integrator_names()) EXPECT_EQ(name_of(parse_integrator_kind(name)), name);
  for (auto name : linear_solver_names()) EXPECT_EQ(name_of(parse_linear_solver_kind(name)), name);
  EXPECT_EQ(parse_integrator_kind("explicit"), IntegratorKind::Explicit);
  EXPECT_EQ(parse_linear_solver_kind("pcg"), LinearSolverKind::Pcg);
  EXPECT_EQ(parse_linear_solver_kind("amg"), LinearSolverKind::Amg);
}

TEST(IntegratorKind, UnknownNamesListTheValidOnes) {
  try {
    parse_integrator_kind("rk4");
    FAIL() << "rk4 accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("valid types are: cvode, ida, explicit"), std::string::npos)
        << e.what();
  }
  EXPECT_THROW(parse_linear_solver_kind("gmres"), std::invalid_argument);
}

// "auto" is resolved by coupling (LinearSolverChoice.h) before a thermal integrator is made; one
// reaching the thermal side is a bug, not a user's unknown name.
TEST(IntegratorKind, AutoIsNoLinearSolverKind) {
  EXPECT_EQ(kDefaultLinearSolverName, "auto");
  EXPECT_THROW(parse_linear_solver_kind(kAutoLinearSolverName), std::logic_error);
  for (auto name : linear_solver_names()) EXPECT_NE(name, kAutoLinearSolverName);
}
