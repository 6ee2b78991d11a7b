#pragma once
// The test-only fault_injection heat-transfer mode (see FaultInjectionMode.cpp).
#include "thermal/modes/ModeDescription.h"

namespace tmdem::testing {

const thermal::ModeDescription& fault_injection_mode();

}  // namespace tmdem::testing
