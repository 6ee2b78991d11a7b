#pragma once
// The scene's view of the registered heat-transfer modes (thermal/modes/ModeRegistry.h): which ones
// its effects switch on, whether contacts carry heat, the reservoir temperatures they bring.
// Generic on purpose: nothing here (or anywhere in coupling/) names a mode.
#include "coupling/scene/Scene.h"
#include "thermal/modes/ModeDescription.h"

namespace tmdem::coupling {

// The mode's effects.<key> is on (a mode without a switch counts as on; whether it is in use is
// up to its own in_use test on the network).
bool switched_on(const Effects& effects, const thermal::ModeDescription& mode);

// Switched on, and its enabled_by parameter (if it declares one) is true: the mode is built.
bool mode_enabled(const Scene& scene, const thermal::ModeDescription& mode);

// Largest near-pair reach (fraction of the smaller radius) of the enabled modes; 0 if none needs
// near pairs.
double near_pair_reach(const Scene& scene);

// Some enabled mode needs to know which near pairs see each other
// (ModeDescription::needs_line_of_sight).
bool needs_line_of_sight(const Scene& scene);

// Some switched-on mode reads the contact conductances: contacts become network edges.
bool contacts_carry_heat(const Effects& effects);

// Some switched-on mode turns the contacts' dissipated mechanical power into heat
// (ModeDescription::uses_contact_dissipation): the coupling hands it to the network every step.
bool contacts_dissipate_heat(const Effects& effects);

// Largest reservoir temperature (fluid, surroundings, ...) of the switched-on modes, K; 0 if none.
double max_mode_temperature_K(const Scene& scene);

}  // namespace tmdem::coupling
