#include "mechanics/model/StepInterrupt.h"

#include <atomic>

namespace tmdem::mechanics {
namespace {
static_assert(std::atomic<bool>::is_always_lock_free, "a signal handler stores to these");
std::atomic<bool> g_armed{false};
std::atomic<bool> g_requested{false};
}  // namespace

void arm_step_interrupt(bool armed) noexcept { g_armed.store(armed); }

void request_step_interrupt() noexcept {
  if (g_armed.load()) g_requested.store(true);
}

void clear_step_interrupt() noexcept { g_requested.store(false); }

bool step_interrupt_requested() noexcept { return g_requested.load(std::memory_order_relaxed); }

}  // namespace tmdem::mechanics
