#pragma once
// The test-only contact solver "wait_for_signal" (see SignalWaitSolver.cpp).
#include <memory>

#include "mechanics/solvers/ContactSolver.h"

namespace tmdem::testing {

std::unique_ptr<mechanics::ContactSolver> make_signal_wait_solver(const mechanics::SolverSettings& settings);

}  // namespace tmdem::testing
