// The built-in heat-transfer modes, one line each, in the order their heat flows are summed:
// TMDEM_HEAT_MODE(name) expects `const ModeDescription& name_mode()` in the mode's own .cpp file
// (thermal/modes/ModeDescription.h). Adding a mode, with its effects key, scene section and
// parameters = one new file + one line here (docs/developing.md: "Adding a heat-transfer mode").
// No include guard on purpose: ModeRegistry.cpp includes this list twice with different
// definitions of the macro. An explicit list, not static self-registration: a static library
// drops object files nothing refers to, and with them their registrations.
TMDEM_HEAT_MODE(contact_conduction)
TMDEM_HEAT_MODE(wall_conduction)
TMDEM_HEAT_MODE(wall_flux)
TMDEM_HEAT_MODE(convection)
TMDEM_HEAT_MODE(radiation)
TMDEM_HEAT_MODE(particle_radiation)
TMDEM_HEAT_MODE(gas_conduction)
TMDEM_HEAT_MODE(heat_source)
TMDEM_HEAT_MODE(friction_heat)
