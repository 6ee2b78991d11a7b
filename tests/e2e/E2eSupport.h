#pragma once
// Runs the tmdem program and reads its HDF5 output back for end-to-end checks.
#include <H5Cpp.h>
#include <nlohmann/json.hpp>
#include <fcntl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "support/SceneBuilder.h"
#include "support/ScratchDir.h"

namespace tmdem::e2e {

using namespace tmdem::test;

struct ProgramResult {
  int exit_code = -1;
  std::string output;  // stdout and stderr together
};

// `environment`: "VAR=value ..." for env(1) (e.g. "-u DISPLAY"), empty for the test's own.
// `launcher`: a command that starts the program (e.g. "mpirun -np 2"), empty for none.
// tmdem started in `cwd` (relative paths in a scene are relative to it: the contract), its
// output logged in log_dir.
inline ProgramResult run_tmdem_from(const std::string& args, const std::string& cwd, const std::string& log_dir,
                                    const std::string& environment = "", const std::string& launcher = "") {
  const std::string log = log_dir + "/tmdem.log";
  const std::string program = (environment.empty() ? "" : "env " + environment + " ") +
                              (launcher.empty() ? "" : launcher + " ") + "'" + TMDEM_BINARY + "'";
  const std::string cmd = "cd '" + cwd + "' && " + program + " " + args + " > '" + log + "' 2>&1";
  const int status = std::system(cmd.c_str());
  ProgramResult r;
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  std::ifstream in(log);
  std::stringstream ss;
  ss << in.rdbuf();
  r.output = ss.str();
  return r;
}

inline ProgramResult run_tmdem(const std::string& args, const std::string& workdir,
                               const std::string& environment = "", const std::string& launcher = "") {
  return run_tmdem_from(args, workdir, workdir, environment, launcher);
}

// A fresh empty folder per test, removed once the test passes (support/ScratchDir.h).
// tmdem started with `args` in `dir`, not waited for (a test that signals a run): its stdout
// and stderr go to dir/child.log. The child's pid, or -1.
// `binary`: tmdem, or TMDEM_TESTING_BINARY for the testing aids (tests/program/).
inline pid_t spawn_tmdem(const std::vector<std::string>& args, const std::string& dir,
                         const char* binary = TMDEM_BINARY) {
  const pid_t pid = fork();
  if (pid != 0) return pid;
  if (chdir(dir.c_str()) != 0) _exit(127);
  const int fd = open("child.log", O_WRONLY | O_CREAT | O_TRUNC, 0644);
  dup2(fd, 1);
  dup2(fd, 2);
  std::vector<char*> argv{const_cast<char*>(binary)};
  for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  execv(binary, argv.data());
  _exit(127);
}

// Waits until dir/child.log (spawn_tmdem) holds `text`, then sends `signal` to the child (unless
// it ended first, or after two minutes) and waits for it to end: its waitpid status.
inline int signal_once_logged(pid_t child, const std::string& dir, const std::string& text, int signal) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(120);
  int status = 0;
  while (std::chrono::steady_clock::now() < deadline) {
    if (waitpid(child, &status, WNOHANG) == child) return status;  // ended before the signal
    std::ifstream log(dir + "/child.log");
    const std::string logged((std::istreambuf_iterator<char>(log)), std::istreambuf_iterator<char>());
    if (logged.find(text) != std::string::npos) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  kill(child, signal);
  waitpid(child, &status, 0);
  return status;
}

inline std::string scratch_dir(const std::string& name) {
  return tmdem::test::scratch_folder("tmdem_e2e_", name);
}

inline void write_file(const std::string& path, const std::string& text) {
  std::ofstream(path) << text;
}

// The whole of a text file ("" when it cannot be read).
inline std::string text_of(const std::string& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// `value` with 17 significant digits: a --set value that reads back as the same double.
inline std::string number(double value) {
  std::ostringstream out;
  out.precision(17);
  out << value;
  return out.str();
}

// How often `part` occurs in `text` (overlapping occurrences counted).
inline std::size_t count_of(const std::string& text, const std::string& part) {
  std::size_t n = 0;
  for (auto at = text.find(part); at != std::string::npos; at = text.find(part, at + 1)) ++n;
  return n;
}

// A 2D copper scene under gravity with dynamic mechanics; tests add the particles and walls.
inline SceneBuilder copper_drop_scene(double duration_s) {
  return SceneBuilder()
      .set({{"simulation.duration", duration_s},
            {"simulation.dimension", 2},
            {"simulation.gravity", {0.0, -9.81, 0.0}},
            {"effects.mechanics", "dynamic"}})
      .add("material", copper());
}

// One steel sphere 9 mm above the floor, settled for 10 steps of 1 ms: free fall all along, so
// after k steps its speed is k h g exactly (the Moreau-Jean velocity update).
inline std::string falling_sphere_scene() {
  return steel_scene()
      .set({{"simulation.duration", 1.0},
            {"simulation.dimension", 3},
            {"simulation.gravity", {0.0, -9.81, 0.0}},
            {"effects.mechanics", "settle"},
            {"mechanics.time_step", 1.0e-3},
            {"mechanics.settle_time", 0.01}})
      .add("particle", particle({0.0, 0.01, 0.0}))
      .add("wall", floor_wall())
      .set(output("out.h5", 0.5))
      .str();
}

inline nlohmann::json read_summary(const std::string& path) {
  std::ifstream in(path);
  return nlohmann::json::parse(in);
}

inline std::vector<double> read_doubles(const H5::H5File& f, const std::string& name,
                                        std::vector<hsize_t>* dims = nullptr) {
  H5::DataSet ds = f.openDataSet(name);
  H5::DataSpace sp = ds.getSpace();
  std::vector<hsize_t> d(std::size_t(sp.getSimpleExtentNdims()));
  sp.getSimpleExtentDims(d.data());
  hsize_t n = 1;
  for (auto x : d) n *= x;
  std::vector<double> out(n);
  if (n) ds.read(out.data(), H5::PredType::NATIVE_DOUBLE);
  if (dims) *dims = d;
  return out;
}

inline std::vector<long long> read_ints(const H5::H5File& f, const std::string& name) {
  H5::DataSet ds = f.openDataSet(name);
  H5::DataSpace sp = ds.getSpace();
  std::vector<hsize_t> d(std::size_t(sp.getSimpleExtentNdims()));
  sp.getSimpleExtentDims(d.data());
  hsize_t n = 1;
  for (auto x : d) n *= x;
  std::vector<long long> out(n);
  if (n) ds.read(out.data(), H5::PredType::NATIVE_LLONG);
  return out;
}

// A result file's contacts: all frames' (pair: 2 per contact), frame f's being
// offset[f] .. offset[f + 1] - 1.
struct ResultContactData {
  std::vector<long long> pair, offset;
  std::vector<double> normal_force_N, conductance_W_per_K;
};

inline ResultContactData read_contact_data(const H5::H5File& f) {
  return {read_ints(f, "/contacts/pair"), read_ints(f, "/frames/contact_offset"),
          read_doubles(f, "/contacts/normal_force"), read_doubles(f, "/contacts/conductance")};
}

inline std::string read_string_attribute(const H5::H5Object& obj, const std::string& name) {
  H5::Attribute a = obj.openAttribute(name);
  std::string value;
  a.read(a.getStrType(), value);
  return value;
}

}  // namespace tmdem::e2e
