#include "coupling/scene/DefaultScene.h"

#include "coupling/scene/SceneLoader.h"

namespace tmdem::coupling {

namespace {

// Keep identical to examples/paper_bed.toml (tests/coupling/test_scene_examples.cpp checks it).
constexpr std::string_view kDefaultScene = R"tmdem(# tmdem default scene (`tmdem run` without a scene runs exactly this file): the heated,
# sedimented 256-particle bed of the reference paper.
#
# 256 steel particles of three radii (0.5, 0.75 and 1 mm) are placed at random in a box, settle
# under gravity onto a floor between two side walls (motion in the xy-plane), and are then
# frozen. The three particles nearest to the bottom-left corner start at 373.15 K, all others at
# 293.15 K; heat spreads through the Hertz contacts (H = 2 k a). With contact conductances of
# about 1e-4 W/K and particle heat capacities of 2e-3 to 1.5e-2 J/K, the time constant of one
# contact is 10 to 100 s, so after 100 s the heat has visibly spread over the neighbours.
format = "tmdem-scene-1"

[simulation]
duration = 100.0
dimension = 2
gravity = [0.0, -9.81, 0.0]
seed = 1

[effects]
mechanics = "settle"
conduction = true
convection = false
radiation = false

[[material]]
name = "steel"
density = 7800.0
young_modulus = 2.1e11
poisson_ratio = 0.3
friction = 0.3
conductivity = 50.0
heat_capacity = 460.0
emissivity = 0.0

[[generate]]
kind = "random"
count = 256
box = { min = [0.001, 0.001, 0.0], max = [0.029, 0.045, 0.0] }
radii = [0.0005, 0.00075, 0.001]
fractions = [0.4, 0.35, 0.25]
material = "steel"
temperature = 293.15

[[assign]]                       # the three particles nearest to the bottom-left corner
nearest = { point = [0.0, 0.0, 0.0], count = 3 }
temperature = 373.15

[[wall]]                         # floor
point = [0.0, 0.0, 0.0]
normal = [0.0, 1.0, 0.0]
material = "steel"

[[wall]]                         # left side
point = [0.0, 0.0, 0.0]
normal = [1.0, 0.0, 0.0]
material = "steel"

[[wall]]                         # right side
point = [0.03, 0.0, 0.0]
normal = [-1.0, 0.0, 0.0]
material = "steel"

[mechanics]
time_step = 1.0e-3
theta = 0.5
settle_time = 5.0
settle_velocity = 1.0e-4

[thermal]
integrator = "cvode"
linear_solver = "klu"
relative_tolerance = 1.0e-6
absolute_tolerance = 1.0e-6
conductance = "hertz"

[output]
file = "tmdem-default.h5"
interval = 1.0
contacts = true
)tmdem";

}  // namespace

std::string_view default_scene_toml() { return kDefaultScene; }

Scene load_default_scene(const std::vector<std::string>& set_overrides) {
  return load_scene_text(kDefaultScene, kDefaultSceneSource, set_overrides);
}

}  // namespace tmdem::coupling
