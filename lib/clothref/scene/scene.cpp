#include "clothref/scene/scene.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <set>

#include <fmt/format.h>

#include "clothref/io/json_input.h"

namespace clothref {

using ordered_json = nlohmann::ordered_json;
using json = nlohmann::json;

namespace {

std::string typeName(const json& value) {
  if (value.is_number_integer() || value.is_number_unsigned()) return "integer";
  return value.type_name();
}

// Reads one JSON object, tracking its pointer for messages and rejecting keys nobody read.
class ObjectReader {
 public:
  ObjectReader(const json& value, std::string pointer)
      : value_(value), pointer_(std::move(pointer)) {
    if (!value_.is_object())
      throw SceneError(pointer_, "expected an object, got " + typeName(value_));
  }

  bool has(const std::string& key) const { return value_.contains(key) && !value_[key].is_null(); }
  std::string at(const std::string& key) const { return pointer_ + "/" + key; }

  const json& get(const std::string& key) {
    seen_.insert(key);
    if (!value_.contains(key)) throw SceneError(at(key), "missing");
    return value_[key];
  }

  double number(const std::string& key) { return checkNumber(get(key), at(key)); }

  int integer(const std::string& key) {
    const json& v = get(key);
    if (!v.is_number_integer() && !v.is_number_unsigned())
      throw SceneError(at(key), "expected an integer, got " + typeName(v));
    const auto i = v.get<long long>();
    if (i < -1000000000LL || i > 1000000000LL) throw SceneError(at(key), "out of range");
    return static_cast<int>(i);
  }

  bool boolean(const std::string& key) {
    const json& v = get(key);
    if (!v.is_boolean()) throw SceneError(at(key), "expected true or false, got " + typeName(v));
    return v.get<bool>();
  }

  std::string string(const std::string& key) {
    const json& v = get(key);
    if (!v.is_string()) throw SceneError(at(key), "expected a string, got " + typeName(v));
    return v.get<std::string>();
  }

  Vector3 vector3(const std::string& key) { return checkVector3(get(key), at(key)); }

  const json& array(const std::string& key) {
    const json& v = get(key);
    if (!v.is_array()) throw SceneError(at(key), "expected an array, got " + typeName(v));
    return v;
  }

  // Marks an optional key as known even when it is absent.
  void optional(const std::string& key) { seen_.insert(key); }

  // Call after reading: any key not read is unknown.
  void finish() const {
    for (const auto& item : value_.items())
      if (!seen_.count(item.key())) throw SceneError(at(item.key()), "unknown key");
  }

  static double checkNumber(const json& v, const std::string& pointer) {
    if (!v.is_number()) throw SceneError(pointer, "expected a number, got " + typeName(v));
    const double d = v.get<double>();
    if (!std::isfinite(d)) throw SceneError(pointer, "must be finite");
    return d;
  }

  static Vector3 checkVector3(const json& v, const std::string& pointer) {
    if (!v.is_array() || v.size() != 3)
      throw SceneError(pointer, "expected an array of 3 numbers [x, y, z]");
    return {checkNumber(v[0], pointer + "/0"), checkNumber(v[1], pointer + "/1"),
            checkNumber(v[2], pointer + "/2")};
  }

 private:
  const json& value_;
  std::string pointer_;
  std::set<std::string> seen_;
};

void require(bool ok, const std::string& pointer, const std::string& problem) {
  if (!ok) throw SceneError(pointer, problem);
}

std::string got(double value) { return fmt::format(" (got {})", value); }

GridSpec readGrid(const json& value, const std::string& pointer) {
  ObjectReader r(value, pointer);
  GridSpec grid;
  grid.particles_per_edge = r.integer("particles_per_edge");
  grid.half_extent = r.number("half_extent");
  grid.y = r.number("y");
  grid.particle_mass = r.number("particle_mass");
  r.finish();
  return grid;
}

ClothSpec readCloth(const json& value, const std::string& pointer) {
  ObjectReader r(value, pointer);
  ClothSpec cloth;
  r.optional("grid");
  r.optional("particles");
  r.optional("springs");
  r.optional("fixed");
  if (r.has("grid")) {
    require(!r.has("particles") && !r.has("springs"), r.at("grid"),
            "give either a grid or particles and springs, not both");
    cloth.grid = readGrid(r.get("grid"), r.at("grid"));
  } else {
    require(r.has("particles"), r.at("particles"), "missing (a cloth needs a grid or particles)");
    const json& particles = r.array("particles");
    for (std::size_t i = 0; i < particles.size(); ++i) {
      ObjectReader p(particles[i], r.at("particles") + "/" + std::to_string(i));
      ParticleSpec spec;
      spec.position = p.vector3("position");
      p.optional("velocity");
      if (p.has("velocity")) spec.velocity = p.vector3("velocity");
      spec.mass = p.number("mass");
      p.finish();
      cloth.particles.push_back(spec);
    }
    if (r.has("springs")) {
      const json& springs = r.array("springs");
      for (std::size_t i = 0; i < springs.size(); ++i) {
        ObjectReader s(springs[i], r.at("springs") + "/" + std::to_string(i));
        SpringSpec spec;
        spec.start = s.integer("start");
        spec.end = s.integer("end");
        spec.rest_length = s.number("rest_length");
        s.finish();
        cloth.springs.push_back(spec);
      }
    }
  }
  if (r.has("fixed")) {
    const json& fixed = r.array("fixed");
    for (std::size_t i = 0; i < fixed.size(); ++i) {
      const std::string at = r.at("fixed") + "/" + std::to_string(i);
      require(fixed[i].is_number_integer() || fixed[i].is_number_unsigned(), at,
              "expected an integer particle index, got " + typeName(fixed[i]));
      const auto index = fixed[i].get<long long>();
      require(index >= 0 && index <= 1000000000LL, at, "particle index out of range");
      cloth.fixed.push_back(static_cast<int>(index));
    }
  }
  cloth.spring_coef = r.number("spring_coef");
  cloth.damper_coef = r.number("damper_coef");
  r.finish();
  return cloth;
}

SpheresSpec readSpheres(const json& value, const std::string& pointer) {
  ObjectReader r(value, pointer);
  SpheresSpec spheres;
  const json& items = r.array("items");
  for (std::size_t i = 0; i < items.size(); ++i) {
    ObjectReader s(items[i], r.at("items") + "/" + std::to_string(i));
    SphereSpec spec;
    spec.center = s.vector3("center");
    spec.radius = s.number("radius");
    s.optional("velocity");
    if (s.has("velocity")) spec.velocity = s.vector3("velocity");
    s.optional("mass");
    if (s.has("mass")) spec.mass = s.number("mass");
    s.finish();
    spheres.items.push_back(spec);
  }
  spheres.density = r.number("density");
  spheres.external_force = r.boolean("external_force");
  spheres.sphere_sphere_collision = r.boolean("sphere_sphere_collision");
  spheres.restitution_cloth = r.number("restitution_cloth");
  spheres.restitution_sphere = r.number("restitution_sphere");
  spheres.correction = r.number("correction");
  r.finish();
  return spheres;
}

FrameLoopSpec readFrameLoop(const json& value, const std::string& pointer) {
  ObjectReader r(value, pointer);
  FrameLoopSpec frame_loop;
  frame_loop.steps_per_frame = r.integer("steps_per_frame");
  frame_loop.sphere_velocity = r.vector3("sphere_velocity");
  r.finish();
  return frame_loop;
}

ordered_json vector3ToJson(const Vector3& v) { return ordered_json::array({v[0], v[1], v[2]}); }

}  // namespace

int clothParticleCount(const Scene& scene) {
  if (!scene.cloth) return 0;
  if (scene.cloth->grid)
    return scene.cloth->grid->particles_per_edge * scene.cloth->grid->particles_per_edge;
  return static_cast<int>(scene.cloth->particles.size());
}

void validateScene(const Scene& scene) {
  require(scene.dt > 0, "/dt", "must be > 0" + got(scene.dt));
  require(scene.viscous_coef >= 0, "/viscous_coef", "must be >= 0" + got(scene.viscous_coef));
  require(scene.cloth || scene.spheres, "", "a scene needs a cloth, spheres or both");
  if (scene.cloth) {
    const ClothSpec& cloth = *scene.cloth;
    if (cloth.grid) {
      const GridSpec& grid = *cloth.grid;
      require(grid.particles_per_edge >= 2, "/cloth/grid/particles_per_edge",
              fmt::format("cloth edge must have >= 2 particles (got {})", grid.particles_per_edge));
      require(grid.particles_per_edge <= 4096, "/cloth/grid/particles_per_edge",
              fmt::format("must be <= 4096 (got {})", grid.particles_per_edge));
      require(grid.half_extent > 0, "/cloth/grid/half_extent",
              "must be > 0" + got(grid.half_extent));
      require(grid.particle_mass >= 0, "/cloth/grid/particle_mass",
              "mass must be >= 0" + got(grid.particle_mass));
    } else {
      require(!cloth.particles.empty(), "/cloth/particles", "needs at least one particle");
      for (std::size_t i = 0; i < cloth.particles.size(); ++i)
        require(cloth.particles[i].mass >= 0, fmt::format("/cloth/particles/{}/mass", i),
                "mass must be >= 0" + got(cloth.particles[i].mass));
      const int count = static_cast<int>(cloth.particles.size());
      for (std::size_t i = 0; i < cloth.springs.size(); ++i) {
        const SpringSpec& s = cloth.springs[i];
        const std::string at = fmt::format("/cloth/springs/{}", i);
        require(s.start >= 0 && s.start < count, at + "/start",
                fmt::format("particle index {} out of range [0, {})", s.start, count));
        require(s.end >= 0 && s.end < count, at + "/end",
                fmt::format("particle index {} out of range [0, {})", s.end, count));
        require(s.start != s.end, at + "/end", "a spring needs two different particles");
        require(s.rest_length >= 0, at + "/rest_length", "must be >= 0" + got(s.rest_length));
      }
    }
    const int count = clothParticleCount(scene);
    for (std::size_t i = 0; i < cloth.fixed.size(); ++i)
      require(cloth.fixed[i] >= 0 && cloth.fixed[i] < count, fmt::format("/cloth/fixed/{}", i),
              fmt::format("particle index {} out of range [0, {})", cloth.fixed[i], count));
    require(cloth.spring_coef >= 0, "/cloth/spring_coef", "must be >= 0" + got(cloth.spring_coef));
    require(cloth.damper_coef >= 0, "/cloth/damper_coef", "must be >= 0" + got(cloth.damper_coef));
  }
  if (scene.spheres) {
    const SpheresSpec& spheres = *scene.spheres;
    require(!spheres.items.empty(), "/spheres/items", "needs at least one sphere");
    for (std::size_t i = 0; i < spheres.items.size(); ++i) {
      const SphereSpec& s = spheres.items[i];
      require(s.radius > 0, fmt::format("/spheres/items/{}/radius", i),
              "must be > 0" + got(s.radius));
      if (s.mass)
        require(*s.mass >= 0, fmt::format("/spheres/items/{}/mass", i),
                "mass must be >= 0" + got(*s.mass));
    }
    require(spheres.density > 0, "/spheres/density", "must be > 0" + got(spheres.density));
    require(spheres.restitution_cloth >= 0 && spheres.restitution_cloth <= 1,
            "/spheres/restitution_cloth", "must be in [0, 1]" + got(spheres.restitution_cloth));
    require(spheres.restitution_sphere >= 0 && spheres.restitution_sphere <= 1,
            "/spheres/restitution_sphere", "must be in [0, 1]" + got(spheres.restitution_sphere));
    require(spheres.correction >= 0 && spheres.correction <= 1, "/spheres/correction",
            "must be in [0, 1]" + got(spheres.correction));
  }
  if (scene.frame_loop) {
    require(scene.frame_loop->steps_per_frame >= 1, "/frame_loop/steps_per_frame",
            fmt::format("must be >= 1 (got {})", scene.frame_loop->steps_per_frame));
    require(scene.spheres.has_value(), "/frame_loop",
            "the frame loop holds sphere 0's velocity: the scene needs spheres");
  }
}

Scene sceneFromJson(const json& document) {
  ObjectReader r(document, "");
  Scene scene;
  scene.name = r.string("name");
  r.optional("description");
  if (r.has("description")) scene.description = r.string("description");
  scene.dt = r.number("dt");
  scene.gravity = r.vector3("gravity");
  scene.viscous_coef = r.number("viscous_coef");
  r.optional("cloth");
  r.optional("spheres");
  r.optional("frame_loop");
  if (r.has("cloth")) scene.cloth = readCloth(r.get("cloth"), "/cloth");
  if (r.has("spheres")) scene.spheres = readSpheres(r.get("spheres"), "/spheres");
  if (r.has("frame_loop")) scene.frame_loop = readFrameLoop(r.get("frame_loop"), "/frame_loop");
  r.finish();
  validateScene(scene);
  return scene;
}

ordered_json sceneToJson(const Scene& scene) {
  ordered_json j;
  j["name"] = scene.name;
  j["description"] = scene.description;
  j["dt"] = scene.dt;
  j["gravity"] = vector3ToJson(scene.gravity);
  j["viscous_coef"] = scene.viscous_coef;
  if (scene.cloth) {
    const ClothSpec& cloth = *scene.cloth;
    ordered_json c;
    if (cloth.grid) {
      c["grid"] = {{"particles_per_edge", cloth.grid->particles_per_edge},
                   {"half_extent", cloth.grid->half_extent},
                   {"y", cloth.grid->y},
                   {"particle_mass", cloth.grid->particle_mass}};
    } else {
      c["particles"] = ordered_json::array();
      for (const ParticleSpec& p : cloth.particles)
        c["particles"].push_back({{"position", vector3ToJson(p.position)},
                                  {"velocity", vector3ToJson(p.velocity)},
                                  {"mass", p.mass}});
      c["springs"] = ordered_json::array();
      for (const SpringSpec& s : cloth.springs)
        c["springs"].push_back(
            {{"start", s.start}, {"end", s.end}, {"rest_length", s.rest_length}});
    }
    c["fixed"] = cloth.fixed;
    c["spring_coef"] = cloth.spring_coef;
    c["damper_coef"] = cloth.damper_coef;
    j["cloth"] = std::move(c);
  }
  if (scene.spheres) {
    const SpheresSpec& spheres = *scene.spheres;
    ordered_json s;
    s["items"] = ordered_json::array();
    for (const SphereSpec& item : spheres.items) {
      ordered_json i;
      i["center"] = vector3ToJson(item.center);
      i["radius"] = item.radius;
      i["velocity"] = vector3ToJson(item.velocity);
      i["mass"] = item.mass ? ordered_json(*item.mass) : ordered_json(nullptr);
      s["items"].push_back(std::move(i));
    }
    s["density"] = spheres.density;
    s["external_force"] = spheres.external_force;
    s["sphere_sphere_collision"] = spheres.sphere_sphere_collision;
    s["restitution_cloth"] = spheres.restitution_cloth;
    s["restitution_sphere"] = spheres.restitution_sphere;
    s["correction"] = spheres.correction;
    j["spheres"] = std::move(s);
  }
  // written only when present, so scenes without it keep their files and trace headers
  if (scene.frame_loop)
    j["frame_loop"] = {{"steps_per_frame", scene.frame_loop->steps_per_frame},
                       {"sphere_velocity", vector3ToJson(scene.frame_loop->sphere_velocity)}};
  return j;
}

const Scene* findBuiltinScene(const std::string& name) {
  for (const Scene& scene : builtinScenes())
    if (scene.name == name) return &scene;
  return nullptr;
}

Scene loadScene(const std::string& name_or_path) {
  if (const Scene* builtin = findBuiltinScene(name_or_path)) return *builtin;
  if (!std::filesystem::exists(name_or_path)) {
    std::string names;
    for (const Scene& scene : builtinScenes()) names += (names.empty() ? "" : ", ") + scene.name;
    throw InputError(name_or_path + ": no such scene file or built-in scene (built-in: " + names +
                     ")");
  }
  const json document = readJsonFile(name_or_path, "scene file");
  try {
    return sceneFromJson(document);
  } catch (const SceneError& error) {
    throw InputError(name_or_path + ": " + error.what());
  }
}

}  // namespace clothref
