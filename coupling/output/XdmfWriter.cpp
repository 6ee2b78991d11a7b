#include "coupling/output/XdmfWriter.h"
#include "coupling/common/ShortestNumber.h"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string_view>
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

// Appends <DataItem ...>file:path</DataItem> naming one whole dataset; the path is given in
// two parts (a frame's view folder and the array) and nothing is built in temporaries: the
// document is rewritten often (ResultWriter.h), so its cost is that of copying its text.
struct Item {
  std::string_view folder, array, dims;
  const char* type = "Float";
  const char* precision = "8";
};

void append_item(std::string& out, std::string_view file, const Item& item) {
  out.append("<DataItem Dimensions=\"").append(item.dims).append("\" NumberType=\"");
  out.append(item.type).append("\" Precision=\"").append(item.precision);
  out.append("\" Format=\"HDF\">").append(file).append(":").append(item.folder);
  out.append(item.array).append("</DataItem>");
}

void append_attribute(std::string& out, std::string_view file, std::string_view name,
                      const char* kind, const char* centre, const Item& item) {
  out.append("        <Attribute Name=\"").append(name).append("\" AttributeType=\"");
  out.append(kind).append("\" Center=\"").append(centre).append("\">");
  append_item(out, file, item);
  out.append("</Attribute>\n");
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
  const std::string n = std::to_string(particles), n3 = n + " 3";
  const std::string w = std::to_string(walls), w4 = w + " 4";
  const std::string corners = std::to_string(4 * walls) + " 3";
  const std::size_t frames = std::min(times_s.size(), views.size());
  bool any_contacts = false;
  for (std::size_t f = 0; f < frames; ++f) any_contacts = any_contacts || views[f].contacts > 0;
  std::string out;
  out.reserve(1024 + frames * (3600 + 24 * file.size()));
  out += "<?xml version=\"1.0\" ?>\n<Xdmf Version=\"3.0\">\n  <Domain>\n";
  std::string view, c, c2, c3, points;
  auto open_frame = [&](const char* grid, std::size_t f) {
    view.assign("/xdmf/frame_").append(std::to_string(f)).append("/");
    out.append("      <Grid Name=\"").append(grid).append("\" GridType=\"Uniform\">\n");
    out.append("        <Time Value=\"").append(number(times_s[f])).append("\"/>\n");
  };
  // Block 0: the particles.
  out += "    <Grid Name=\"particles\" GridType=\"Collection\" CollectionType=\"Temporal\">\n";
  for (std::size_t f = 0; f < frames; ++f) {
    open_frame("particles", f);
    out.append("        <Topology TopologyType=\"Polyvertex\" NumberOfElements=\"").append(n);
    out.append("\" NodesPerElement=\"1\">");
    append_item(out, file, {"/xdmf/", "vertices", n, "Int"});
    out.append("</Topology>\n        <Geometry GeometryType=\"XYZ\">");
    append_item(out, file, {view, "position", n3});
    out.append("</Geometry>\n");
    append_attribute(out, file, "temperature", "Scalar", "Node", {view, "temperature", n});
    append_attribute(out, file, "velocity", "Vector", "Node", {view, "velocity", n3});
    append_attribute(out, file, "radius", "Scalar", "Node", {"/particles/", "radius", n});
    append_attribute(out, file, "material", "Scalar", "Node",
                     {"/particles/", "material", n, "Int", "4"});
    append_attribute(out, file, "id", "Scalar", "Node", {"/xdmf/", "vertices", n, "Int"});
    out += "      </Grid>\n";
  }
  out += "    </Grid>\n";
  // Block 1: the contacts, in every frame once any frame has some (a frame without contacts
  // gets an empty line set, so the blocks keep their places).
  if (any_contacts) {
    out += "    <Grid Name=\"contacts\" GridType=\"Collection\" CollectionType=\"Temporal\">\n";
    for (std::size_t f = 0; f < frames; ++f) {
      const bool some = views[f].contacts > 0;
      c = std::to_string(views[f].contacts);
      c2 = c + " 2";
      c3 = c + " 3";
      points = std::to_string(particles + views[f].wall_contacts + views[f].image_ends) + " 3";
      open_frame("contacts", f);
      out.append("        <Topology TopologyType=\"Polyline\" NumberOfElements=\"").append(c);
      out.append("\" NodesPerElement=\"2\">");
      append_item(out, file, some ? Item{view, "contact_lines", c2, "Int"}
                                  : Item{"/xdmf/", "no_lines", c2, "Int"});
      out.append("</Topology>\n        <Geometry GeometryType=\"XYZ\">");
      append_item(out, file, {view, some ? "contact_points" : "position", points});
      out.append("</Geometry>\n");
      for (const char* name : {"normal_force", "conductance", "heat_flow"})
        append_attribute(out, file, name, "Scalar", "Cell",
                         some ? Item{view, name, c} : Item{"/xdmf/", "no_values", c});
      append_attribute(out, file, "tangential_force", "Vector", "Cell",
                       some ? Item{view, "tangential_force", c3}
                            : Item{"/xdmf/", "no_vectors", c3});
      out += "      </Grid>\n";
    }
    out += "    </Grid>\n";
  }
  // Last block: the walls, repeated per frame so that every reader keeps them; static unless a
  // wall (a piston) has moved, then the frame's own corners.
  if (walls > 0) {
    out += "    <Grid Name=\"walls\" GridType=\"Collection\" CollectionType=\"Temporal\">\n";
    for (std::size_t f = 0; f < frames; ++f) {
      open_frame("walls", f);
      out.append("        <Topology TopologyType=\"Quadrilateral\" NumberOfElements=\"");
      out.append(w).append("\">");
      append_item(out, file, {"/xdmf/walls/", "quads", w4, "Int"});
      out.append("</Topology>\n        <Geometry GeometryType=\"XYZ\">");
      append_item(out, file, views[f].moved_walls ? Item{view, "wall_points", corners}
                                                  : Item{"/xdmf/walls/", "points", corners});
      out.append("</Geometry>\n");
      append_attribute(out, file, "temperature", "Scalar", "Cell",
                       {"/xdmf/walls/", "temperature", w});
      out += "      </Grid>\n";
    }
    out += "    </Grid>\n";
  }
  out += "  </Domain>\n</Xdmf>\n";
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
