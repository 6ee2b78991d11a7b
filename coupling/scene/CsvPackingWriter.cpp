#include "coupling/scene/CsvPackingWriter.h"

#include "coupling/common/ShortestNumber.h"

namespace tmdem::coupling {

std::string packing_csv(const Packing& packing) {
  bool material = false, temperature = false, fixed = false, held = false, source = false;
  for (const auto& row : packing.rows) {
    material = material || row.material.has_value();
    temperature = temperature || row.temperature_K.has_value();
    fixed = fixed || row.fixed.has_value();
    held = held || row.fixed_temperature.has_value();
    source = source || row.heat_source_W.has_value();
  }
  std::string out = "x,y,z,radius";
  if (material) out += ",material";
  if (temperature) out += ",temperature";
  if (fixed) out += ",fixed";
  if (held) out += ",fixed_temperature";
  if (source) out += ",heat_source";
  out += '\n';
  // Appended piece by piece: GCC 12 warns falsely (-Wrestrict) on "literal" + std::string.
  const auto cell = [&out](const std::string& text) {
    out += ',';
    out += text;
  };
  for (const auto& row : packing.rows) {
    out += shortest_number(row.position[0]);
    cell(shortest_number(row.position[1]));
    cell(shortest_number(row.position[2]));
    cell(shortest_number(row.radius));
    if (material) cell(row.material.value_or(""));
    if (temperature) cell(shortest_number(row.temperature_K.value_or(293.15)));
    if (fixed) cell(row.fixed.value_or(false) ? "1" : "0");
    if (held) cell(row.fixed_temperature.value_or(false) ? "1" : "0");
    if (source) cell(shortest_number(row.heat_source_W.value_or(0.0)));
    out += '\n';
  }
  return out;
}

}  // namespace tmdem::coupling
