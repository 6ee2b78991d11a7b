#pragma once
// What the heat-transfer mode tests share (test_modes_exact_answers.cpp and
// test_modes_registry_and_domain.cpp): the energy-balance check every run makes, and the
// ModeTest fixture run for every integrator (instantiated once, in test_modes_exact_answers.cpp).
#include <gtest/gtest.h>

#include <cstdio>
#include <span>
#include <string>

#include "thermal/ThermalTestSupport.h"

namespace tmdem::thermal::mode_test {

inline constexpr double kBalanceTolerance = 1e-8;

// Prints the measured balance so the figure is visible in the test log, and checks it.
inline void expect_balance(const ThermalSystem& sys, std::span<const double> T0,
                           const ThermalIntegrator& integ, const std::string& what) {
  const double err = testing::balance_error_rel(sys, T0, integ);
  std::printf("[ balance  ] %-52s %s t = %-8g balance_error_rel = %.2e\n", what.c_str(),
              std::string(integ.name()).c_str(), integ.time_s(), err);
  EXPECT_LT(err, kBalanceTolerance) << what << " at t = " << integ.time_s();
}

inline std::string test_name() {
  return ::testing::UnitTest::GetInstance()->current_test_info()->name();
}

class ModeTest : public ::testing::TestWithParam<testing::IntegratorCase> {};

}  // namespace tmdem::thermal::mode_test
