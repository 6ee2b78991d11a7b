#pragma once
// Owns a SUNDIALS 6 context for the lifetime of one integrator.
#include <sundials/sundials_context.h>

#include <stdexcept>

namespace tmdem::thermal {

class SundialsContext {
 public:
  SundialsContext() {
    if (SUNContext_Create(nullptr, &ctx_) != 0) throw std::runtime_error("SUNContext_Create failed");
  }
  ~SundialsContext() { SUNContext_Free(&ctx_); }
  SundialsContext(const SundialsContext&) = delete;
  SundialsContext& operator=(const SundialsContext&) = delete;
  operator SUNContext() const { return ctx_; }

 private:
  SUNContext ctx_ = nullptr;
};

}  // namespace tmdem::thermal
