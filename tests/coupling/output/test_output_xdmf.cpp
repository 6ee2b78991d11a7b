// XdmfWriter: the ParaView description of a result file.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "coupling/output/ResultWriter.h"
#include "coupling/output/XdmfWriter.h"

namespace {

namespace fs = std::filesystem;
using namespace tmdem::coupling;

std::size_t count(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

std::string read_text(const std::string& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// Elements open and close in matching numbers (self-closing ones count as both).
void expect_balanced(const std::string& xml, const std::string& element) {
  const std::size_t open = count(xml, "<" + element + " ") + count(xml, "<" + element + ">");
  std::size_t self_closing = 0;
  for (std::size_t at = xml.find("<" + element + " "); at != std::string::npos;
       at = xml.find("<" + element + " ", at + 1)) {
    if (xml[xml.find('>', at) - 1] == '/') ++self_closing;
  }
  EXPECT_EQ(open - self_closing, count(xml, "</" + element + ">")) << element;
}

TEST(XdmfWriter, PathNextToResult) {
  EXPECT_EQ(xdmf_path_for("result.h5"), "result.xdmf");
  EXPECT_EQ(xdmf_path_for("out/run.1.h5"), "out/run.1.xdmf");
  EXPECT_EQ(xdmf_path_for("/tmp/result"), "/tmp/result.xdmf");
}

TEST(XdmfWriter, DocumentNamesWholeDatasetsPerFrame) {
  const std::vector<double> times = {0.0, 0.1, 0.2};
  // Frame 0 without contacts, frame 1 with 4 (one on a wall), frame 2 with 2 (both on walls).
  const std::vector<FrameViewCounts> views = {{0, 0}, {4, 1}, {2, 2}};
  const std::string xml = xdmf_document("result.h5", 5, 3, times, views);
  EXPECT_EQ(xml.rfind("<?xml", 0), 0u);
  EXPECT_EQ(xml.find("HyperSlab"), std::string::npos);  // ParaView's Xdmf3 readers skip them
  // Three temporal collections (blocks keep their places at every time), one grid per frame.
  EXPECT_EQ(count(xml, "CollectionType=\"Temporal\""), 3u);
  EXPECT_EQ(count(xml, "<Grid Name=\"particles\" GridType=\"Uniform\""), 3u);
  EXPECT_EQ(count(xml, "<Time Value="), 9u);
  EXPECT_EQ(count(xml, "TopologyType=\"Polyvertex\" NumberOfElements=\"5\""), 3u);
  EXPECT_EQ(count(xml, "result.h5:/xdmf/vertices</DataItem>"), 6u);  // topology and id
  for (int f = 0; f < 3; ++f) {
    const std::string view = "result.h5:/xdmf/frame_" + std::to_string(f) + "/";
    for (const char* array : {"velocity", "temperature"})
      EXPECT_EQ(count(xml, view + array + "</DataItem>"), 1u) << f << array;
    // Also the points of frame 0's empty line set.
    EXPECT_EQ(count(xml, view + "position</DataItem>"), f == 0 ? 2u : 1u) << f;
  }
  EXPECT_EQ(count(xml, "result.h5:/particles/radius</DataItem>"), 3u);
  EXPECT_EQ(count(xml, "result.h5:/particles/material</DataItem>"), 3u);
  // Contacts: a line set over the positions and the wall feet; frame 0 has an empty one.
  EXPECT_EQ(count(xml, "<Grid Name=\"contacts\" GridType=\"Uniform\""), 3u);
  EXPECT_EQ(xml.find("/xdmf/frame_0/contact"), std::string::npos);
  EXPECT_NE(xml.find("NumberOfElements=\"0\" NodesPerElement=\"2\"><DataItem Dimensions=\"0 2\" "
                     "NumberType=\"Int\" Precision=\"8\" Format=\"HDF\">result.h5:/xdmf/no_lines"),
            std::string::npos);
  EXPECT_NE(xml.find("TopologyType=\"Polyline\" NumberOfElements=\"4\" NodesPerElement=\"2\">"
                     "<DataItem Dimensions=\"4 2\""),
            std::string::npos);
  EXPECT_NE(xml.find("<DataItem Dimensions=\"6 3\" NumberType=\"Float\" Precision=\"8\" "
                     "Format=\"HDF\">result.h5:/xdmf/frame_1/contact_points"),
            std::string::npos);
  EXPECT_NE(xml.find("Dimensions=\"7 3\" NumberType=\"Float\" Precision=\"8\" "
                     "Format=\"HDF\">result.h5:/xdmf/frame_2/contact_points"),
            std::string::npos);
  for (const char* array : {"normal_force", "conductance", "heat_flow", "tangential_force"})
    EXPECT_EQ(count(xml, "<Attribute Name=\"" + std::string(array)), 3u) << array;
  // Walls in every frame: 3 quadrilaterals.
  EXPECT_EQ(count(xml, "TopologyType=\"Quadrilateral\" NumberOfElements=\"3\""), 3u);
  EXPECT_EQ(count(xml, "result.h5:/xdmf/walls/temperature</DataItem>"), 3u);
  EXPECT_NE(xml.find("<Time Value=\"0.1\"/>"), std::string::npos);
  for (const char* element : {"Xdmf", "Domain", "Grid", "Topology", "Geometry", "Attribute",
                              "DataItem", "Time"}) {
    expect_balanced(xml, element);
  }
  // No walls: no wall grid; no contacts in any frame: no contact grid.
  EXPECT_EQ(xdmf_document("result.h5", 5, 0, times, views).find("walls"), std::string::npos);
  const std::vector<FrameViewCounts> none = {{0, 0}, {0, 0}, {0, 0}};
  EXPECT_EQ(xdmf_document("result.h5", 5, 0, times, none).find("contacts"), std::string::npos);
}

TEST(XdmfWriter, EscapesFileName) {
  const std::vector<double> times = {0.0};
  const std::vector<FrameViewCounts> views = {{0, 0}};
  const std::string xml = xdmf_document("a&b<c>.h5", 1, 0, times, views);
  EXPECT_NE(xml.find("a&amp;b&lt;c&gt;.h5:/xdmf/frame_0/position"), std::string::npos);
  EXPECT_EQ(xml.find("a&b"), std::string::npos);
}

TEST(XdmfWriter, ResultWriterKeepsXdmfCurrent) {
  const fs::path dir = fs::temp_directory_path() / ("tmdem-output-xdmf-" + std::to_string(getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  const std::string path = (dir / "bed.h5").string();
  {
    ResultHeader header;
    header.radius_m = {1e-3, 1e-3};
    header.mass_kg = {1e-5, 1e-5};
    header.heat_capacity_J_per_K = {1e-2, 1e-2};
    header.material = {0, 0};
    ResultWriter writer(path, header, true);
    const std::vector<double> xyz(6, 0.0), temperature(2, 300.0);
    // A frame at t_s without contacts (members not set stay empty).
    auto frame_at = [&](double t_s) {
      FrameView view;
      view.time_s = t_s;
      view.position_m = xyz;
      view.velocity_m_per_s = xyz;
      view.temperature_K = temperature;
      view.thermal_energy_J = 6.0;
      return view;
    };
    for (int f = 0; f < 2; ++f) writer.write_frame(frame_at(0.5 * f));
    EXPECT_EQ(writer.xdmf_path(), (dir / "bed.xdmf").string());
    const std::string during = read_text(writer.xdmf_path());
    EXPECT_EQ(count(during, "<Grid Name=\"particles\" GridType=\"Uniform\""), 2u);
    writer.write_frame(frame_at(1.0));
    writer.finish("ok");
  }
  const std::string xml = read_text((dir / "bed.xdmf").string());
  EXPECT_EQ(count(xml, "<Grid Name=\"particles\" GridType=\"Uniform\""), 3u);
  EXPECT_EQ(count(xml, "/position</DataItem>"), 3u);
  EXPECT_EQ(xml.find(dir.string()), std::string::npos);  // file name only, no folder
  EXPECT_FALSE(fs::exists(dir / "bed.xdmf.tmp"));
  fs::remove_all(dir);
}

}  // namespace
