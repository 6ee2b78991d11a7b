#pragma once
// `tmdem render RESULT.h5 -o bed.png [--frame K] [--cut x|y|z] [--forces]`: one frame of a
// result drawn by ParaView (pvbatch running tmdem_render.py, docs/paraview.md): the spheres at
// their true size coloured by temperature over that frame's range, a colour bar
// "temperature (K)", optionally cut at the bed's mid-plane and with the force network as tubes.
// pvbatch is taken from $TMDEM_PVBATCH or PATH; without an X display it renders on a virtual
// one, an Xvfb of its own (-displayfd -noreset), a failure tried twice more on new ones.
// The script is $TMDEM_RENDER_SCRIPT, else tmdem_render.py next to the tmdem program (CMake
// copies it there), else the source checkout's coupling/app/tmdem_render.py.
// Exit codes: 0; 2 for a frame the file does not hold, an output that is not .png or a bad
// --cut; 4 for a result (or its .xdmf) that cannot be read, pvbatch, Xvfb or the script
// missing, or pvbatch failing or writing no image.
#include <ostream>
#include <string>
#include <vector>

namespace tmdem::coupling {

struct RenderOptions {
  std::string result_path;
  std::string png_path;
  std::string frame = "last";  // "last", or a frame number (negative counts from the end)
  std::string cut;             // "", "x", "y" or "z"
  bool forces = false;
  std::vector<int> size;       // {width, height} in pixels; empty: the script's 1200 x 900
};

int run_render_command(const RenderOptions& options, std::ostream& out, std::ostream& log);

// The first executable file `name` in the directories of PATH ("" if none). A name with a
// slash is taken as it is.
std::string find_executable(const std::string& name);

// Where tmdem_render.py is (see above); "" if nowhere.
std::string find_render_script();

}  // namespace tmdem::coupling
