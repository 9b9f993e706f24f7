// Scene: everything a run needs except the integrator, dt overrides and precision. Parameters are
// stored in double, exactly as written in the scene JSON; a world converts them to its precision.
// A scene holds only the parts it uses: a cloth (grid or explicit particles and springs), spheres,
// or both.
#pragma once

#include <array>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "clothref/io/error.h"

namespace clothref {

using Vector3 = std::array<double, 3>;

// The course's n x n grid (initializeVertex + initializeSpring).
struct GridSpec {
  int particles_per_edge = 25;  // n >= 2
  double half_extent = 2;       // metres; the grid spans [-h, h] in x and z
  double y = 0;                 // metres; height of the grid plane
  double particle_mass = 1;     // kilograms, every grid particle

  bool operator==(const GridSpec&) const = default;
};

// One particle of an explicitly listed cloth.
struct ParticleSpec {
  Vector3 position{};
  Vector3 velocity{};
  double mass = 1;  // kilograms; 0 = fixed

  bool operator==(const ParticleSpec&) const = default;
};

// One explicitly listed spring.
struct SpringSpec {
  int start = 0;
  int end = 1;
  double rest_length = 1;  // metres

  bool operator==(const SpringSpec&) const = default;
};

struct ClothSpec {
  std::optional<GridSpec> grid;         // either a grid ...
  std::vector<ParticleSpec> particles;  // ... or explicit particles
  std::vector<SpringSpec> springs;      //     and springs
  std::vector<int> fixed;      // particle indices given mass 0 (grid corners in the course)
  double spring_coef = 25000;  // N/m
  double damper_coef = 750;    // N s/m

  bool operator==(const ClothSpec&) const = default;
};

struct SphereSpec {
  Vector3 center{};
  double radius = 0.5;         // metres
  Vector3 velocity{};          // metres / second
  std::optional<double> mass;  // kilograms; default density * r^3 (the course's formula)

  bool operator==(const SphereSpec&) const = default;
};

struct SpheresSpec {
  std::vector<SphereSpec> items;
  double density = 1000;                // kg / m^3 in the course's mass = density * r^3
  bool external_force = true;           // gravity and drag on spheres (2022 yes, 2024 no)
  bool sphere_sphere_collision = true;  // the 2022 Spheres::collide() (removed in 2024)
  double restitution_cloth = 0;         // coefRestitution in Spheres::collide(Cloth*)
  double restitution_sphere = 0.8;      // coefRestitution in Spheres::collide()
  double correction = 0.15;             // fraction of the penetration undone per contact

  bool operator==(const SpheresSpec&) const = default;
};

// The 2024 course program's per-frame work (docs/course.md): before each frame's steps it re-pins
// the fixed cloth particles (mass 0, velocity and acceleration zero) and sets sphere 0's velocity
// to the held value (spheres.setVelocity(0, vel)). A scene without it steps as the 2022 loop does.
struct FrameLoopSpec {
  // the course's simulationPerFrame (10 at dt 1e-4) x speedMultiplier (240 / refresh rate):
  // 40 on a 60 Hz monitor, 16 at 150 Hz, 10 at 240 Hz
  int steps_per_frame = 40;
  Vector3 sphere_velocity{};  // metres / second; arrow keys hold +-5 in x or z, space resets to 0

  bool operator==(const FrameLoopSpec&) const = default;
};

struct Scene {
  std::string name;
  std::string description;
  double dt = 1e-4;              // seconds (the course's deltaTime)
  Vector3 gravity{0, -9.8, 0};   // metres / second^2
  double viscous_coef = 3.4e-4;  // kg / s, linear drag on every free particle
  std::optional<ClothSpec> cloth;
  std::optional<SpheresSpec> spheres;
  std::optional<FrameLoopSpec> frame_loop;  // absent: no per-frame work (the 2022 loop)

  bool operator==(const Scene&) const = default;
};

// Bad scene content. what() is one line, "<JSON pointer>: <problem>", for example
// "/cloth/spring_coef: expected a number, got string".
class SceneError : public InputError {
 public:
  SceneError(const std::string& pointer, const std::string& problem)
      : InputError((pointer.empty() ? std::string("/") : pointer) + ": " + problem) {}
};

// Every parameter, in a fixed key order.
nlohmann::ordered_json sceneToJson(const Scene& scene);

// Reads and validates a scene; throws SceneError on an unknown key, a wrong type, a non-finite
// number or an out-of-range value.
Scene sceneFromJson(const nlohmann::json& document);

// Checks ranges and indices of a scene built in code; throws SceneError as sceneFromJson does.
void validateScene(const Scene& scene);

// The built-in scenes, the default (course2022) first.
const std::vector<Scene>& builtinScenes();

// A built-in scene by name, or nullptr.
const Scene* findBuiltinScene(const std::string& name);

// A built-in scene name, or a path to a scene JSON file. Throws InputError naming the file and,
// for bad content, the JSON pointer: "scenes/x.json: /dt: must be > 0 (got -1)".
Scene loadScene(const std::string& name_or_path);

// Number of cloth particles of a scene (0 without a cloth).
int clothParticleCount(const Scene& scene);

}  // namespace clothref
