// The registered heat-transfer modes, one line each: TMDEM_HEAT_MODE(name) expects a factory
// `std::unique_ptr<HeatTransferMode> make_<name>_mode(const ModeSettings&)` defined in the mode's
// own .cpp file. Adding a mode = one new file + one line here. No include guard on purpose:
// ModeRegistry.cpp includes this list twice with different definitions of the macro.
TMDEM_HEAT_MODE(contact_conduction)
TMDEM_HEAT_MODE(wall_conduction)
TMDEM_HEAT_MODE(convection)
TMDEM_HEAT_MODE(radiation)
TMDEM_HEAT_MODE(heat_source)
TMDEM_HEAT_MODE(fault_injection)
