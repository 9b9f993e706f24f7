#include "clothref/scene/scene.h"

#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>

#include "test_util.h"

namespace clothref {
namespace {

using json = nlohmann::json;

TEST(Scene, EveryBuiltinRoundTripsThroughJson) {
  for (const Scene& scene : builtinScenes()) {
    const std::string text = sceneToJson(scene).dump(2);
    const Scene loaded = sceneFromJson(json::parse(text));
    EXPECT_EQ(loaded, scene) << scene.name;
    EXPECT_EQ(sceneToJson(loaded).dump(2), text) << scene.name;
  }
}

TEST(Scene, DefaultIsCourse2022WithTheCourseValues) {
  const Scene& scene = builtinScenes().front();
  EXPECT_EQ(scene.name, "course2022");
  EXPECT_EQ(scene.dt, 1e-4);
  EXPECT_EQ(scene.viscous_coef, 3.4e-4);
  EXPECT_EQ(scene.cloth->grid->particles_per_edge, 25);
  EXPECT_EQ(scene.cloth->spring_coef, 25000);
  EXPECT_EQ(scene.cloth->damper_coef, 750);
  EXPECT_EQ(scene.spheres->items.size(), 4u);
  // the double parameters convert to the course's float literals exactly
  EXPECT_EQ(float(scene.dt), 1e-4f);
  EXPECT_EQ(float(scene.viscous_coef), 3.4e-4f);
  EXPECT_EQ(float(scene.gravity[1]), -9.8f);
  EXPECT_EQ(float(scene.spheres->restitution_sphere), 0.8f);
  EXPECT_EQ(float(scene.spheres->correction), 0.15f);
  const Scene& s2024 = *findBuiltinScene("course2024");
  EXPECT_EQ(s2024.cloth->spring_coef, 20000);
  EXPECT_EQ(s2024.cloth->grid->y, 1);
  EXPECT_FALSE(s2024.spheres->external_force);
  EXPECT_FALSE(s2024.spheres->sphere_sphere_collision);
  // the 2024 main loop at 60 Hz: simulationPerFrame 10 x speedMultiplier 240 / 60
  ASSERT_TRUE(s2024.frame_loop.has_value());
  EXPECT_EQ(s2024.frame_loop->steps_per_frame, 40);
  EXPECT_EQ(s2024.frame_loop->sphere_velocity, (Vector3{0, 0, 0}));
  EXPECT_FALSE(scene.frame_loop.has_value()) << "the 2022 loop has no per-frame work";
  EXPECT_FALSE(sceneToJson(scene).contains("frame_loop"));
}

TEST(Scene, FrameLoopCanBeTurnedOffAndChanged) {
  json document = json::parse(sceneToJson(*findBuiltinScene("course2024")).dump());
  document["frame_loop"]["steps_per_frame"] = 16;  // a 150 Hz monitor
  document["frame_loop"]["sphere_velocity"] = json::array({5, 0, 0});
  const Scene held = sceneFromJson(document);
  EXPECT_EQ(held.frame_loop->steps_per_frame, 16);
  EXPECT_EQ(held.frame_loop->sphere_velocity, (Vector3{5, 0, 0}));
  document["frame_loop"] = nullptr;
  EXPECT_FALSE(sceneFromJson(document).frame_loop.has_value());
  document.erase("frame_loop");
  EXPECT_FALSE(sceneFromJson(document).frame_loop.has_value());
}

// Each bad scene: a mutation of a valid document and the one-line message it must produce.
struct BadCase {
  const char* scene;
  const char* pointer;  // JSON pointer to change ("" to leave the document alone)
  const char* value;    // replacement (JSON or "Infinity"), or null to delete the key
  const char* message;  // expected what()
};

const BadCase kBadCases[] = {
    {"course2022", "/cloth/grid/colour", "1", "/cloth/grid/colour: unknown key"},
    {"course2022", "/dt", "\"fast\"", "/dt: expected a number, got string"},
    {"course2022", "/cloth/grid/particles_per_edge", "2.5",
     "/cloth/grid/particles_per_edge: expected an integer, got number"},
    {"course2022", "/viscous_coef", "Infinity", "/viscous_coef: must be finite"},
    {"course2022", "/dt", "0", "/dt: must be > 0 (got 0)"},
    {"course2022", "/dt", "-1e-4", "/dt: must be > 0 (got -0.0001)"},
    {"course2022", "/cloth/grid/particles_per_edge", "1",
     "/cloth/grid/particles_per_edge: cloth edge must have >= 2 particles (got 1)"},
    {"course2022", "/cloth/grid/particle_mass", "-1",
     "/cloth/grid/particle_mass: mass must be >= 0 (got -1)"},
    {"spring", "/cloth/particles/1/mass", "-2",
     "/cloth/particles/1/mass: mass must be >= 0 (got -2)"},
    {"two-spheres", "/spheres/items/1/mass", "-5",
     "/spheres/items/1/mass: mass must be >= 0 (got -5)"},
    {"course2022", "/spheres/items/2/radius", "0", "/spheres/items/2/radius: must be > 0 (got 0)"},
    {"course2022", "/spheres/restitution_sphere", "1.5",
     "/spheres/restitution_sphere: must be in [0, 1] (got 1.5)"},
    {"course2022", "/spheres/restitution_cloth", "-0.1",
     "/spheres/restitution_cloth: must be in [0, 1] (got -0.1)"},
    {"course2022", "/cloth/fixed/3", "625",
     "/cloth/fixed/3: particle index 625 out of range [0, 625)"},
    {"spring", "/cloth/springs/0/end", "2",
     "/cloth/springs/0/end: particle index 2 out of range [0, 2)"},
    {"course2022", "/gravity", "[0, -9.8]", "/gravity: expected an array of 3 numbers [x, y, z]"},
    {"course2022", "/spheres/external_force", "1",
     "/spheres/external_force: expected true or false, got integer"},
    {"course2022", "/cloth/spring_coef", nullptr, "/cloth/spring_coef: missing"},
    {"course2024", "/frame_loop/steps_per_frame", "0",
     "/frame_loop/steps_per_frame: must be >= 1 (got 0)"},
    {"course2024", "/frame_loop/sphere_velocity", "[1, 2]",
     "/frame_loop/sphere_velocity: expected an array of 3 numbers [x, y, z]"},
    {"course2024", "/frame_loop/refresh", "60", "/frame_loop/refresh: unknown key"},
};

json mutated(const BadCase& c) {
  json document = json::parse(sceneToJson(*findBuiltinScene(c.scene)).dump());
  const json::json_pointer pointer(c.pointer);
  if (c.value && std::string(c.value) == "Infinity")  // JSON text cannot hold it; a caller can
    document[pointer] = std::numeric_limits<double>::infinity();
  else if (c.value)
    document[pointer] = json::parse(c.value);
  else
    document[pointer.parent_pointer()].erase(pointer.back());
  return document;
}

TEST(Scene, EachBadValueIsNamedByItsJsonPointer) {
  for (const BadCase& c : kBadCases) {
    try {
      sceneFromJson(mutated(c));
      ADD_FAILURE() << "accepted: " << c.pointer << " = " << (c.value ? c.value : "(deleted)");
    } catch (const SceneError& error) {
      EXPECT_EQ(std::string(error.what()), c.message);
    }
  }
}

class SceneFiles : public ::testing::Test {
 protected:
  std::string write(const std::string& name, const std::string& text) {
    const std::string path = dir_.file(name);
    std::ofstream(path) << text;
    return path;
  }
  test::TempDir dir_;
};

TEST_F(SceneFiles, BadSceneFileIsOneLineExit2AndNoOutput) {
  for (const BadCase& c : kBadCases) {
    if (c.value && std::string(c.value) == "Infinity") continue;  // see OverflowingNumber
    const std::string scene = write("bad.json", mutated(c).dump(2));
    const std::string out = dir_.file("out.jsonl");
    const auto result = test::runCli("trace --scene " + scene + " --steps 3 -o " + out);
    EXPECT_EQ(result.exit_code, 2) << c.pointer;
    EXPECT_EQ(result.output, "clothref: " + scene + ": " + c.message + "\n");
    EXPECT_FALSE(std::filesystem::exists(out)) << c.pointer;
    EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir_.path()), {}), 1)
        << "left a file behind";
  }
}

TEST_F(SceneFiles, MissingFileAndBrokenJson) {
  auto result = test::runCli("trace --scene " + dir_.file("nope.json"));
  EXPECT_EQ(result.exit_code, 2);
  EXPECT_NE(result.output.find("nope.json: no such scene file or built-in scene"),
            std::string::npos)
      << result.output;
  const std::string broken = write("broken.json", "{\n  \"name\": \"x\",\n  \"dt\": NaN\n}\n");
  result = test::runCli("trace --scene " + broken);
  EXPECT_EQ(result.exit_code, 2);
  EXPECT_NE(result.output.find("broken.json: /dt: not valid JSON (line 3, column 9): syntax error"),
            std::string::npos)
      << result.output;
}

TEST_F(SceneFiles, OverflowingNumberIsRejected) {
  std::string text = sceneToJson(*findBuiltinScene("spring")).dump(2);
  text.replace(text.find("\"viscous_coef\": 0.0"), 20, "\"viscous_coef\": 1e999");
  const std::string scene = write("overflow.json", text);
  const auto result = test::runCli("trace --scene " + scene);
  EXPECT_EQ(result.exit_code, 2);
  // the JSON pointer and the line of the bad number, although the parser itself gives neither
  const auto line = 1 + std::count(text.begin(), text.begin() + text.find("1e999"), '\n');
  EXPECT_EQ(result.output.rfind("clothref: " + scene + ": /viscous_coef: not valid JSON (line " +
                                    std::to_string(line) + ", column ",
                                0),
            0u)
      << result.output;
  EXPECT_NE(result.output.find("): number overflow parsing '1e999'\n"), std::string::npos);
}

TEST_F(SceneFiles, ASavedSceneLoadsByPathAndRunsLikeTheBuiltin) {
  const std::string path = write("spring.json", sceneToJson(*findBuiltinScene("spring")).dump(2));
  EXPECT_EQ(loadScene(path), *findBuiltinScene("spring"));
  const auto by_name = test::runCli("trace --scene spring --steps 50 --stride 10");
  const auto by_path = test::runCli("trace --scene " + path + " --steps 50 --stride 10");
  EXPECT_EQ(by_name.exit_code, 0);
  // identical apart from the stderr summary's wall time
  auto body = [](const std::string& s) { return s.substr(0, s.find("clothref trace:")); };
  EXPECT_EQ(body(by_name.output), body(by_path.output));
}

}  // namespace
}  // namespace clothref
