#include "coupling/output/RunSummary.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <optional>
#include <type_traits>
#include <utility>

namespace tmdem::coupling {
namespace {

// One value into its key. Numbers that are NaN or infinite are written as null by nlohmann::json.
template <class Value>
void summary_put(nlohmann::json& object, const char* key, const Value& value, bool omit_empty) {
  if constexpr (std::is_same_v<Value, std::optional<double>>) {
    if (value) object[key] = *value;
    else if (!omit_empty) object[key] = nullptr;
  } else if constexpr (std::is_same_v<Value, std::string>) {
    if (!omit_empty || !value.empty()) object[key] = value;
  } else {
    object[key] = value;
  }
}

// One key into its value; a missing key leaves the value as it is (the struct's default). null
// reads back as NaN (what was written as null was not finite).
template <class Value>
void summary_get(const nlohmann::json& object, const char* key, Value& value) {
  if (!object.contains(key)) return;
  const nlohmann::json& node = object.at(key);
  if constexpr (std::is_same_v<Value, double> || std::is_same_v<Value, std::optional<double>>) {
    value = node.is_null() ? std::numeric_limits<double>::quiet_NaN() : node.get<double>();
  } else {
    value = node.get<Value>();
  }
}

// Every field of `fields` (RunSummary.h) from `block` into `object`, and back.
template <class Block, class Fields>
void write_summary_fields(nlohmann::json& object, const Block& block, const Fields& fields) {
  std::apply([&](const auto&... f) { (summary_put(object, f.key, block.*(f.member), f.omit_empty), ...); },
             fields);
}

template <class Block, class Fields>
void read_summary_fields(const nlohmann::json& object, Block& block, const Fields& fields) {
  std::apply([&](const auto&... f) { (summary_get(object, f.key, block.*(f.member)), ...); }, fields);
}

// An optional block: written under `key` when set, read back when present.
template <class Block, class Fields>
void write_summary_block(nlohmann::json& object, const char* key, const std::optional<Block>& block,
                 const Fields& fields) {
  if (block) write_summary_fields(object[key], *block, fields);
}

template <class Block, class Fields>
void read_summary_block(const nlohmann::json& object, const char* key, std::optional<Block>& block,
                const Fields& fields) {
  if (!object.contains(key)) return;
  Block b;
  read_summary_fields(object.at(key), b, fields);
  block = std::move(b);
}

const nlohmann::json& section(const nlohmann::json& object, const char* key) {
  static const nlohmann::json empty = nlohmann::json::object();
  return object.contains(key) ? object.at(key) : empty;
}

}  // namespace

nlohmann::json RunSummary::to_json() const {
  nlohmann::json j;
  write_summary_fields(j, *this, kRunSummaryFields);
  nlohmann::json& m = j["mechanics"];
  write_summary_fields(m, mechanics, kMechanicsSummaryFields);
  if (const auto& ts = mechanics.tolerance_schedule) {
    nlohmann::json& block = m["tolerance_schedule"];
    write_summary_fields(block, *ts, kToleranceScheduleFields);
    block["tightened_step"] = ts->tightened ? nlohmann::json(ts->tightened_step) : nlohmann::json();
    block["tightened_time_s"] = ts->tightened ? nlohmann::json(ts->tightened_time_s) : nlohmann::json();
  }
  write_summary_block(m, "fallback", mechanics.fallback, kFallbackSummaryFields);
  write_summary_fields(j["thermal"], thermal, kThermalSummaryFields);
  nlohmann::json& e = j["energy"];
  write_summary_fields(e, energy, kEnergySummaryFields);
  if (energy.mechanical) {
    nlohmann::json& me = e["mechanical"];
    write_summary_fields(me, *energy.mechanical, kMechanicalEnergyFields);
    if (energy.mechanical->heat) write_summary_fields(me, *energy.mechanical, kMechanicalHeatFields);
  }
  if (settle) {
    write_summary_block(j, "settle", settle, kSettleSummaryFields);
  } else {
    nlohmann::json& block = j["settle"];
    block["at_rest"] = packing_held ? nlohmann::json(true) : nlohmann::json();
    block["time_s"] = 0.0;
    block["steps"] = 0;
    block["max_speed_m_s"] = packing_held ? nlohmann::json(0.0) : nlohmann::json();
    block["ended_by"] = kNoSettlePhase;
  }
  write_summary_block(j, "thermo_mechanics", thermo_mechanics, kThermoMechanicsSummaryFields);
  write_summary_block(j, "wall_time_parts", wall_time_parts, kWallTimePartsFields);
  write_summary_block(j, "openmp", openmp, kOpenMpSummaryFields);
  write_summary_block(j, "mpi", mpi, kMpiSummaryFields);
  for (const auto& i : imports) {
    nlohmann::json entry;
    write_summary_fields(entry, i, kImportSummaryFields);
    j["imports"].push_back(std::move(entry));
  }
  return j;
}

RunSummary RunSummary::from_json(const nlohmann::json& j) {
  RunSummary s;
  read_summary_fields(j, s, kRunSummaryFields);
  const nlohmann::json& m = section(j, "mechanics");
  read_summary_fields(m, s.mechanics, kMechanicsSummaryFields);
  read_summary_block(m, "tolerance_schedule", s.mechanics.tolerance_schedule, kToleranceScheduleFields);
  if (auto& ts = s.mechanics.tolerance_schedule; ts && ts->tightened) {  // null (not tightened) stays 0
    const nlohmann::json& block = m.at("tolerance_schedule");
    summary_get(block, "tightened_step", ts->tightened_step);
    summary_get(block, "tightened_time_s", ts->tightened_time_s);
  }
  read_summary_block(m, "fallback", s.mechanics.fallback, kFallbackSummaryFields);
  read_summary_fields(section(j, "thermal"), s.thermal, kThermalSummaryFields);
  const nlohmann::json& e = section(j, "energy");
  read_summary_fields(e, s.energy, kEnergySummaryFields);
  read_summary_block(e, "mechanical", s.energy.mechanical, kMechanicalEnergyFields);
  if (auto& a = s.energy.mechanical) {
    a->heat = e.at("mechanical").contains("heat_generated_J");
    read_summary_fields(e.at("mechanical"), *a, kMechanicalHeatFields);
  }
  if (const nlohmann::json& block = section(j, "settle");
      block.contains("ended_by") && block.at("ended_by") == kNoSettlePhase)
    s.packing_held = block.at("at_rest").is_boolean() && block.at("at_rest").get<bool>();
  else
    read_summary_block(j, "settle", s.settle, kSettleSummaryFields);
  read_summary_block(j, "thermo_mechanics", s.thermo_mechanics, kThermoMechanicsSummaryFields);
  read_summary_block(j, "wall_time_parts", s.wall_time_parts, kWallTimePartsFields);
  read_summary_block(j, "openmp", s.openmp, kOpenMpSummaryFields);
  read_summary_block(j, "mpi", s.mpi, kMpiSummaryFields);
  if (j.contains("imports"))
    for (const auto& entry : j.at("imports")) read_summary_fields(entry, s.imports.emplace_back(), kImportSummaryFields);
  return s;
}

void RunSummary::write(const std::string& path) const {
  const std::string text = to_json().dump(2) + "\n";
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  if (!out) throw OutputError("cannot write run summary '" + path + "': cannot create the file");
  out << text;
  out.close();
  if (!out) throw OutputError("cannot write run summary '" + path + "': write failed");
}

MechanicalEnergySummary MechanicalEnergySummary::with_errors(bool heat_on) const {
  MechanicalEnergySummary a = *this;
  const double scale =
      std::max(std::abs(energy_change_J), std::abs(contact_dissipation_J) + std::abs(numerical_dissipation_J));
  a.balance_error_rel =
      scale == 0.0 ? 0.0
                   : std::abs(energy_change_J + contact_dissipation_J + numerical_dissipation_J) / scale;
  a.heat = heat_on;
  a.heat_error_rel = 0.0;
  if (!heat_on) return a;
  // The run's bookkeeping: what it handed over against what the mechanics dissipated.
  if (contact_dissipation_J == 0.0)
    a.heat_error_rel = heat_generated_J == 0.0 ? 0.0 : 1.0;  // heat out of nothing: all wrong
  else
    a.heat_error_rel =
        std::abs(heat_generated_J - contact_dissipation_J) / std::abs(contact_dissipation_J);
  // The integrator's: what it integrated of the particles' share against the exact integral.
  const double received_scale = std::max(std::abs(heat_share_J), std::abs(heat_received_J));
  if (received_scale > 0.0)
    a.heat_error_rel = std::max(a.heat_error_rel,
                                std::abs(heat_received_J - heat_share_J) / received_scale);
  return a;
}

double RunSummary::balance_error_rel(double initial_J, double final_J, double boundary_heat_J) {
  const double scale = std::max(std::abs(initial_J), std::abs(boundary_heat_J));
  if (scale == 0.0) return 0.0;  // nothing to compare with (as specified)
  return std::abs(final_J - initial_J - boundary_heat_J) / scale;
}

}  // namespace tmdem::coupling
