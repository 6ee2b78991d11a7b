// thermal.conductance and thermal.particle_resistance are parsed once into kinds: every name
// round-trips to its kind, the names stand in the enums' order, and an unknown name is refused
// with the valid names listed.
#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

#include "thermal/modes/ConductanceLaw.h"
#include "thermal/modes/ParticleResistanceKind.h"

namespace tmdem::thermal {

TEST(ContactLawKinds, ConductanceLawNamesRoundTrip) {
  EXPECT_EQ(conductance_law_from_name("hertz"), ConductanceLawKind::Hertz);
  EXPECT_EQ(conductance_law_from_name("constant"), ConductanceLawKind::Constant);
  EXPECT_EQ(conductance_law_from_name("bahrami"), ConductanceLawKind::Bahrami);
  for (auto name : kConductanceLawNames) EXPECT_EQ(name_of(conductance_law_from_name(name)), name);
  EXPECT_FALSE(conductance_law_uses_force(ConductanceLawKind::Constant));
  EXPECT_TRUE(conductance_law_uses_force(ConductanceLawKind::Bahrami));
}

TEST(ContactLawKinds, ParticleResistanceNamesRoundTrip) {
  EXPECT_EQ(parse_particle_resistance("off"), ParticleResistanceKind::Off);
  EXPECT_EQ(parse_particle_resistance("isothermal_core"), ParticleResistanceKind::IsothermalCore);
  EXPECT_EQ(parse_particle_resistance("isothermal_core_rays"),
            ParticleResistanceKind::IsothermalCoreRays);
  for (auto name : kParticleResistanceNames) EXPECT_EQ(name_of(parse_particle_resistance(name)), name);
}

TEST(ContactLawKinds, UnknownNamesListTheValidOnes) {
  try {
    conductance_law_from_name("Hertz");
    FAIL() << "Hertz accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("unknown conductance law \"Hertz\"; valid types are: "
                                         "hertz, constant, bahrami"),
              std::string::npos)
        << e.what();
  }
  try {
    parse_particle_resistance("shell");
    FAIL() << "shell accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("valid types are: off, isothermal_core, "
                                         "isothermal_core_rays"),
              std::string::npos)
        << e.what();
  }
}

}  // namespace tmdem::thermal
