// tmdem_testing: the tmdem program plus the test-only heat-transfer modes and contact solvers.
// The production binary never registers them, so it neither contains nor honours them.
#include "FaultInjectionMode.h"
#include "SignalWaitSolver.h"
#include "mechanics/solvers/ContactSolverRegistry.h"
#include "coupling/app/TmdemMain.h"
#include "thermal/modes/ModeRegistry.h"

int main(int argc, char** argv) {
  tmdem::thermal::register_heat_transfer_mode(tmdem::testing::fault_injection_mode());
  tmdem::mechanics::register_contact_solver("wait_for_signal", &tmdem::testing::make_signal_wait_solver);
  return tmdem::coupling::tmdem_main(argc, argv);
}
