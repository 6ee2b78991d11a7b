#include "coupling/run/Interruption.h"

#include <unistd.h>

#include <atomic>
#include <csignal>
#include <cstddef>

#include "mechanics/model/StepInterrupt.h"

namespace tmdem::coupling {
namespace {

constexpr const char kRunNotice[] =
    "\ninterrupt received: stopping after the last whole step (a mechanics step still being "
    "solved is given up, to be taken again on restart), then writing a last frame and a "
    "checkpoint (while settling: a settle checkpoint, from which --restart resumes the "
    "settle); a second signal aborts at once\n";

std::atomic<int> g_signal{0};
std::atomic<bool> g_quiet{false};
std::atomic<const char*> g_notice{kRunNotice};  // a string that outlives the handler
struct sigaction g_previous_int {}, g_previous_term {};

extern "C" void on_signal(int signal) {
  if (g_signal.load() != 0) {
    // Second signal: abort now, with the default action of this signal.
    std::signal(signal, SIG_DFL);
    std::raise(signal);
    return;
  }
  g_signal.store(signal);
  mechanics::request_step_interrupt();  // lock-free atomics: async-signal-safe (does nothing unarmed)
  if (!g_quiet.load()) {
    const char* notice = g_notice.load();
    std::size_t length = 0;  // strlen, which is not async-signal-safe
    while (notice[length] != '\0') ++length;
    const ssize_t ignored = ::write(STDERR_FILENO, notice, length);
    (void)ignored;
  }
}

}  // namespace

Interruption::Interruption(bool quiet, const char* notice, bool give_up_mechanics_step) {
  g_signal.store(0);
  mechanics::clear_step_interrupt();
  mechanics::arm_step_interrupt(give_up_mechanics_step);
  g_quiet.store(quiet);
  g_notice.store(notice ? notice : kRunNotice);
  struct sigaction action {};
  action.sa_handler = on_signal;
  sigemptyset(&action.sa_mask);
  action.sa_flags = SA_RESTART;  // system calls of the step in progress carry on
  sigaction(SIGINT, &action, &g_previous_int);
  sigaction(SIGTERM, &action, &g_previous_term);
}

Interruption::~Interruption() {
  mechanics::arm_step_interrupt(false);
  mechanics::clear_step_interrupt();
  sigaction(SIGINT, &g_previous_int, nullptr);
  sigaction(SIGTERM, &g_previous_term, nullptr);
}

int Interruption::pending() { return g_signal.load(); }

const char* signal_name(int signal) {
  return signal == SIGINT ? "SIGINT" : signal == SIGTERM ? "SIGTERM" : "signal";
}

}  // namespace tmdem::coupling
