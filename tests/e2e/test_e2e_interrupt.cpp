// End to end: SIGTERM to a running dynamic scene finishes the step, writes a last frame and a
// checkpoint, marks result and summary "interrupted", says how to resume and exits 143; a second
// writer of the same result meanwhile is refused; the checkpoint resumes to a completed run, bit
// for bit the run that never stopped (given the same checkpoint times).
#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <thread>

#include "E2eSupport.h"
#include "ResultComparison.h"

using namespace tmdem::e2e;
namespace fs = std::filesystem;

namespace {

std::size_t frames_in_xdmf(const std::string& path) {
  const std::string text = text_of(path);
  std::size_t n = 0;
  for (auto at = text.find("<Grid Name=\"particles\" GridType=\"Uniform\""); at != std::string::npos;
       at = text.find("<Grid Name=\"particles\" GridType=\"Uniform\"", at + 1))
    ++n;
  return n;
}

// " a b c": arguments for run_tmdem's command line.
std::string joined(const std::vector<std::string>& args) {
  std::string out;
  for (const auto& a : args) out += " " + a;
  return out;
}

TEST(EndToEndInterrupt, SigtermLeavesInterruptedResultSummaryCheckpointAndExit143) {
  const auto dir = scratch_dir("interrupt");
  fs::copy_file(fs::path(TMDEM_SOURCE_DIR) / "examples" / "poured_bed.toml", dir + "/bed.toml");
  const pid_t child = spawn_tmdem({"run", "bed.toml", "--quiet", "-o", "out.h5", "--summary",
                                   "s.json", "--set", "simulation.duration=50"},
                                  dir);
  ASSERT_GT(child, 0);
  // Wait until the run has written a few frames (the XDMF follows every frame).
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (frames_in_xdmf(dir + "/out.xdmf") < 3 && std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  ASSERT_GE(frames_in_xdmf(dir + "/out.xdmf"), 3u) << text_of(dir + "/child.log");

  // A second writer of the same file is refused while the first runs, naming the file.
  const auto second = run_tmdem("run bed.toml --quiet --overwrite -o out.h5 "
                                "--set simulation.duration=50",
                                dir);
  EXPECT_EQ(second.exit_code, 4) << second.output;
  EXPECT_NE(second.output.find("out.h5"), std::string::npos) << second.output;
  EXPECT_NE(second.output.find("another process"), std::string::npos) << second.output;

  ASSERT_EQ(kill(child, SIGTERM), 0);
  int status = 0;
  ASSERT_EQ(waitpid(child, &status, 0), child);
  const std::string log = text_of(dir + "/child.log");
  ASSERT_TRUE(WIFEXITED(status)) << log;
  EXPECT_EQ(WEXITSTATUS(status), 143) << log;
  EXPECT_NE(log.find("interrupted by SIGTERM"), std::string::npos) << log;
  EXPECT_NE(log.find("--restart out.checkpoint.h5"), std::string::npos) << log;

  double interrupted_at_s = 0.0;
  std::size_t frames = 0;
  {
    H5::H5File file(dir + "/out.h5", H5F_ACC_RDONLY);
    EXPECT_EQ(read_string_attribute(file, "status"), "interrupted");
    const auto times = read_doubles(file, "/frames/time");
    ASSERT_GE(times.size(), 3u);
    frames = times.size();
    interrupted_at_s = times.back();
    H5::H5File checkpoint(dir + "/out.checkpoint.h5", H5F_ACC_RDONLY);
    double checkpoint_time_s = -1.0;
    checkpoint.openAttribute("time_s").read(H5::PredType::NATIVE_DOUBLE, &checkpoint_time_s);
    EXPECT_EQ(checkpoint_time_s, interrupted_at_s);  // the last frame is the checkpoint's moment
    EXPECT_LT(interrupted_at_s, 50.0);
  }
  EXPECT_EQ(frames_in_xdmf(dir + "/out.xdmf"), frames);
  const auto summary = read_summary(dir + "/s.json");
  EXPECT_EQ(summary["status"], "interrupted");
  EXPECT_DOUBLE_EQ(summary["simulated_time_s"].get<double>(), interrupted_at_s);

  // The checkpoint resumes: a little further, then the run completes.
  std::ostringstream end;
  end << interrupted_at_s + 0.03;
  const auto resumed = run_tmdem("run bed.toml --quiet -o out.h5 --restart out.checkpoint.h5 "
                                 "--set simulation.duration=" + end.str(),
                                 dir);
  ASSERT_EQ(resumed.exit_code, 0) << resumed.output;
  H5::H5File file(dir + "/out.h5", H5F_ACC_RDONLY);
  EXPECT_EQ(read_string_attribute(file, "status"), "ok");
  const auto times = read_doubles(file, "/frames/time");
  EXPECT_GT(times.size(), frames);
  for (std::size_t f = 1; f < times.size(); ++f) EXPECT_LT(times[f - 1], times[f]) << f;
  EXPECT_NEAR(times.back(), interrupted_at_s + 0.03, 1e-9);
}

// Rows [first, first + count) of a dataset with `width` values per row.
std::vector<double> rows(const std::vector<double>& values, std::size_t row, std::size_t width) {
  return {values.begin() + std::ptrdiff_t(row * width), values.begin() + std::ptrdiff_t((row + 1) * width)};
}

// A run stopped by timeout(1), as scripts and the gauntlet stop runs: timeout sends its SIGTERM to
// the command and then to the command's process group, two signals at once. They are one request:
// the run writes its summary, result and checkpoint as for one signal (it used to abort on the
// second, leaving none of them).
TEST(EndToEndInterrupt, TimeoutsTwoSigtermsAtOnceAreOneRequest) {
  const auto dir = scratch_dir("interrupt_timeout");
  fs::copy_file(fs::path(TMDEM_SOURCE_DIR) / "examples" / "poured_bed.toml", dir + "/bed.toml");
  const auto r = run_tmdem("run bed.toml --quiet -o out.h5 --summary s.json --set simulation.duration=500", dir, "",
                           "timeout -s TERM 6");
  EXPECT_EQ(r.exit_code, 124) << r.output;  // timeout's own: the time ran out
  EXPECT_NE(r.output.find("interrupted by SIGTERM"), std::string::npos) << r.output;
  ASSERT_TRUE(fs::exists(dir + "/s.json")) << r.output;
  EXPECT_EQ(read_summary(dir + "/s.json")["status"], "interrupted");
  EXPECT_TRUE(fs::exists(dir + "/out.checkpoint.h5")) << r.output;
  H5::H5File file(dir + "/out.h5", H5F_ACC_RDONLY);
  EXPECT_EQ(read_string_attribute(file, "status"), "interrupted");
}

TEST(EndToEndInterrupt, SigtermThenResumeEndsBitwiseWhereTheUninterruptedRunEnds) {
  const auto dir = scratch_dir("interrupt_resume");
  const auto reference = scratch_dir("interrupt_reference");
  for (const auto& d : {dir, reference})
    fs::copy_file(fs::path(TMDEM_SOURCE_DIR) / "examples" / "poured_bed.toml", d + "/bed.toml");
  const pid_t child = spawn_tmdem({"run", "bed.toml", "--quiet", "-o", "out.h5", "--set",
                                   "simulation.duration=50"},
                                  dir);
  ASSERT_GT(child, 0);
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (frames_in_xdmf(dir + "/out.xdmf") < 4 && std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  ASSERT_EQ(kill(child, SIGTERM), 0);
  int status = 0;
  ASSERT_EQ(waitpid(child, &status, 0), child);
  ASSERT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 143) << text_of(dir + "/child.log");
  double stopped_s = -1.0;
  {
    H5::H5File checkpoint(dir + "/out.checkpoint.h5", H5F_ACC_RDONLY);
    checkpoint.openAttribute("time_s").read(H5::PredType::NATIVE_DOUBLE, &stopped_s);
  }
  ASSERT_GT(stopped_s, 0.0);

  // The run that never stopped has its checkpoint (an integration boundary) at the moment the
  // signal stopped the other one; both go on 0.03 s past it.
  const std::string settings = " --set simulation.duration=" + number(stopped_s + 0.03) +
                               " --set output.checkpoint_interval=" + number(stopped_s);
  auto r = run_tmdem("run bed.toml --quiet -o out.h5 --summary s.json" + settings, reference);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  r = run_tmdem("run bed.toml --quiet -o out.h5 --restart out.checkpoint.h5 --summary s.json" + settings, dir);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_EQ(summary_without_wall_times(reference + "/s.json"), summary_without_wall_times(dir + "/s.json"));

  // Frame for frame at the times both files hold (the resumed one also has the frame written at
  // the signal), bit for bit; then the contacts of the last frame.
  H5::H5File a(reference + "/out.h5", H5F_ACC_RDONLY), b(dir + "/out.h5", H5F_ACC_RDONLY);
  const auto ta = read_doubles(a, "/frames/time"), tb = read_doubles(b, "/frames/time");
  const std::size_t n = read_doubles(a, "/particles/radius").size();
  std::size_t matched = 0;
  for (const std::string name : {"position", "velocity", "temperature", "boundary_heat", "thermal_energy"}) {
    const auto va = read_doubles(a, "/frames/" + name), vb = read_doubles(b, "/frames/" + name);
    const std::size_t width = va.size() / ta.size();
    ASSERT_EQ(width, name == "position" || name == "velocity" ? 3 * n : name == "temperature" ? n : 1u);
    for (std::size_t fa = 0; fa < ta.size(); ++fa) {
      const auto fb = std::find(tb.begin(), tb.end(), ta[fa]);
      ASSERT_NE(fb, tb.end()) << "frame at " << ta[fa] << " s missing after the resume";
      EXPECT_TRUE(rows(va, fa, width) == rows(vb, std::size_t(fb - tb.begin()), width))
          << name << " differs at t = " << ta[fa] << " s";
      ++matched;
    }
  }
  EXPECT_GE(matched, 5 * 4u);
  EXPECT_EQ(ta.back(), tb.back());
  const auto offset_a = read_ints(a, "/frames/contact_offset"), offset_b = read_ints(b, "/frames/contact_offset");
  for (const std::string name : {"normal_force", "tangential_force", "conductance"}) {
    const auto ca = read_doubles(a, "/contacts/" + name), cb = read_doubles(b, "/contacts/" + name);
    const std::size_t width = name == "tangential_force" ? 3 : 1;
    const std::vector<double> last_a(ca.begin() + std::ptrdiff_t(width * offset_a[offset_a.size() - 2]), ca.end());
    const std::vector<double> last_b(cb.begin() + std::ptrdiff_t(width * offset_b[offset_b.size() - 2]), cb.end());
    EXPECT_FALSE(last_a.empty()) << name;
    EXPECT_TRUE(last_a == last_b) << name << " of the last frame differs";
  }
}

// A signal while the packing settles (before t = 0) is acted on after the current settle step:
// no result file yet (there is no frame), a settle checkpoint from which a restart resumes
// settling, a summary that says "interrupted" with the settle steps done, one line saying how to
// resume, exit 143.
TEST(EndToEndInterrupt, SigtermWhileSettlingStopsPromptlyWithASettleCheckpoint) {
  const auto dir = scratch_dir("interrupt_settle");
  fs::copy_file(fs::path(TMDEM_SOURCE_DIR) / "examples" / "paper_bed.toml", dir + "/bed.toml");
  // 256 particles that never reach 1e-9 m/s: settling would go on for the full 100 s.
  const pid_t child = spawn_tmdem({"run", "bed.toml", "-o", "out.h5", "--summary", "s.json", "--set",
                                   "mechanics.settle_velocity=1e-9", "--set", "mechanics.settle_time=100"},
                                  dir);
  ASSERT_GT(child, 0);
  // Wait until settling has begun and reported progress at least once.
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (text_of(dir + "/child.log").find("settle") == std::string::npos &&
         std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  const auto signalled = std::chrono::steady_clock::now();
  ASSERT_EQ(kill(child, SIGTERM), 0);
  int status = 0;
  ASSERT_EQ(waitpid(child, &status, 0), child);
  const double exit_after_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - signalled).count();
  const std::string log = text_of(dir + "/child.log");
  ASSERT_TRUE(WIFEXITED(status)) << log;
  EXPECT_EQ(WEXITSTATUS(status), 143) << log;
  // One settle step of this bed takes tens of ms; settling itself would take 100 s of steps.
  EXPECT_LT(exit_after_s, 5.0) << log;
  EXPECT_NE(log.find("interrupted by SIGTERM while settling"), std::string::npos) << log;
  EXPECT_NE(log.find("resume settling with: tmdem run bed.toml"), std::string::npos) << log;
  EXPECT_NE(log.find("--restart out.checkpoint.h5"), std::string::npos) << log;
  EXPECT_EQ(log.find("WITHOUT coming to rest"), std::string::npos) << log;
  EXPECT_FALSE(fs::exists(dir + "/out.h5"));
  EXPECT_FALSE(fs::exists(dir + "/out.xdmf"));
  EXPECT_TRUE(fs::exists(dir + "/out.checkpoint.h5"));
  const auto summary = read_summary(dir + "/s.json");
  EXPECT_EQ(summary["status"], "interrupted");
  EXPECT_EQ(summary["simulated_time_s"].get<double>(), 0.0);
  EXPECT_FALSE(summary["settle"]["at_rest"].get<bool>());
  EXPECT_EQ(summary["settle"]["ended_by"], "interrupted");
  const auto steps = summary["settle"]["steps"].get<long long>();
  EXPECT_GT(steps, 0);
  EXPECT_LT(steps, 100000);  // far from settle_time / time_step
  EXPECT_EQ(summary["mechanics"]["steps"].get<long long>(), steps);
  // The settle checkpoint belongs to this scene: another one is refused, naming the key.
  const auto refused = run_tmdem("run bed.toml --quiet -o out.h5 --restart out.checkpoint.h5 "
                                 "--set mechanics.settle_velocity=1e-9 --set mechanics.settle_time=50",
                                 dir);
  EXPECT_EQ(refused.exit_code, 2) << refused.output;
  EXPECT_NE(refused.output.find("mechanics.settle_time"), std::string::npos) << refused.output;
  EXPECT_FALSE(fs::exists(dir + "/out.h5"));
}

// The paper's bed settled for 2,000 steps (never at rest at 1e-9 m/s: frozen at settle_time;
// about 2 s here), then heated for 1 s; `extra` settings after these. Copies the scene into
// `dir` and `reference`, runs the uninterrupted run in `reference`, and returns the settings.
std::vector<std::string> long_settle(const std::string& dir, const std::string& reference,
                                     const std::vector<std::string>& extra = {}) {
  for (const auto& d : {dir, reference})
    fs::copy_file(fs::path(TMDEM_SOURCE_DIR) / "examples" / "paper_bed.toml", d + "/bed.toml");
  std::vector<std::string> settings = {"--set", "simulation.duration=1", "--set", "output.interval=0.5",
                                       "--set", "mechanics.settle_velocity=1e-9", "--set",
                                       "mechanics.settle_time=2"};
  settings.insert(settings.end(), extra.begin(), extra.end());
  const auto r = run_tmdem("run bed.toml --quiet -o out.h5 --summary s.json" + joined(settings), reference);
  EXPECT_EQ(r.exit_code, 0) << r.output;
  return settings;
}

// Resumes the settle checkpoint in `dir` to the end: the very result and summary of the
// uninterrupted run in `reference`, and no settle checkpoint left.
void expect_resumed_as_never_stopped(const std::string& dir, const std::string& reference,
                                     const std::vector<std::string>& settings) {
  ASSERT_TRUE(fs::exists(dir + "/out.checkpoint.h5"));
  ASSERT_FALSE(fs::exists(dir + "/out.h5"));
  const auto r = run_tmdem("run bed.toml --quiet -o out.h5 --summary s.json --restart out.checkpoint.h5" +
                               joined(settings), dir);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  for (const auto& line : result_differences(reference + "/out.h5", dir + "/out.h5")) ADD_FAILURE() << line;
  EXPECT_EQ(summary_without_wall_times(reference + "/s.json"), summary_without_wall_times(dir + "/s.json"));
  EXPECT_FALSE(fs::exists(dir + "/out.checkpoint.h5"));
}

std::vector<std::string> run_args(const std::vector<std::string>& settings) {
  std::vector<std::string> args = {"run", "bed.toml", "-o", "out.h5", "--summary", "s.json"};
  args.insert(args.end(), settings.begin(), settings.end());
  return args;
}

// A settle interrupted at whatever step the signal finds, then resumed from its settle checkpoint
// (and the run carried on to its end), writes the very result and summary of the run that never
// stopped: the settle goes on from the integrator's whole state and the settle's own, and the
// run then starts at t = 0 as any run.
TEST(EndToEndInterrupt, SigtermWhileSettlingThenRestartEqualsUninterruptedRunBitwise) {
  const auto dir = scratch_dir("settle_resume");
  const auto reference = scratch_dir("settle_reference");
  const auto settings = long_settle(dir, reference);
  const pid_t child = spawn_tmdem(run_args(settings), dir);
  ASSERT_GT(child, 0);
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (text_of(dir + "/child.log").find("settle") == std::string::npos &&
         std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  std::this_thread::sleep_for(std::chrono::milliseconds(200));
  ASSERT_EQ(kill(child, SIGTERM), 0);
  int status = 0;
  ASSERT_EQ(waitpid(child, &status, 0), child);
  const std::string log = text_of(dir + "/child.log");
  ASSERT_TRUE(WIFEXITED(status)) << log;
  if (WEXITSTATUS(status) == 0) GTEST_SKIP() << "the run ended before the signal; nothing to test";
  ASSERT_EQ(WEXITSTATUS(status), 143) << log;
  if (log.find("while settling") == std::string::npos)
    GTEST_SKIP() << "the signal came after settling; the run's own restart tests cover that";
  expect_resumed_as_never_stopped(dir, reference, settings);
}

// SIGKILL while settling (a crash: nothing written at the end): the last periodic settle
// checkpoint (output.settle_checkpoint_interval, wall-clock) resumes the settle, and the run
// then writes the very result and summary of the run that never stopped. A completed run
// removes its settle checkpoint: there is nothing left to resume.
TEST(EndToEndInterrupt, SigkillWhileSettlingThenRestartFromSettleCheckpointEqualsUninterruptedRun) {
  const auto dir = scratch_dir("settle_sigkill");
  const auto reference = scratch_dir("settle_sigkill_reference");
  const auto settings = long_settle(dir, reference, {"--set", "output.settle_checkpoint_interval=0.2"});
  EXPECT_FALSE(fs::exists(reference + "/out.checkpoint.h5"));
  // The settle checkpoints' time is output, not mechanics: the parts still add up to the wall time.
  const auto parts = read_summary(reference + "/s.json")["wall_time_parts"];
  EXPECT_GT(parts["output_s"].get<double>(), 0.0);
  EXPECT_LE(parts["mechanics_s"].get<double>() + parts["thermal_s"].get<double>() +
                parts["output_s"].get<double>(),
            read_summary(reference + "/s.json")["wall_time_s"].get<double>());
  const pid_t child = spawn_tmdem(run_args(settings), dir);
  ASSERT_GT(child, 0);
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (!fs::exists(dir + "/out.checkpoint.h5") && std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  ASSERT_EQ(kill(child, SIGKILL), 0);
  int status = 0;
  ASSERT_EQ(waitpid(child, &status, 0), child);
  if (!WIFSIGNALED(status)) GTEST_SKIP() << "the run ended before the kill; nothing to test";
  if (fs::exists(dir + "/out.h5")) GTEST_SKIP() << "the kill came after settling; nothing to test";
  expect_resumed_as_never_stopped(dir, reference, settings);
}

// SIGKILL (a crash: no handler, nothing written at the end) mid-run: the last periodic
// checkpoint restarts the run, which then writes the very file of the run that never stopped.
TEST(EndToEndInterrupt, SigkillThenRestartFromLastCheckpointEqualsUninterruptedRunBitwise) {
  const auto dir = scratch_dir("sigkill_resume");
  const auto reference = scratch_dir("sigkill_reference");
  for (const auto& d : {dir, reference})
    fs::copy_file(fs::path(TMDEM_SOURCE_DIR) / "examples" / "poured_bed.toml", d + "/bed.toml");
  const std::vector<std::string> settings = {"--set", "simulation.duration=0.5", "--set",
                                             "output.checkpoint_interval=0.1"};
  std::vector<std::string> args = {"run", "bed.toml", "--quiet", "-o", "out.h5", "--summary", "s.json"};
  args.insert(args.end(), settings.begin(), settings.end());
  const pid_t child = spawn_tmdem(args, dir);
  ASSERT_GT(child, 0);
  // Frames every 0.05 s: the seventh frame is t = 0.3 s, past the checkpoints at 0.1 and 0.2 s.
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (frames_in_xdmf(dir + "/out.xdmf") < 7 && std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  ASSERT_EQ(kill(child, SIGKILL), 0);
  int status = 0;
  ASSERT_EQ(waitpid(child, &status, 0), child);
  if (!WIFSIGNALED(status)) GTEST_SKIP() << "the run ended before the kill; nothing to test";
  ASSERT_TRUE(fs::exists(dir + "/out.checkpoint.h5"));

  auto r = run_tmdem("run bed.toml --quiet -o out.h5 --summary s.json --set simulation.duration=0.5 "
                     "--set output.checkpoint_interval=0.1", reference);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  r = run_tmdem("run bed.toml --quiet -o out.h5 --summary s.json --restart out.checkpoint.h5 "
                "--set simulation.duration=0.5 --set output.checkpoint_interval=0.1", dir);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  for (const auto& line : result_differences(reference + "/out.h5", dir + "/out.h5")) ADD_FAILURE() << line;
  EXPECT_EQ(summary_without_wall_times(reference + "/s.json"), summary_without_wall_times(dir + "/s.json"));
}

// Runs tmdem_testing with `args` in `dir` and its "wait_for_signal" solver
// (tests/program/SignalWaitSolver.cpp), which solves until the step is given up (two minutes at
// most) and says so on its first solve; sends SIGTERM 0.1 s after that line, and waits at most
// 60 s for the run to end (then kills it). The waitpid status, or -1 if it had to be killed.
int sigterm_during_a_solve(const std::string& dir, std::vector<std::string> args) {
  args.insert(args.end(), {"--set", "mechanics.solver=\"wait_for_signal\""});
  const pid_t child = spawn_tmdem(args, dir, TMDEM_TESTING_BINARY);
  if (child <= 0) return -1;
  const auto solving = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (text_of(dir + "/child.log").find("wait_for_signal: solving") == std::string::npos &&
         std::chrono::steady_clock::now() < solving)
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  std::this_thread::sleep_for(std::chrono::milliseconds(100));
  kill(child, SIGTERM);
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  int status = 0;
  while (std::chrono::steady_clock::now() < deadline) {
    if (waitpid(child, &status, WNOHANG) == child) return status;
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  kill(child, SIGKILL);
  waitpid(child, &status, 0);
  return -1;
}

// A signal while a step's contact solve is running gives that step up at once: the state goes
// back to the step's start, the last frame and the checkpoint are those of the last whole step
// (t = 0 here), and the run exits 143 without finishing the solve (before, it waited for it).
TEST(EndToEndInterrupt, SigtermDuringAContactSolveGivesTheStepUpAndStopsAtOnce) {
  const auto dir = scratch_dir("interrupt_in_solve");
  fs::copy_file(fs::path(TMDEM_SOURCE_DIR) / "examples" / "poured_bed.toml", dir + "/bed.toml");
  const int status =
      sigterm_during_a_solve(dir, {"run", "bed.toml", "--quiet", "-o", "out.h5", "--summary", "s.json"});
  const std::string log = text_of(dir + "/child.log");
  EXPECT_NE(log.find("wait_for_signal: solving"), std::string::npos) << log;
  ASSERT_NE(status, -1) << "the run did not stop within 60 s of SIGTERM:\n" << log;
  ASSERT_TRUE(WIFEXITED(status)) << log;
  EXPECT_EQ(WEXITSTATUS(status), 143) << log;
  EXPECT_NE(log.find("interrupted by SIGTERM at t = 0 s"), std::string::npos) << log;
  // Only the frame at t = 0, written before the first step.
  EXPECT_EQ(frames_in_xdmf(dir + "/out.xdmf"), 1u);
  H5::H5File file(dir + "/out.h5", H5F_ACC_RDONLY);
  EXPECT_EQ(read_string_attribute(file, "status"), "interrupted");
  EXPECT_EQ(read_doubles(file, "/frames/time"), std::vector<double>{0.0});
  H5::H5File checkpoint(dir + "/out.checkpoint.h5", H5F_ACC_RDONLY);
  double checkpoint_time_s = -1.0;
  checkpoint.openAttribute("time_s").read(H5::PredType::NATIVE_DOUBLE, &checkpoint_time_s);
  EXPECT_EQ(checkpoint_time_s, 0.0);
  const auto summary = read_summary(dir + "/s.json");
  EXPECT_EQ(summary["status"], "interrupted");
  EXPECT_EQ(summary["simulated_time_s"].get<double>(), 0.0);
  // The step given up is not counted: not taken, not unconverged.
  EXPECT_EQ(summary["mechanics"]["steps"].get<long>(), 0);
  EXPECT_EQ(summary["mechanics"]["unconverged_steps"].get<long>(), 0);
}

// The same while settling: the settle step being solved is given up, and the settle checkpoint
// holds the settle as it stood before it (no step taken here).
TEST(EndToEndInterrupt, SigtermDuringASettleSolveGivesTheStepUpWithASettleCheckpoint) {
  const auto dir = scratch_dir("interrupt_in_settle_solve");
  fs::copy_file(fs::path(TMDEM_SOURCE_DIR) / "examples" / "paper_bed.toml", dir + "/bed.toml");
  const int status = sigterm_during_a_solve(dir, {"run", "bed.toml", "-o", "out.h5", "--summary", "s.json"});
  const std::string log = text_of(dir + "/child.log");
  EXPECT_NE(log.find("wait_for_signal: solving"), std::string::npos) << log;
  ASSERT_NE(status, -1) << "the settle did not stop within 60 s of SIGTERM:\n" << log;
  ASSERT_TRUE(WIFEXITED(status)) << log;
  EXPECT_EQ(WEXITSTATUS(status), 143) << log;
  EXPECT_NE(log.find("interrupted by SIGTERM while settling"), std::string::npos) << log;
  EXPECT_TRUE(fs::exists(dir + "/out.checkpoint.h5"));
  EXPECT_FALSE(fs::exists(dir + "/out.h5"));
  const auto summary = read_summary(dir + "/s.json");
  EXPECT_EQ(summary["status"], "interrupted");
  EXPECT_EQ(summary["settle"]["steps"].get<long>(), 0) << summary.dump();
  EXPECT_EQ(summary["settle"]["ended_by"], "interrupted");
}

}  // namespace
