// The message of a failed KLU factorisation (CVODE/IDA's CV_LSETUP_FAIL with klu): what failed,
// from KLU's status, and which thermal.linear_solver to set instead. A real failure needs a
// factor larger than memory (a 10^6-particle 3D bed: hours of factorising first), so the text
// is tested here and the integrators append it (SundialsIntegratorBase::failure_detail).
#include <gtest/gtest.h>

#include <string>

#include "thermal/integrators/ThermalSolverError.h"

using tmdem::thermal::klu_failure_hint;

namespace {

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

TEST(KluFailureHint, OutOfMemoryNamesTheConjugateGradientSolvers) {
  const auto text = klu_failure_hint(-2, 1000000, true);
  EXPECT_TRUE(contains(text, "the sparse LU factorisation (KLU) of the 1000000-unknown Newton "
                             "matrix failed (out of memory"))
      << text;
  EXPECT_TRUE(contains(text, "set thermal.linear_solver = \"amg\" or \"pcg\"")) << text;
  EXPECT_TRUE(contains(text, "valid values: \"auto\", \"klu\", \"pcg\", \"amg\"")) << text;
}

TEST(KluFailureHint, EachStatusSaysWhatFailed) {
  EXPECT_TRUE(contains(klu_failure_hint(1, 10, true), "(singular matrix)"));
  EXPECT_TRUE(contains(klu_failure_hint(-4, 10, true), "overflows an integer"));
  EXPECT_TRUE(contains(klu_failure_hint(-3, 10, true), "(out of memory or singular; KLU status -3)"));
}

TEST(KluFailureHint, AOneSidedJacobianIsNotSentToPcgOrAmg) {
  // pcg and amg refuse it (SundialsIntegratorBase): the hint must not send the user there.
  const auto text = klu_failure_hint(-2, 1000000, false);
  EXPECT_FALSE(contains(text, "set thermal.linear_solver = \"amg\"")) << text;
  EXPECT_TRUE(contains(text, "one-sided")) << text;
  EXPECT_TRUE(contains(text, "only thermal.linear_solver = \"klu\"")) << text;
}

TEST(KluFailureHint, ReadsOnAfterTheSolverFlag) {
  // The integrators put it after "CVODE failed in CVode with CV_LSETUP_FAIL (-6) at t = ...".
  char* flag_name = nullptr;  // from_solver frees it; null prints "?"
  const auto error = tmdem::thermal::ThermalSolverError::from_solver(
      "CVODE", flag_name, -6, "CVode", 0.0, 0.0, 0, klu_failure_hint(-2, 8, true));
  EXPECT_TRUE(contains(error.what(), "CVODE failed in CVode with ? (-6) at t = 0 s, step size 0 s "
                                     "after 0 steps: the sparse LU factorisation (KLU)"))
      << error.what();
  EXPECT_EQ(error.code, -6);
}

}  // namespace
