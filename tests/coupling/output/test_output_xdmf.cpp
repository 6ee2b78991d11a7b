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

TEST(XdmfWriter, DocumentHasOneGridPerFrame) {
  const std::vector<double> times = {0.0, 0.1, 0.2};
  const std::string xml = xdmf_document("result.h5", 5, times);
  EXPECT_EQ(xml.rfind("<?xml", 0), 0u);
  EXPECT_EQ(count(xml, "CollectionType=\"Temporal\""), 1u);
  EXPECT_EQ(count(xml, "<Grid Name=\"frame_"), 3u);
  EXPECT_EQ(count(xml, "TopologyType=\"Polyvertex\" NumberOfElements=\"5\""), 3u);
  EXPECT_EQ(count(xml, "result.h5:/frames/position</DataItem>"), 3u);
  EXPECT_EQ(count(xml, "result.h5:/frames/temperature</DataItem>"), 3u);
  EXPECT_EQ(count(xml, "result.h5:/frames/velocity</DataItem>"), 3u);
  EXPECT_EQ(count(xml, "result.h5:/particles/radius</DataItem>"), 3u);
  EXPECT_NE(xml.find("<Time Value=\"0.1\"/>"), std::string::npos);
  // Frame 2 of 3: hyperslab start row 2, source dimensions 3 x 5 x 3.
  EXPECT_NE(xml.find(">2 0 0 1 1 1 1 5 3</DataItem>"), std::string::npos);
  EXPECT_NE(xml.find("Dimensions=\"3 5 3\""), std::string::npos);
  for (const char* element : {"Xdmf", "Domain", "Grid", "Topology", "Geometry", "Attribute",
                              "DataItem", "Time"}) {
    expect_balanced(xml, element);
  }
}

TEST(XdmfWriter, EscapesFileName) {
  const std::vector<double> times = {0.0};
  const std::string xml = xdmf_document("a&b<c>.h5", 1, times);
  EXPECT_NE(xml.find("a&amp;b&lt;c&gt;.h5:/frames/position"), std::string::npos);
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
    for (int f = 0; f < 2; ++f) {
      writer.write_frame(FrameView{0.5 * f, xyz, xyz, temperature, 6.0, 0.0, {}, {}, {}, {}});
    }
    EXPECT_EQ(writer.xdmf_path(), (dir / "bed.xdmf").string());
    const std::string during = read_text(writer.xdmf_path());
    EXPECT_EQ(count(during, "<Grid Name=\"frame_"), 2u);
    writer.write_frame(FrameView{1.0, xyz, xyz, temperature, 6.0, 0.0, {}, {}, {}, {}});
    writer.finish("ok");
  }
  const std::string xml = read_text((dir / "bed.xdmf").string());
  EXPECT_EQ(count(xml, "<Grid Name=\"frame_"), 3u);
  EXPECT_EQ(count(xml, "bed.h5:/frames/position"), 3u);
  EXPECT_EQ(xml.find(dir.string()), std::string::npos);  // file name only, no folder
  EXPECT_FALSE(fs::exists(dir / "bed.xdmf.tmp"));
  fs::remove_all(dir);
}

}  // namespace
