#pragma once
// What a heat-transfer mode declares about itself, all in its own .cpp file: the name it is built
// by, the effects.<key> switch that turns it on, its scene section and the numbers it reads there
// (unit, default, allowed range, one-line description), any further check of those numbers, and
// its factory. The scene reader, the scene schema, `tmdem check` and the generated scene
// reference (docs/scene.md) read these declarations generically, so nothing outside the mode's
// file names the mode (LAMMPS sub-model / OpenFOAM run-time selection style).
// Plain data on purpose: no TOML here, thermal/ stays free of the scene format.
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "thermal/modes/HeatTransferMode.h"
#include "thermal/network/ThermalNetwork.h"

namespace tmdem::thermal {

// Allowed values of a number. describe() gives the phrase used in error messages and the docs.
struct ParameterRange {
  enum class Kind { Any, Greater, AtLeast, Open, OpenClosed, Closed };
  Kind kind = Kind::Any;
  double lo = 0.0;
  double hi = 0.0;

  static constexpr ParameterRange any() { return {}; }
  static constexpr ParameterRange greater(double lo) { return {Kind::Greater, lo, 0.0}; }
  static constexpr ParameterRange at_least(double lo) { return {Kind::AtLeast, lo, 0.0}; }
  static constexpr ParameterRange open(double lo, double hi) { return {Kind::Open, lo, hi}; }
  static constexpr ParameterRange open_closed(double lo, double hi) {
    return {Kind::OpenClosed, lo, hi};
  }
  static constexpr ParameterRange closed(double lo, double hi) { return {Kind::Closed, lo, hi}; }

  bool contains(double value) const;
  std::string describe() const;  // "must be > 0", "must be in (-1, 0.5)"
  std::string interval() const;  // "> 0", "(-1, 0.5)", "any finite number"
};

// One value a mode reads from its scene section: a number, a boolean (`boolean`, stored as 0 or
// 1) or a name out of `choices` (stored as its index; an unknown name lists the valid ones).
struct ModeParameter {
  std::string_view key{};          // key inside the section: "coefficient"
  std::string_view unit{};         // "W/(m^2 K)", "K"; "" for a pure number
  double default_value = 0.0;    // used when the scene omits the key
  ParameterRange range;          // checked when the mode is switched on
  std::string_view description{};  // one line, for the scene reference
  // A reservoir temperature (fluid, surroundings) the particles can be driven to: it counts
  // towards the largest temperature of the run (explicit stability bound, `tmdem check`).
  bool bounds_temperature = false;
  bool boolean = false;                      // true/false in the scene; default_value 0 or 1
  std::vector<std::string_view> choices{};   // names; default_value is the default's index
};

struct ModeDescription;

// Shortest text that reads back as the same double ("0.001", "2.1e+11"), for messages.
std::string parameter_text(double value);

// The values of one mode's parameters, in declaration order, defaults filled in.
class ModeParameters {
 public:
  ModeParameters(const ModeDescription& mode, std::vector<double> values);
  // The value of a declared key; an undeclared key is a programming error (std::logic_error).
  double operator[](std::string_view key) const;
  // The name chosen for a declared choice parameter.
  std::string_view choice(std::string_view key) const;
  const ModeDescription& mode() const { return *mode_; }

 private:
  const ModeDescription* mode_;
  std::vector<double> values_;
};

// A problem found by a mode's own check: the key it concerns and what is wrong, e.g.
// {"max_temperature", "must be > min_temperature = 300 (got 250)"}.
struct ParameterProblem {
  std::string key;
  std::string problem;
};

struct ModeDescription {
  std::string_view name{};     // registry name, also the key of its values in ModeSettings
  std::string_view summary{};  // one line: what the mode adds to the heat balance

  // The scene switch effects.<effect>. Several modes may share one (contact and wall conduction
  // both follow effects.conduction) if they declare the same default. "" = no switch: the mode is
  // on whenever in_use says so.
  std::string_view effect{};
  bool effect_default = false;
  std::string_view effect_description{};

  // The scene section [section] holding `parameters`; "" when the mode has none.
  std::string_view section{};
  std::string_view section_description{};
  std::vector<ModeParameter> parameters{};

  // True for modes that read the contact conductances: contacts become network edges (with their
  // conductances) only while such a mode is switched on.
  bool uses_contact_conductance = false;
  // True for modes that read the mechanical power dissipated at the contacts
  // (ThermalNetwork::dissipation_W): the coupling then fills it every mechanical step, and the
  // scene refuses the mode's switch unless effects.mechanics = "dynamic".
  bool uses_contact_dissipation = false;
  // Key of the parameter that holds the mode's reach across gaps, as a fraction of the smaller
  // radius ("" = contacts only). The network then also holds every pair (and isothermal-wall
  // pair) whose gap is at most that fraction, with its gap (thermal/network/ThermalNetwork.h). Near
  // pairs come from a cell-grid search of the packing (frozen: once; dynamic: every step).
  std::string_view near_pair_reach{};
  // True for modes that need to know which near pairs see each other: the network then marks
  // the pairs whose centre-to-centre line a third particle crosses
  // (ThermalNetwork::edge_shadowed).
  bool needs_line_of_sight = false;
  // Key of a boolean parameter that must be true for the mode to be built ("" = none), for a
  // mode that shares its effects switch and section with another (pair radiation).
  std::string_view enabled_by{};
  // Further condition on the network's nodes (null: always), e.g. only when some particle has a
  // heat source. A mode that is off or not in use is never constructed.
  bool (*in_use)(const ThermalNetwork& nodes) = nullptr;
  // Checks across parameters beyond each one's range (null: none).
  std::optional<ParameterProblem> (*check)(const ModeParameters& parameters) = nullptr;
  std::unique_ptr<HeatTransferMode> (*make)(const ModeParameters& parameters) = nullptr;
};

}  // namespace tmdem::thermal
