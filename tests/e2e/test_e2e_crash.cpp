// End to end: a run killed on the spot (SIGKILL, no cleanup) leaves a result file and an XDMF
// that describe the same frames, also past the first 32 frames where frames are stored in
// batches (of up to 1/32 of the frames, or a second's): the XDMF lists exactly the frames the .h5 holds, and every dataset it points at has
// the dimensions it declares. The crash comes from the test-only fault_injection mode
// (tests/program, tmdem_testing) at a chosen right-hand-side evaluation.
#include <gtest/gtest.h>

#include <map>
#include <regex>
#include <sstream>

#include "E2eSupport.h"

using namespace tmdem::e2e;

namespace {

// The lattice with the explicit update at one step per frame: evaluation k is frame k's step.
std::string crashing_scene(int crash_at_evaluation) {
  return thermal_scene()
      .set("simulation.duration", 30.0)
      .add("generate", lattice({4, 4, 4}))
      .add("assign", assign_ids({0}, {{"temperature", 373.15}}))
      .set(output("out.h5", 0.01))
      .set({{"thermal.integrator", "explicit"},
            {"thermal.explicit_step", 0.01},
            {"effects.fault_injection", true},
            {"fault_injection.after_rhs_evaluations", crash_at_evaluation},
            {"fault_injection.crash", 1}});
}

}  // namespace

TEST(EndToEndCrash, KilledRunLeavesXdmfDescribingExactlyTheFramesOfTheH5) {
  // Crash points well after the 32 frames that are stored one by one.
  for (const int crash_at : {300, 1500, 2222}) {
    const auto dir = scratch_dir("crash_" + std::to_string(crash_at));
    write_file(dir + "/s.toml", crashing_scene(crash_at));
    const std::string cmd = "cd '" + dir + "' && '" + TMDEM_TESTING_BINARY + "' run s.toml --quiet > log.txt 2>&1";
    const int status = std::system(cmd.c_str());
    // The shell reports its child's SIGKILL as exit 128 + 9.
    ASSERT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 137) << crash_at << ": " << status;

    H5::H5File file(dir + "/out.h5", H5F_ACC_RDONLY);
    EXPECT_EQ(read_string_attribute(file, "status"), "running");
    std::vector<hsize_t> position_dims;
    read_doubles(file, "/frames/position", &position_dims);
    const auto times = read_doubles(file, "/frames/time");
    ASSERT_EQ(position_dims.size(), 3u);
    const std::size_t frames = times.size();
    EXPECT_EQ(position_dims[0], frames);
    EXPECT_EQ(read_doubles(file, "/frames/temperature").size(), frames * 64);
    // Frames up to the crash are there, less at most what arrived in its last wall second.
    EXPECT_LE(frames, std::size_t(crash_at) + 1) << crash_at;
    EXPECT_GE(32 * frames, 31 * std::size_t(crash_at)) << crash_at;

    const std::string xdmf = text_of(dir + "/out.xdmf");
    std::size_t listed = 0;
    for (auto at = xdmf.find("<Grid Name=\"particles\" GridType=\"Uniform\""); at != std::string::npos;
         at = xdmf.find("<Grid Name=\"particles\" GridType=\"Uniform\"", at + 1))
      ++listed;
    EXPECT_EQ(listed, frames) << crash_at;
    // Every HDF5 dataset the XDMF points at has the dimensions it declares there.
    const std::regex reference("<DataItem[^>]*Dimensions=\"([0-9 ]+)\"[^>]*Format=\"HDF\"[^>]*>out\\.h5:([^<]+)</DataItem>");
    std::map<std::string, std::string> actual_dims;  // dataset path -> "d0 d1 ..."
    std::size_t references = 0;
    for (auto it = std::sregex_iterator(xdmf.begin(), xdmf.end(), reference); it != std::sregex_iterator(); ++it) {
      const std::string path = (*it)[2].str();
      if (!actual_dims.count(path)) {
        H5::DataSpace space = file.openDataSet(path).getSpace();
        std::vector<hsize_t> dims(std::size_t(space.getSimpleExtentNdims()));
        space.getSimpleExtentDims(dims.data());
        std::ostringstream text;
        for (std::size_t k = 0; k < dims.size(); ++k) text << (k ? " " : "") << dims[k];
        actual_dims[path] = text.str();
      }
      ASSERT_EQ((*it)[1].str(), actual_dims[path]) << crash_at << ": " << path;
      ++references;
    }
    EXPECT_GE(references, frames) << crash_at;
  }
}
