#include "coupling/output/XdmfWriter.h"
#include "coupling/common/ShortestNumber.h"

#include <charconv>
#include <filesystem>
#include <fstream>
#include <system_error>

#include "coupling/output/OutputError.h"

namespace tmdem::coupling {
namespace {

std::string xml_escape(const std::string& text) {
  std::string out;
  out.reserve(text.size());
  for (char c : text) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      default: out += c;
    }
  }
  return out;
}

std::string number(double value) { return shortest_number(value); }

// A hyperslab of one frame f out of an HDF5 dataset [frames, particles(, 3)].
void hyperslab(std::string& out, const std::string& indent, const std::string& source,
               std::size_t frame, std::size_t frames, std::size_t particles, bool vector) {
  const std::string n = std::to_string(particles);
  const std::string f = std::to_string(frame);
  const std::string total = std::to_string(frames);
  const std::string rank = vector ? "3" : "2";
  out += indent + "<DataItem ItemType=\"HyperSlab\" Dimensions=\"1 " + n + (vector ? " 3" : "") +
         "\" Type=\"HyperSlab\">\n";
  out += indent + "  <DataItem Dimensions=\"3 " + rank + "\" Format=\"XML\" NumberType=\"Int\">" +
         (vector ? f + " 0 0 1 1 1 1 " + n + " 3" : f + " 0 1 1 1 " + n) + "</DataItem>\n";
  out += indent + "  <DataItem Dimensions=\"" + total + " " + n + (vector ? " 3" : "") +
         "\" NumberType=\"Float\" Precision=\"8\" Format=\"HDF\">" + source + "</DataItem>\n";
  out += indent + "</DataItem>\n";
}

}  // namespace

std::string xdmf_path_for(const std::string& h5_path) {
  std::filesystem::path path(h5_path);
  path.replace_extension(".xdmf");
  return path.string();
}

std::string xdmf_document(const std::string& h5_file_name, std::size_t particles,
                          std::span<const double> times_s) {
  const std::string file = xml_escape(h5_file_name);
  const std::string n = std::to_string(particles);
  const std::size_t frames = times_s.size();
  std::string out;
  out.reserve(512 + frames * (1800 + 4 * file.size()));
  out += "<?xml version=\"1.0\" ?>\n";
  out += "<!DOCTYPE Xdmf SYSTEM \"Xdmf.dtd\" []>\n";
  out += "<Xdmf Version=\"2.0\">\n";
  out += "  <Domain>\n";
  out += "    <Grid Name=\"particles\" GridType=\"Collection\" CollectionType=\"Temporal\">\n";
  const std::string in = "          ";
  for (std::size_t f = 0; f < frames; ++f) {
    out += "      <Grid Name=\"frame_" + std::to_string(f) + "\" GridType=\"Uniform\">\n";
    out += "        <Time Value=\"" + number(times_s[f]) + "\"/>\n";
    out += "        <Topology TopologyType=\"Polyvertex\" NumberOfElements=\"" + n +
           "\" NodesPerElement=\"1\"/>\n";
    out += "        <Geometry GeometryType=\"XYZ\">\n";
    hyperslab(out, in, file + ":/frames/position", f, frames, particles, true);
    out += "        </Geometry>\n";
    out += "        <Attribute Name=\"temperature\" AttributeType=\"Scalar\" Center=\"Node\">\n";
    hyperslab(out, in, file + ":/frames/temperature", f, frames, particles, false);
    out += "        </Attribute>\n";
    out += "        <Attribute Name=\"velocity\" AttributeType=\"Vector\" Center=\"Node\">\n";
    hyperslab(out, in, file + ":/frames/velocity", f, frames, particles, true);
    out += "        </Attribute>\n";
    out += "        <Attribute Name=\"radius\" AttributeType=\"Scalar\" Center=\"Node\">\n";
    out += in + "<DataItem Dimensions=\"" + n +
           "\" NumberType=\"Float\" Precision=\"8\" Format=\"HDF\">" + file +
           ":/particles/radius</DataItem>\n";
    out += "        </Attribute>\n";
    out += "        <Attribute Name=\"material\" AttributeType=\"Scalar\" Center=\"Node\">\n";
    out += in + "<DataItem Dimensions=\"" + n +
           "\" NumberType=\"Int\" Precision=\"4\" Format=\"HDF\">" + file +
           ":/particles/material</DataItem>\n";
    out += "        </Attribute>\n";
    out += "      </Grid>\n";
  }
  out += "    </Grid>\n";
  out += "  </Domain>\n";
  out += "</Xdmf>\n";
  return out;
}

void write_xdmf(const std::string& h5_path, std::size_t particles,
                std::span<const double> times_s) {
  const std::string target = xdmf_path_for(h5_path);
  const std::string temporary = target + ".tmp";
  const std::string document =
      xdmf_document(std::filesystem::path(h5_path).filename().string(), particles, times_s);
  std::error_code ignored;
  {
    std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
    if (!out) {
      throw OutputError("cannot write XDMF file '" + target + "': cannot create '" + temporary +
                        "'");
    }
    out << document;
    out.close();
    if (!out) {
      std::filesystem::remove(temporary, ignored);
      throw OutputError("cannot write XDMF file '" + target + "': write to '" + temporary +
                        "' failed");
    }
  }
  std::error_code error;
  std::filesystem::rename(temporary, target, error);
  if (error) {
    std::filesystem::remove(temporary, ignored);
    throw OutputError("cannot write XDMF file '" + target + "': " + error.message());
  }
}

}  // namespace tmdem::coupling
