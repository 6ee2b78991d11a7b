#include "coupling/app/RenderCommand.h"

#include <fcntl.h>
#include <spawn.h>
#include <sys/file.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdlib>
#include <filesystem>

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

// Runs argv (argv[0] a full path), its output going to ours; the exit status, or -1.
int run_program(const std::vector<std::string>& argv) {
  std::vector<char*> pointers;
  for (const auto& a : argv) pointers.push_back(const_cast<char*>(a.c_str()));
  pointers.push_back(nullptr);
  pid_t pid = 0;
  if (posix_spawn(&pid, pointers[0], nullptr, nullptr, pointers.data(), environ) != 0) return -1;
  int status = 0;
  while (waitpid(pid, &status, 0) < 0)
    if (errno != EINTR) return -1;
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + (WIFSIGNALED(status) ? WTERMSIG(status) : 0);
}

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
  // Debian's ParaView renders through X: without a display, pvbatch runs under xvfb-run.
  std::vector<std::string> argv;
  const char* display = std::getenv("DISPLAY");
  if (!display || !*display) {
    const std::string xvfb = find_executable("xvfb-run");
    if (xvfb.empty()) {
      log << "error: no X display (DISPLAY is unset) and xvfb-run not found: pvbatch needs one "
             "to render; install xvfb (scripts/setup.sh --with-paraview) or run under a display\n";
      return kExitIo;
    }
    // xvfb-run -a takes the first display number from -n on (given before -a) whose lock file
    // is free; two xvfb-runs started together (ctest -j) or one just after another (whose Xvfb
    // is still going away) can then meet on the same display, and pvbatch aborts with "bad X
    // server connection". Starting from a number of our own makes that rare; a failure is
    // tried again (below).
    argv = {xvfb, "-n", std::to_string(100 + ::getpid() % 5000), "-a"};
  }
  argv.push_back(pvbatch);
  argv.push_back("--force-offscreen-rendering");
  argv.push_back(script);
  argv.push_back(fs::absolute(xdmf).string());
  argv.push_back(options.png_path);
  argv.push_back("--frame");
  argv.push_back(std::to_string(chosen.index));
  if (!options.cut.empty()) argv.insert(argv.end(), {"--cut", options.cut});
  if (options.forces) argv.push_back("--forces");
  if (options.size.size() == 2)
    argv.insert(argv.end(), {"--size", std::to_string(options.size[0]), std::to_string(options.size[1])});

  fs::remove(options.png_path, ec);  // an old image must not pass for a new one
  out.flush();
  // Several xvfb-run + pvbatch at once fail here (3 of 4 started together aborted with "bad X
  // server connection", each on its own display, Xvfb reporting nothing), so renders under
  // xvfb-run wait for each other: an flock on a file in the temporary folder (released when
  // this process exits).
  if (argv[0] != pvbatch) {
    const std::string lock_path = (fs::temp_directory_path(ec) / "tmdem-render-xvfb.lock").string();
    const int lock = ::open(lock_path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0666);
    if (lock >= 0)
      while (::flock(lock, LOCK_EX) != 0 && errno == EINTR) {
      }
  }
  int status = run_program(argv);
  // Under xvfb-run, pvbatch now and then finds no X server ("bad X server connection", then
  // SIGABRT; xvfb-run may then exit with its own code): try twice more on other displays.
  // Exit 2 is the script refusing an argument, which another display would not change.
  for (int attempt = 1; attempt < 3 && status != 0 && status != 2 && argv[0] != pvbatch; ++attempt) {
    log << "pvbatch failed under xvfb-run (exit " << status << "); trying again on another display\n";
    argv[2] = std::to_string(100 + (::getpid() + 1700 * attempt) % 5000);
    status = run_program(argv);
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
