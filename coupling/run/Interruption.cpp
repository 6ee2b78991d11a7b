#include "coupling/run/Interruption.h"

#include <unistd.h>

#include <atomic>
#include <csignal>
#include <cstddef>
#include <cstdint>
#include <ctime>

#include "mechanics/model/StepInterrupt.h"

namespace tmdem::coupling {
namespace {

constexpr const char kRunNotice[] =
    "\ninterrupt received: stopping after the last whole step (a mechanics step still being "
    "solved is given up, to be taken again on restart), then writing a last frame and a "
    "checkpoint (while settling: a settle checkpoint, from which --restart resumes the "
    "settle); a second signal, a second or more later, aborts at once\n";

std::atomic<int> g_signal{0};
constexpr std::int64_t kSameRequestNs = 1000000000;  // 1 s
std::atomic<bool> g_quiet{false};
std::atomic<const char*> g_notice{kRunNotice};  // a string that outlives the handler
struct sigaction g_previous_int {}, g_previous_term {};

// CLOCK_MONOTONIC in ns (clock_gettime is async-signal-safe).
std::int64_t monotonic_ns() {
  timespec now{};
  clock_gettime(CLOCK_MONOTONIC, &now);
  return std::int64_t(now.tv_sec) * 1000000000 + now.tv_nsec;
}

std::atomic<std::int64_t> g_first_signal_ns{0};

extern "C" void on_signal(int signal) {
  if (g_signal.load() != 0) {
    // A repeat within kSameRequestNs of the first is the same request: `timeout` sends its
    // SIGTERM to the command and then to the command's process group, so a run stopped by
    // `timeout` got two at once and aborted, writing neither its summary nor its checkpoint.
    if (monotonic_ns() - g_first_signal_ns.load() < kSameRequestNs) return;
    // Second signal: abort now, with the default action of this signal.
    std::signal(signal, SIG_DFL);
    std::raise(signal);
    return;
  }
  g_first_signal_ns.store(monotonic_ns());
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
