#pragma once
// Owns a SUNDIALS 6 context for the lifetime of one integrator. Everything created in it must be
// freed before it: declare it before the other SUNDIALS owners (SundialsHandles.h).
#include <sundials/sundials_context.h>

#include <string>

#include "thermal/integrators/ThermalSolverError.h"

namespace tmdem::thermal {

class SundialsContext {
 public:
  SundialsContext() {
    if (const int flag = SUNContext_Create(nullptr, &ctx_); flag != 0 || !ctx_)
      throw ThermalSolverError("SUNContext_Create failed (" + std::to_string(flag) + ")", flag);
  }
  ~SundialsContext() { SUNContext_Free(&ctx_); }
  SundialsContext(const SundialsContext&) = delete;
  SundialsContext& operator=(const SundialsContext&) = delete;
  operator SUNContext() const { return ctx_; }

 private:
  SUNContext ctx_ = nullptr;
};

}  // namespace tmdem::thermal
