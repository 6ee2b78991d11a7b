#include "coupling/app/RenderCommand.h"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <spawn.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "coupling/app/FrameOption.h"
#include "coupling/common/ExitCode.h"
#include "coupling/output/ResultFrameReader.h"
#include "coupling/output/XdmfWriter.h"

extern char** environ;

namespace tmdem::coupling {

namespace fs = std::filesystem;

namespace {

bool executable(const fs::path& path) {
  std::error_code ec;
  return fs::is_regular_file(path, ec) && ::access(path.c_str(), X_OK) == 0;
}

// Runs argv (argv[0] a full path), its output going to ours, with the environment `env`
// (nullptr: ours); the exit status, or -1.
int run_program(const std::vector<std::string>& argv, char* const* env = nullptr) {
  std::vector<char*> pointers;
  for (const auto& a : argv) pointers.push_back(const_cast<char*>(a.c_str()));
  pointers.push_back(nullptr);
  pid_t pid = 0;
  if (posix_spawn(&pid, pointers[0], nullptr, nullptr, pointers.data(), env ? env : environ) != 0)
    return -1;
  int status = 0;
  while (waitpid(pid, &status, 0) < 0)
    if (errno != EINTR) return -1;
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + (WIFSIGNALED(status) ? WTERMSIG(status) : 0);
}

// A virtual X server of our own, for pvbatch when there is no display. pvbatch connects, goes
// away and connects again (ParaView probes OpenGL first); an X server resets when its last client
// leaves and drops connections made meanwhile, so under load pvbatch found its second connection
// hung up ("bad X server connection", then SIGABRT: with xvfb-run, 6 of 20 renders four at a time
// beside two busy loops needed a second try, and a clean-clone CI run failed all three tries of
// one). Hence -noreset. With -displayfd, Xvfb takes a display number no other server holds and
// writes it once it accepts connections, so renders started together need no lock (6 at a time
// beside two busy loops, 3 rounds: none failed; without -noreset 4 of 12 did).
class VirtualDisplay {
 public:
  // Starts `xvfb` and waits up to `timeout_s` for its display number; display() is "" on
  // failure, and why() says what Xvfb printed.
  VirtualDisplay(const std::string& xvfb, double timeout_s) {
    std::error_code ec;
    log_path_ = (fs::temp_directory_path(ec) / ("tmdem-xvfb-" + std::to_string(::getpid()) + ".log"))
                    .string();
    int fds[2];
    if (::pipe2(fds, O_CLOEXEC) != 0) {
      why_ = std::string("pipe: ") + std::strerror(errno);
      return;
    }
    const std::string fd_text = std::to_string(fds[1]);
    // Everything the child needs, prepared before fork (only async-signal-safe calls after it).
    const std::vector<std::string> args = {xvfb, "-displayfd", fd_text, "-noreset", "-nolisten", "tcp",
                                           "-screen", "0", "1600x1200x24"};
    std::vector<char*> argv;
    for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    const pid_t parent = ::getpid();
    pid_ = ::fork();
    if (pid_ == 0) {
      // The server goes when we do, even if we are killed: no Xvfb left behind.
      ::prctl(PR_SET_PDEATHSIG, SIGTERM);
      if (::getppid() != parent) ::_exit(127);
      const int log_fd = ::open(log_path_.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
      if (log_fd >= 0) {
        ::dup2(log_fd, 1);
        ::dup2(log_fd, 2);
      }
      ::fcntl(fds[1], F_SETFD, 0);  // the write end, kept open across exec for -displayfd
      ::execv(argv[0], argv.data());
      ::_exit(127);
    }
    ::close(fds[1]);
    if (pid_ < 0) {
      ::close(fds[0]);
      why_ = std::string("fork: ") + std::strerror(errno);
      return;
    }
    std::string number;
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
    for (;;) {
      const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
                            deadline - std::chrono::steady_clock::now()).count();
      if (left <= 0) break;
      pollfd p{fds[0], POLLIN, 0};
      const int ready = ::poll(&p, 1, static_cast<int>(left));
      if (ready < 0 && errno == EINTR) continue;
      if (ready <= 0) break;
      char buffer[32];
      const ssize_t n = ::read(fds[0], buffer, sizeof buffer);
      if (n < 0 && errno == EINTR) continue;
      if (n <= 0) break;  // Xvfb exited (or closed the pipe) without a number
      number.append(buffer, static_cast<std::size_t>(n));
      if (number.find('\n') != std::string::npos) break;
    }
    ::close(fds[0]);
    while (!number.empty() && (number.back() == '\n' || number.back() == '\r')) number.pop_back();
    if (!number.empty() && number.find_first_not_of("0123456789") == std::string::npos) {
      display_ = ":" + number;
      return;
    }
    std::ifstream in(log_path_);
    std::stringstream text;
    text << in.rdbuf();
    why_ = "Xvfb gave no display within " + std::to_string(static_cast<int>(timeout_s)) + " s" +
           (text.str().empty() ? std::string() : "; it printed:\n" + text.str());
  }
  ~VirtualDisplay() {
    if (pid_ > 0) {
      ::kill(pid_, SIGTERM);
      int status = 0;
      while (::waitpid(pid_, &status, 0) < 0 && errno == EINTR) {
      }
    }
    std::error_code ec;
    fs::remove(log_path_, ec);
  }
  VirtualDisplay(const VirtualDisplay&) = delete;
  VirtualDisplay& operator=(const VirtualDisplay&) = delete;

  const std::string& display() const { return display_; }
  const std::string& why() const { return why_; }

 private:
  pid_t pid_ = -1;
  std::string display_, why_, log_path_;
};

// Our environment with DISPLAY set to `display`: the strings and the pointer array execve takes.
struct Environment {
  std::vector<std::string> entries;
  std::vector<char*> pointers;
  explicit Environment(const std::string& display) {
    for (char** e = environ; *e; ++e)
      if (std::strncmp(*e, "DISPLAY=", 8) != 0) entries.emplace_back(*e);
    entries.push_back("DISPLAY=" + display);
    for (auto& e : entries) pointers.push_back(e.data());
    pointers.push_back(nullptr);
  }
};

const char* kInstallHint =
    "install ParaView's pvbatch: apt-get install paraview python3-paraview xvfb "
    "(scripts/setup.sh --with-paraview), or set TMDEM_PVBATCH to a pvbatch";

}  // namespace

std::string find_executable(const std::string& name) {
  if (name.find('/') != std::string::npos) return executable(name) ? name : "";
  const char* path = std::getenv("PATH");
  std::string dirs = path ? path : "/usr/local/bin:/usr/bin:/bin";
  std::size_t start = 0;
  while (start <= dirs.size()) {
    const std::size_t end = std::min(dirs.find(':', start), dirs.size());
    const fs::path candidate = fs::path(end > start ? dirs.substr(start, end - start) : ".") / name;
    if (executable(candidate)) return candidate.string();
    start = end + 1;
  }
  return "";
}

std::string find_render_script() {
  std::error_code ec;
  if (const char* set = std::getenv("TMDEM_RENDER_SCRIPT"); set && *set)
    return fs::is_regular_file(set, ec) ? std::string(set) : "";
  const fs::path self = fs::read_symlink("/proc/self/exe", ec);
  if (!ec && fs::is_regular_file(self.parent_path() / "tmdem_render.py", ec))
    return (self.parent_path() / "tmdem_render.py").string();
#ifdef TMDEM_RENDER_SCRIPT_SOURCE
  if (fs::is_regular_file(TMDEM_RENDER_SCRIPT_SOURCE, ec)) return TMDEM_RENDER_SCRIPT_SOURCE;
#endif
  return "";
}

int run_render_command(const RenderOptions& options, std::ostream& out, std::ostream& log) {
  const std::optional<std::int64_t> parsed = parse_frame_option(options.frame);
  if (!parsed) {
    log << "error: --frame must be \"last\" or a frame number (got \"" << options.frame << "\")\n";
    return kExitInvalid;
  }
  const std::int64_t frame = *parsed;
  if (!options.cut.empty() && options.cut != "x" && options.cut != "y" && options.cut != "z") {
    log << "error: --cut must be x, y or z (got \"" << options.cut << "\")\n";
    return kExitInvalid;
  }
  if (fs::path(options.png_path).extension() != ".png") {
    log << "error: -o must name a .png file (got \"" << options.png_path << "\")\n";
    return kExitInvalid;
  }
  ResultFrame chosen;
  try {
    chosen = read_result_frame(options.result_path, frame);
  } catch (const FrameOutOfRange& e) {
    log << "error: " << e.what() << "\n";
    return kExitInvalid;
  } catch (const std::runtime_error& e) {
    log << "error: " << e.what() << "\n";
    return kExitIo;
  }
  const std::string xdmf = xdmf_path_for(options.result_path);
  std::error_code ec;
  if (!fs::is_regular_file(xdmf, ec)) {
    log << "error: " << xdmf << " does not exist: ParaView reads the result through it "
        << "(tmdem run writes it next to " << options.result_path << ")\n";
    return kExitIo;
  }

  const char* chosen_pvbatch = std::getenv("TMDEM_PVBATCH");
  const std::string pvbatch =
      find_executable(chosen_pvbatch && *chosen_pvbatch ? chosen_pvbatch : "pvbatch");
  if (pvbatch.empty()) {
    log << "error: pvbatch not found"
        << (chosen_pvbatch && *chosen_pvbatch ? std::string(" (TMDEM_PVBATCH=") + chosen_pvbatch + ")"
                                              : std::string(" on PATH"))
        << "; " << kInstallHint << "\n";
    return kExitIo;
  }
  const std::string script = find_render_script();
  if (script.empty()) {
    log << "error: tmdem_render.py not found (looked at $TMDEM_RENDER_SCRIPT, next to the tmdem "
           "program, and in the source checkout's coupling/app/)\n";
    return kExitIo;
  }
  // Debian's ParaView renders through X: without a display, pvbatch gets a virtual one (Xvfb).
  const char* display = std::getenv("DISPLAY");
  std::string xvfb;
  if (!display || !*display) {
    xvfb = find_executable("Xvfb");
    if (xvfb.empty()) {
      log << "error: no X display (DISPLAY is unset) and Xvfb not found: pvbatch needs one to "
             "render; install xvfb (scripts/setup.sh --with-paraview) or run under a display\n";
      return kExitIo;
    }
  }
  std::vector<std::string> argv = {pvbatch, "--force-offscreen-rendering", script,
                                   fs::absolute(xdmf).string(), options.png_path, "--frame",
                                   std::to_string(chosen.index)};
  if (!options.cut.empty()) argv.insert(argv.end(), {"--cut", options.cut});
  if (options.forces) argv.push_back("--forces");
  if (options.size.size() == 2)
    argv.insert(argv.end(), {"--size", std::to_string(options.size[0]), std::to_string(options.size[1])});

  fs::remove(options.png_path, ec);  // an old image must not pass for a new one
  out.flush();
  int status = -1;
  if (xvfb.empty()) {
    status = run_program(argv);
  } else {
    // A failure is still tried twice more, each on a new server; exit 2 is the script refusing an
    // argument, which another server would not change.
    for (int attempt = 0; attempt < 3; ++attempt) {
      VirtualDisplay server(xvfb, 30.0);
      if (server.display().empty()) {
        log << "could not start Xvfb (" << xvfb << ", try " << attempt + 1 << " of 3): "
            << server.why() << "\n";
        status = -1;
        continue;
      }
      Environment env(server.display());
      status = run_program(argv, env.pointers.data());
      if (status == 0 || status == 2) break;
      if (attempt < 2)
        log << "pvbatch failed on the virtual display " << server.display() << " (exit " << status
            << "); trying again on a new one\n";
    }
  }
  if (status != 0 || !fs::is_regular_file(options.png_path, ec)) {
    log << "error: pvbatch " << (status < 0 ? std::string("could not be started")
                                            : "exited with " + std::to_string(status))
        << (status == 0 ? " but wrote no " + options.png_path : std::string())
        << " (its output is above)\n";
    return status == 2 ? kExitInvalid : kExitIo;
  }
  out << "rendered frame " << chosen.index << " (t = " << chosen.time_s << " s) of "
      << options.result_path << " to " << options.png_path << "\n";
  return kExitOk;
}

}  // namespace tmdem::coupling
