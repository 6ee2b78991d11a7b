#pragma once
// Turns a scene and the mechanics' contacts into the thermal network: nodes from the particles,
// edges (with conductances from the scene's law) from the contacts, and the list of
// heat-transfer modes the scene switches on. The only place that knows both sides' data.
#include <string>
#include <vector>

#include "coupling/bridge/ContactList.h"
#include "coupling/scene/Scene.h"
#include "mechanics/model/ParticleSet.h"
#include "mechanics/model/Wall.h"
#include "thermal/modes/ConductanceLaw.h"
#include "thermal/modes/ModeSettings.h"
#include "thermal/modes/RoughContactConductance.h"
#include "thermal/network/ThermalNetwork.h"

namespace tmdem::coupling {

class ThermalNetworkBuilder {
 public:
  explicit ThermalNetworkBuilder(const Scene& scene);

  // Node data: heat capacity m c, surface 4 pi r^2, emissivity, sources, held flags, wall
  // temperature tables and flux-wall powers (flux x area).
  thermal::ThermalNetwork nodes() const;
  // Fills contacts.conductance_W_per_K and writes the edge arrays of `edges` (node arrays are
  // left alone). A wall contact becomes an edge only for an isothermal wall; with conduction
  // off (no switched-on mode reads conductances), no contact carries heat and every
  // conductance is 0.
  // is_active (optional, one per contact): 0 marks a pattern-only pair, an edge of zero
  // conductance that keeps the sparsity pattern while the contact is open.
  // geometry: the packing the contacts belong to. Required when a switched-on mode works across
  // gaps (ModeDescription::near_pair_reach): every contact then becomes an edge (contact
  // conductance 0 if conduction is off) with its gap and Hertz contact radius, and every pair
  // within the reach (cell-grid search, O(N)) that is no contact is added as a near edge.
  void build_edges(ContactList& contacts, thermal::ThermalNetwork& edges,
                   const std::vector<std::uint8_t>* is_active = nullptr,
                   const mechanics::ParticleSet* geometry = nullptr) const;
  // Largest reach of the switched-on gap modes, fraction of the smaller radius (0: none).
  double near_reach() const { return near_reach_; }
  // Moving packings: `out` = the step's contacts (canonical order) plus every near pair of
  // `geometry` within the reach (cell grid, O(N); force 0; isothermal walls only), canonical.
  void add_near_pairs(const ContactList& contacts, const mechanics::ParticleSet& geometry,
                      ContactList& out) const;
  // Edges for every entry of a sticky pattern (canonical order, near pairs included), each with
  // this step's gap; contact conductance only for the entries that are contacts now (`active`,
  // canonical). Fills pattern.conductance_W_per_K.
  void build_pattern_edges(ContactList& pattern, const ContactList& active,
                           thermal::ThermalNetwork& edges,
                           const mechanics::ParticleSet& geometry) const;

  // Conductance of one contact by the scene's law, W/K.
  double conductance_W_per_K(std::int64_t i, std::int64_t j, double normal_force_N) const;

  // Names of the registered heat-transfer modes the scene switches on and that are in use on
  // these nodes (e.g. no heat_source mode without a source), in registry (RHS) order.
  std::vector<std::string> mode_names(const thermal::ThermalNetwork& nodes) const;
  // Every mode's parameters, as read from the scene's sections.
  const thermal::ModeSettings& mode_settings() const;

 private:
  thermal::ContactBody body(std::int64_t id) const;  // id: particle, or a wall (mechanics/model/PairIndex.h)

  const Scene& scene_;
  // Per scene wall: index of its temperature table / of its flux power in the network's node
  // data, -1 for none.
  std::vector<std::int32_t> wall_table_, wall_flux_;
  thermal::ConductanceLawKind law_;
  thermal::ContactGas contact_gas_;  // the gas in rough contacts' micro-gaps (none: vacuum)
  bool contacts_carry_heat_;  // some switched-on mode reads the contact conductances
  double near_reach_;         // fraction of the smaller radius; 0: contacts only
  bool line_of_sight_;        // some enabled mode needs the shadowed near pairs marked

  void build_edges_with_gaps(ContactList& contacts, thermal::ThermalNetwork& edges,
                             const mechanics::ParticleSet& geometry) const;
  // One edge with its gap: particle pair, flux-wall contact or isothermal wall (adiabatic: none).
  void add_gap_edge(thermal::ThermalNetwork& edges, std::int64_t i, std::int64_t j, double H,
                    double force_N, bool contact, const mechanics::ParticleSet& geometry,
                    const std::vector<mechanics::Wall>& walls) const;
  bool contact_carries_heat(std::int64_t j) const;  // j: particle or wall code
  // An isothermal-wall edge (with its wall's material when properties follow T).
  void add_wall_edge(thermal::ThermalNetwork& edges, std::int64_t i, std::size_t wall, double H,
                     double gap_m = 0.0, double contact_radius_m = 0.0, bool contact = true) const;
  // Temperature-dependent materials: every material's k(T) and c(T) tables (a constant as one
  // point), each node's material and mass (ThermalNetwork).
  void add_material_tables(thermal::ThermalNetwork& net) const;
  static void points_to_table(const std::vector<std::array<double, 2>>& points,
                              thermal::PiecewiseLinearTable& table);
  bool temperature_dependent_;  // some material gives k or c as a table
};

}  // namespace tmdem::coupling
