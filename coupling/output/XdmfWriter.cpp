#include "coupling/output/XdmfWriter.h"
#include "coupling/common/ShortestNumber.h"

#include <algorithm>
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

// <DataItem ...>file:path</DataItem>, one whole dataset.
std::string item(const std::string& file, const std::string& path, const std::string& dims,
                 const char* type = "Float", int precision = 8) {
  return "<DataItem Dimensions=\"" + dims + "\" NumberType=\"" + type + "\" Precision=\"" +
         std::to_string(precision) + "\" Format=\"HDF\">" + file + ":" + path + "</DataItem>";
}

void attribute(std::string& out, const std::string& name, const char* kind, const char* centre,
               const std::string& data) {
  out += "        <Attribute Name=\"" + name + "\" AttributeType=\"" + kind + "\" Center=\"" +
         centre + "\">" + data + "</Attribute>\n";
}

}  // namespace

std::string xdmf_path_for(const std::string& h5_path) {
  std::filesystem::path path(h5_path);
  path.replace_extension(".xdmf");
  return path.string();
}

std::string xdmf_document(const std::string& h5_file_name, std::size_t particles,
                          std::size_t walls, std::span<const double> times_s,
                          std::span<const FrameViewCounts> views) {
  const std::string file = xml_escape(h5_file_name);
  const std::string n = std::to_string(particles);
  const std::string w = std::to_string(walls);
  const std::size_t frames = std::min(times_s.size(), views.size());
  bool any_contacts = false;
  for (std::size_t f = 0; f < frames; ++f) any_contacts = any_contacts || views[f].contacts > 0;
  std::string out;
  out.reserve(1024 + frames * (3000 + 20 * file.size()));
  out += "<?xml version=\"1.0\" ?>\n";
  out += "<Xdmf Version=\"3.0\">\n";
  out += "  <Domain>\n";
  auto open_frame = [&](const char* grid, std::size_t f) {
    out += "      <Grid Name=\"" + std::string(grid) + "\" GridType=\"Uniform\">\n";
    out += "        <Time Value=\"" + number(times_s[f]) + "\"/>\n";
  };
  // Block 0: the particles.
  out += "    <Grid Name=\"particles\" GridType=\"Collection\" CollectionType=\"Temporal\">\n";
  for (std::size_t f = 0; f < frames; ++f) {
    const std::string view = "/xdmf/frame_" + std::to_string(f) + "/";
    open_frame("particles", f);
    out += "        <Topology TopologyType=\"Polyvertex\" NumberOfElements=\"" + n +
           "\" NodesPerElement=\"1\">" + item(file, "/xdmf/vertices", n, "Int") +
           "</Topology>\n";
    out += "        <Geometry GeometryType=\"XYZ\">" + item(file, view + "position", n + " 3") +
           "</Geometry>\n";
    attribute(out, "temperature", "Scalar", "Node", item(file, view + "temperature", n));
    attribute(out, "velocity", "Vector", "Node", item(file, view + "velocity", n + " 3"));
    attribute(out, "radius", "Scalar", "Node", item(file, "/particles/radius", n));
    attribute(out, "material", "Scalar", "Node", item(file, "/particles/material", n, "Int", 4));
    attribute(out, "id", "Scalar", "Node", item(file, "/xdmf/vertices", n, "Int"));
    out += "      </Grid>\n";
  }
  out += "    </Grid>\n";
  // Block 1: the contacts, in every frame once any frame has some (a frame without contacts
  // gets an empty line set, so the blocks keep their places).
  if (any_contacts) {
    out += "    <Grid Name=\"contacts\" GridType=\"Collection\" CollectionType=\"Temporal\">\n";
    for (std::size_t f = 0; f < frames; ++f) {
      const bool some = views[f].contacts > 0;
      const std::string view = "/xdmf/frame_" + std::to_string(f) + "/";
      const std::string c = std::to_string(views[f].contacts);
      const std::string points = std::to_string(particles + views[f].wall_contacts);
      open_frame("contacts", f);
      out += "        <Topology TopologyType=\"Polyline\" NumberOfElements=\"" + c +
             "\" NodesPerElement=\"2\">" +
             item(file, some ? view + "contact_lines" : "/xdmf/no_lines", c + " 2", "Int") +
             "</Topology>\n";
      out += "        <Geometry GeometryType=\"XYZ\">" +
             item(file, view + (some ? "contact_points" : "position"), points + " 3") +
             "</Geometry>\n";
      for (const char* name : {"normal_force", "conductance", "heat_flow"})
        attribute(out, name, "Scalar", "Cell",
                  item(file, some ? view + name : "/xdmf/no_values", c));
      attribute(out, "tangential_force", "Vector", "Cell",
                item(file, some ? view + "tangential_force" : "/xdmf/no_vectors", c + " 3"));
      out += "      </Grid>\n";
    }
    out += "    </Grid>\n";
  }
  // Last block: the walls, static, repeated per frame so that every reader keeps them.
  if (walls > 0) {
    out += "    <Grid Name=\"walls\" GridType=\"Collection\" CollectionType=\"Temporal\">\n";
    for (std::size_t f = 0; f < frames; ++f) {
      open_frame("walls", f);
      out += "        <Topology TopologyType=\"Quadrilateral\" NumberOfElements=\"" + w +
             "\">" + item(file, "/xdmf/walls/quads", w + " 4", "Int") + "</Topology>\n";
      out += "        <Geometry GeometryType=\"XYZ\">" +
             item(file, "/xdmf/walls/points", std::to_string(4 * walls) + " 3") +
             "</Geometry>\n";
      attribute(out, "temperature", "Scalar", "Cell", item(file, "/walls/temperature", w));
      out += "      </Grid>\n";
    }
    out += "    </Grid>\n";
  }
  out += "  </Domain>\n";
  out += "</Xdmf>\n";
  return out;
}

void write_xdmf(const std::string& h5_path, std::size_t particles, std::size_t walls,
                std::span<const double> times_s, std::span<const FrameViewCounts> views) {
  const std::string target = xdmf_path_for(h5_path);
  const std::string temporary = target + ".tmp";
  const std::string document =
      xdmf_document(std::filesystem::path(h5_path).filename().string(), particles, walls, times_s,
                    views);
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
