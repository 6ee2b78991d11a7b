// `tmdem render` (coupling/app/RenderCommand.h, tmdem_render.py through pvbatch) draws a bed
// heated from its floor with the colours of the chosen frame's temperature range: the bottom
// spheres at the hot end of the colour map, the top ones at the cold end (tests/paraview/
// bed_colours.py reads the PNG's hues). Had the range been t = 0's (every sphere at 293.15 K),
// the top spheres would sit mid-map (green) and everything warmer would be clamped to red.
// The rendering tests are skipped when pvbatch is absent (scripts/setup.sh --with-paraview) or
// there is neither an X display nor Xvfb; the argument checks run without ParaView.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>

#include "e2e/E2eSupport.h"

using namespace tmdem::e2e;

namespace {

bool have(const char* program) {
  return std::system(("command -v " + std::string(program) + " > /dev/null 2>&1").c_str()) == 0;
}

// 4 x 6 x 3 touching steel spheres settled on a floor at 373.15 K, heated for 120 s (frames at
// 0, 60 and 120 s): after 120 s the bottom layer is near 340 K and the top one near 293 K.
std::string heated_bed(const std::string& dir) {
  const std::string scene = steel_scene()
                                .set({{"simulation.duration", 120.0},
                                      {"simulation.dimension", 3},
                                      {"simulation.gravity", {0.0, -9.81, 0.0}},
                                      {"effects.mechanics", "settle"}})
                                .add("generate", lattice({4, 6, 3}))
                                .add("wall", floor_wall({{"temperature", 373.15}}))
                                .set(output("bed.h5", 60.0))
                                .str();
  write_file(dir + "/bed.toml", scene);
  const auto r = run_tmdem("run bed.toml --quiet", dir);
  EXPECT_EQ(r.exit_code, 0) << r.output;
  return dir + "/bed.h5";
}

struct Hues {
  double bottom = 0.0, top = 0.0;
  std::string text;
};

// bed_colours.py on IMAGE: the median hue of the bed's bottom and top rows (degrees).
Hues hues_of(const std::string& image) {
  const std::string out = image + ".hues";
  const std::string command = "/usr/bin/python3 '" + std::string(TMDEM_SOURCE_DIR) +
                              "/tests/paraview/bed_colours.py' '" + image + "' > '" + out + "' 2>&1";
  const int status = std::system(command.c_str());
  std::ifstream in(out);
  std::stringstream text;
  text << in.rdbuf();
  Hues h;
  h.text = text.str();
  if (status != 0 || std::sscanf(h.text.c_str(), "bottom_hue %lf top_hue %lf", &h.bottom, &h.top) != 2)
    ADD_FAILURE() << "bed_colours.py failed on " << image << ": " << h.text;
  return h;
}

class ParaViewRender : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!have("pvbatch")) GTEST_SKIP() << "pvbatch not found (scripts/setup.sh --with-paraview)";
    const char* display = std::getenv("DISPLAY");
    if ((!display || !*display) && !have("Xvfb"))
      GTEST_SKIP() << "no X display and no Xvfb (scripts/setup.sh --with-paraview installs xvfb)";
  }
};

}  // namespace

TEST_F(ParaViewRender, BedHeatedFromBelowIsHotColouredAtTheBottomAndColdColouredAtTheTop) {
  const auto dir = scratch_dir("paraview_render");
  heated_bed(dir);
  // Turbo: the hot end is red (hue about 0), the cold end purple (about 280); a t = 0 range
  // would make the top green (about 100) and the bottom red.
  // Each render starts pvbatch (about 5 s): --cut z and --forces are drawn together.
  for (const std::string options : {"", "--cut x", "--cut z --forces"}) {
    SCOPED_TRACE("tmdem render " + options);
    std::string name = "bed" + options + ".png";
    for (char& c : name)
      if (c == ' ' || c == '-') c = '_';
    const auto r = run_tmdem("render bed.h5 -o " + name + " --size 600 450 " + options, dir);
    ASSERT_EQ(r.exit_code, 0) << r.output;
    EXPECT_NE(r.output.find("rendered frame 2 (t = 120 s)"), std::string::npos) << r.output;
    const Hues h = hues_of(dir + "/" + name);
    EXPECT_LT(h.bottom, 40.0) << h.text;    // red to orange: the hot end
    EXPECT_GT(h.bottom, -30.0) << h.text;
    EXPECT_GT(h.top, 200.0) << h.text;      // blue to purple: the cold end
  }
}

TEST_F(ParaViewRender, EarlierFrameIsColouredOverItsOwnRange) {
  const auto dir = scratch_dir("paraview_render_frame");
  heated_bed(dir);
  const auto r = run_tmdem("render bed.h5 -o first.png --size 600 450 --frame 1", dir);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("rendered frame 1 (t = 60 s)"), std::string::npos) << r.output;
  const Hues h = hues_of(dir + "/first.png");
  EXPECT_LT(h.bottom, 40.0) << h.text;
  EXPECT_GT(h.top, 200.0) << h.text;
}

// Without ParaView: what `tmdem render` refuses before it would start pvbatch.
TEST(Render, FrameOutsideTheFileIsRefusedNamingTheValidRange) {
  const auto dir = scratch_dir("render_frame");
  heated_bed(dir);
  const auto r = run_tmdem("render bed.h5 -o bed.png --frame 3", dir);
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("has frames 0 to 2"), std::string::npos) << r.output;
  EXPECT_FALSE(std::filesystem::exists(dir + "/bed.png"));
}

TEST(Render, MissingPvbatchSaysWhatToInstall) {
  const auto dir = scratch_dir("render_no_pvbatch");
  heated_bed(dir);
  for (const std::string env : {"TMDEM_PVBATCH=/nonexistent/pvbatch", "PATH=/nonexistent"}) {
    const auto r = run_tmdem("render bed.h5 -o bed.png", dir, env);
    EXPECT_EQ(r.exit_code, 4) << env << ": " << r.output;
    EXPECT_NE(r.output.find("pvbatch not found"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("python3-paraview"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("scripts/setup.sh --with-paraview"), std::string::npos) << r.output;
  }
}

TEST(Render, OutputMustBeAPng) {
  const auto dir = scratch_dir("render_not_png");
  heated_bed(dir);
  const auto r = run_tmdem("render bed.h5 -o bed.jpg", dir);
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find(".png"), std::string::npos) << r.output;
}
