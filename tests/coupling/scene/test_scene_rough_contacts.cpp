// The scene keys of rough contacts (thermal.conductance = "bahrami", fluid.model = "bahrami"):
// the material's surface keys are read with their defaults and ranges, and every refusal names
// the key (and the material) at fault: a rough surface without its slope or microhardness, a
// conductivity table, a gas model without the pressure its jump needs, a law that needs forces
// where there are none.
#include <gtest/gtest.h>

#include <string>

#include "tests/coupling/SceneTestUtil.h"

namespace tmdem::coupling::test {
namespace {

// material[0] is steel: Beaulieu's surface (sigma 19 nm, m 0.056, H_mic 3 GPa).
const std::vector<std::string> kRoughSteel{"material[0].roughness=19e-9",
                                           "material[0].asperity_slope=0.056",
                                           "material[0].microhardness=3e9"};

std::vector<std::string> with(std::vector<std::string> a, const std::vector<std::string>& b) {
  a.insert(a.end(), b.begin(), b.end());
  return a;
}

TEST(SceneRoughContacts, SurfaceKeysAreReadWithTheirDefaults) {
  const Scene plain = load_scene_text(kBaseScene, "t");
  EXPECT_EQ(plain.materials[0].roughness_m, 0.0);  // smooth
  EXPECT_EQ(plain.materials[0].asperity_slope, 0.0);
  EXPECT_EQ(plain.materials[0].microhardness_Pa, 0.0);  // not given
  const Scene rough = load_scene_text(kBaseScene, "t", with(kRoughSteel, {"thermal.conductance=\"bahrami\""}));
  EXPECT_EQ(rough.materials[0].roughness_m, 19e-9);
  EXPECT_EQ(rough.materials[0].asperity_slope, 0.056);
  EXPECT_EQ(rough.materials[0].microhardness_Pa, 3e9);
  EXPECT_EQ(rough.thermal.conductance, thermal::ConductanceLawKind::Bahrami);
  EXPECT_EQ(rough.materials[1].roughness_m, 0.0);  // glass stays smooth
}

TEST(SceneRoughContacts, SurfaceKeysOutOfRangeAreNamed) {
  expect_scene_error(kBaseScene, {"material[0].roughness=-1e-9"}, {"material[0].roughness", "must be >= 0"});
  expect_scene_error(kBaseScene, {"material[1].asperity_slope=-0.1"},
                     {"material[1].asperity_slope", "must be >= 0"});
  expect_scene_error(kBaseScene, {"material[0].microhardness=0.0"},
                     {"material[0].microhardness", "must be > 0"});
  expect_scene_error(kBaseScene, {"material[0].microhardness=\"hard\""},
                     {"material[0].microhardness", "expected a number"});
}

TEST(SceneRoughContacts, ARoughSurfaceNeedsItsSlopeAndMicrohardnessUnderTheRoughLaw) {
  expect_scene_error(kBaseScene,
                     {"thermal.conductance=\"bahrami\"", "material[0].roughness=19e-9",
                      "material[0].microhardness=3e9"},
                     {"material[0].asperity_slope", "rough surface", "bahrami"});
  expect_scene_error(kBaseScene,
                     {"thermal.conductance=\"bahrami\"", "material[0].roughness=19e-9",
                      "material[0].asperity_slope=0.056"},
                     {"material[0].microhardness", "rough surface", "bahrami"});
  // Smooth surfaces need neither; under the Hertz law the surface keys are not used at all.
  EXPECT_NO_THROW(load_scene_text(kBaseScene, "t", {"thermal.conductance=\"bahrami\""}));
  EXPECT_NO_THROW(load_scene_text(kBaseScene, "t", {"material[0].roughness=19e-9"}));
}

TEST(SceneRoughContacts, TheRoughLawIsChosenByNameAndRefusesWhatItCannotHonour) {
  expect_scene_error(kBaseScene, {"thermal.conductance=\"linear\""},
                     {"thermal.conductance", "\"hertz\", \"constant\", \"bahrami\""});
  // No k(T) form: a conductivity table is refused naming the material.
  expect_scene_error(kBaseScene,
                     {"thermal.conductance=\"bahrami\"", "material[1].conductivity=[[250.0, 2.0], [400, 3.5]]"},
                     {"thermal.conductance", "bahrami", "glass", "conductivity as a table"});
  // The roughness replaces the flattened spot.
  expect_scene_error(kBaseScene, {"thermal.conductance=\"bahrami\"", "thermal.contact_flattening=0.02"},
                     {"thermal.contact_flattening", "bahrami"});
  // It reads contact forces as the Hertz law does.
  expect_scene_error(kBaseScene, {"effects.mechanics=off", "thermal.conductance=\"bahrami\""},
                     {"thermal.conductance", "\"bahrami\" needs contact forces", "effects.mechanics = \"off\""});
}

TEST(SceneRoughContacts, TheMacrogapNeedsAPressureAndKeepsTheLumpedShells) {
  const std::vector<std::string> gas{"effects.gas_conduction=true", "fluid.model=\"bahrami\""};
  expect_scene_error(kBaseScene, gas, {"fluid.pressure", "model = \"bahrami\" needs the gas pressure"});
  const Scene scene = load_scene_text(
      kBaseScene, "t", with(gas, {"fluid.pressure=101325.0", "fluid.heat_capacity_ratio=1.4", "fluid.prandtl=0.69"}));
  EXPECT_EQ(scene.effects.heat.at("gas_conduction"), true);
  // A pressure is still refused with the touching-pair closed form of Vargas & McCarthy.
  expect_scene_error(kBaseScene, {"effects.gas_conduction=true", "fluid.pressure=101325.0"},
                     {"fluid.pressure", "vargas_mccarthy"});
  for (const char* bad : {"fluid.heat_capacity_ratio=0.9", "fluid.prandtl=0.0"})
    expect_scene_error(kBaseScene, with(gas, {"fluid.pressure=101325.0", bad}),
                       {std::string(bad).substr(0, std::string(bad).find('='))});
  // The shells per ray are the surrounding layer's: refused naming the model in use.
  expect_scene_error(kBaseScene,
                     with(gas, {"fluid.pressure=101325.0", "thermal.particle_resistance=\"isothermal_core_rays\""}),
                     {"thermal.particle_resistance", "fluid.model is \"bahrami\""});
  EXPECT_NO_THROW(load_scene_text(
      kBaseScene, "t", with(gas, {"fluid.pressure=101325.0", "thermal.particle_resistance=\"isothermal_core\""})));
}

}  // namespace
}  // namespace tmdem::coupling::test
