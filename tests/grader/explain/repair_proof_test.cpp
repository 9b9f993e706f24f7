#include "grader/grade/explain/repair_proof.h"
#include "grader/grade/cause_ids.h"

#include <gtest/gtest.h>

namespace clothref::grader {
namespace {

const Repair* find(const std::vector<Repair>& repairs, const std::string& cause) {
  for (const Repair& r : repairs)
    if (r.cause == cause) return &r;
  return nullptr;
}

// The line `n` (1-based) of `text`, without its end.
std::string lineOf(const std::string& text, int n) {
  std::size_t start = 0;
  for (int k = 1; k < n; ++k) start = text.find('\n', start) + 1;
  const std::size_t end = text.find('\n', start);
  std::string line = text.substr(start, end - start);
  if (!line.empty() && line.back() == '\r') line.pop_back();
  return line;
}

const std::string kSphere =
    "void Spheres::collide(Cloth* cloth) {\n"                                           // 1
    "  for (int i = 0; i < sphereCount; ++i) {\n"                                       // 2
    "    // auto old = _particles.position(i) - cloth->particles().position(0);\n"      // 3
    "    auto N = cloth->particles().position(0) - _particles.position(i);\r\n"         // 4
    "    auto n = (_particles.position(i) - cloth->particles().position(0)).norm();\n"  // 5
    "  }\n"                                                                             // 6
    "}\n"                                                                               // 7
    "void Spheres::collide() { auto d = _particles.position(0) - _particles.position(1); }\n";

// An `auto` Eigen expression inside the stub is evaluated into a vector on its own line; a
// commented one, a number (`.norm()`) and one in another stub are left alone; line numbers and
// line ends stay.
TEST(RepairProof, AutoExpressionsAreEvaluated) {
  const std::vector<Repair> repairs = repairsOf("sphere.cpp", kSphere, "Spheres::collide(Cloth*)");
  const Repair* r = find(repairs, cause::kDanglingAutoExpression);
  ASSERT_NE(r, nullptr);
  ASSERT_EQ(r->lines.size(), 1u);
  EXPECT_EQ(r->lines[0].line, 4);
  EXPECT_EQ(r->lines[0].text, "auto N = cloth->particles().position(0) - _particles.position(i);");
  EXPECT_EQ(lineOf(r->patched, 4),
            "    auto N = (cloth->particles().position(0) - _particles.position(i)).eval();");
  EXPECT_NE(r->patched.find(".eval();\r\n"), std::string::npos);
  EXPECT_EQ(lineOf(r->patched, 3), lineOf(kSphere, 3));
  EXPECT_EQ(lineOf(r->patched, 5), lineOf(kSphere, 5));
  EXPECT_EQ(lineOf(r->patched, 8), lineOf(kSphere, 8));
  EXPECT_EQ(r->what, "line 4 repaired (its `auto` expression stored as a vector with `.eval()`)");
}

const std::string kIntegrator =
    "void MidpointEuler::integrate(const std::vector<Particles*>& particles,\n"           // 1
    "                              std::function<void(void)> simulateOneStep) const {\n"  // 2
    "  auto backup = particles;\n"                                                        // 3
    "  float half = 1 / 2 * deltaTime;  // 1 / 2 is fine in a comment\n"                  // 4
    "  deltaTime /= 2;\n"                                                                 // 5
    "}\n"                                                                                 // 6
    "void RungeKuttaFourth::integrate(const std::vector<Particles*>& particles,\n"        // 7
    "                                 std::function<void(void)> simulateOneStep) const {\n"
    "  std::vector<Eigen::Ref<Eigen::Matrix4Xf>> x0;\n"  // 9
    "  auto v = particles[0]->velocity();\n"             // 10
    "  x = x0 + (1/6) * (k1 + k4);\n"                    // 11
    "  y = 1 / 6.0f;\n"                                  // 12
    "  z = (k2 + k3) * (1 / 3) + k1 * (1 / 2);\n"        // 13
    "}\n";

TEST(RepairProof, IntegerDivisionBackupsAndDeltaTime) {
  const std::vector<Repair> midpoint =
      repairsOf("integrator.cpp", kIntegrator, "MidpointEuler::integrate");
  const Repair* half = find(midpoint, cause::kIntegerDivisionHalf);
  ASSERT_NE(half, nullptr);
  EXPECT_EQ(lineOf(half->patched, 4),
            "  float half = 1.0f / 2 * deltaTime;  // 1 / 2 is fine in a comment");
  const Repair* alias = find(midpoint, cause::kBackupAlias);
  ASSERT_NE(alias, nullptr);
  EXPECT_EQ(lineOf(alias->patched, 3),
            "  std::vector<Particles> backup_copies_; for (auto* p_ : particles) "
            "backup_copies_.push_back(*p_); std::vector<Particles*> backup; for (auto& c_ : "
            "backup_copies_) backup.push_back(&c_);");
  const Repair* dt = find(midpoint, cause::kDeltatimeMutated);
  ASSERT_NE(dt, nullptr);
  EXPECT_EQ(dt->lines.size(), 1u);
  EXPECT_EQ(dt->lines[0].line, 5);
  // The guard is on the line of the opening brace; the line numbers stay.
  EXPECT_NE(lineOf(dt->patched, 2).find("~ClothrefRestore_() { deltaTime = v; }"),
            std::string::npos);
  EXPECT_EQ(lineOf(dt->patched, 5), lineOf(kIntegrator, 5));
  EXPECT_EQ(dt->what, "deltaTime restored to its value when integrate() returns");

  const std::vector<Repair> rk4 =
      repairsOf("integrator.cpp", kIntegrator, "RungeKuttaFourth::integrate");
  const Repair* sixth = find(rk4, cause::kIntegerDivisionRk4);
  ASSERT_NE(sixth, nullptr);
  ASSERT_EQ(sixth->lines.size(), 2u);  // 1 / 6.0f is float division
  EXPECT_EQ(lineOf(sixth->patched, 11), "  x = x0 + (1.0f / 6) * (k1 + k4);");
  // 1 / 3 is RK4's weight too; a stage's 1 / 2 is the half step's own mistake
  EXPECT_EQ(lineOf(sixth->patched, 13), "  z = (k2 + k3) * (1.0f / 3) + k1 * (1 / 2);");
  const Repair* stage_half = find(rk4, cause::kIntegerDivisionHalf);
  ASSERT_NE(stage_half, nullptr);
  ASSERT_EQ(stage_half->lines.size(), 1u);
  EXPECT_EQ(lineOf(stage_half->patched, 13), "  z = (k2 + k3) * (1 / 3) + k1 * (1.0f / 2);");
  const Repair* views = find(rk4, cause::kBackupAlias);
  ASSERT_NE(views, nullptr);
  EXPECT_EQ(lineOf(views->patched, 9), "  std::vector<Eigen::Matrix4Xf> x0;");
  EXPECT_EQ(lineOf(views->patched, 10), "  auto v = particles[0]->velocity().eval();");
  EXPECT_EQ(find(rk4, cause::kDeltatimeMutated), nullptr);
}

TEST(RepairProof, DiscardedNormalizedInTheSpringForce) {
  const std::string cloth =
      "void Cloth::computeSpringForce() {\n"
      "  Eigen::Vector4f dir = a - b;\n"
      "  dir.normalized();  // 單位向量\n"
      "  dir = dir.normalized();\n"
      "}\n";
  const std::vector<Repair> repairs = repairsOf("cloth.cpp", cloth, "Cloth::computeSpringForce");
  const Repair* r = find(repairs, cause::kDirectionNotNormalised);
  ASSERT_NE(r, nullptr);
  ASSERT_EQ(r->lines.size(), 1u);
  EXPECT_EQ(lineOf(r->patched, 3), "  dir.normalize();  // 單位向量");
  EXPECT_EQ(lineOf(r->patched, 4), "  dir = dir.normalized();");
}

// A reference to the temporary std::max returns (undefined behaviour that need not crash).
TEST(RepairProof, AReferenceToATemporaryBecomesACopy) {
  const std::string cloth =
      "void Cloth::computeSpringForce() {\n"
      "  const float& length = std::max(d.norm(), 1e-6f);\n"
      "  const float& k = springCoef;\n"
      "}\n";
  const std::vector<Repair> repairs = repairsOf("cloth.cpp", cloth, "Cloth::computeSpringForce");
  const Repair* r = find(repairs, cause::kUndefinedBehaviour);
  ASSERT_NE(r, nullptr);
  ASSERT_EQ(r->lines.size(), 1u);
  EXPECT_EQ(lineOf(r->patched, 2), "  const float length = std::max(d.norm(), 1e-6f);");
  EXPECT_EQ(lineOf(r->patched, 3), "  const float& k = springCoef;");
}

// A helper the stub calls that returns a reference to its own local (issue 38, blind2's mao): the
// reference is dropped from its declaration and definition, and the stub's own lines stay. A
// helper that returns a static local, a parameter or a member by reference, or one the stub does
// not call, is left alone.
TEST(RepairProof, AHelperReturningItsLocalByReferenceReturnsByValue) {
  const std::string sphere =
      "const Eigen::Vector4f& normal(const Eigen::Vector4f& a, const Eigen::Vector4f& b);\n"   // 1
      "// returns the unit vector from b to a\n"                                               // 2
      "const Eigen::Vector4f& normal(const Eigen::Vector4f& a, const Eigen::Vector4f& b) {\n"  // 3
      "  Eigen::Vector4f n = (a - b).normalized();\n"                                          // 4
      "  return n;\n"                                                                          // 5
      "}\n"                                                                                    // 6
      "const Eigen::Vector4f& kept(const Eigen::Vector4f& a) { static Eigen::Vector4f s; s = a; "
      "return s; }\n"                                                          // 7
      "const Eigen::Vector4f& same(const Eigen::Vector4f& a) { return a; }\n"  // 8
      "void Spheres::collide(Cloth* cloth) {\n"                                // 9
      "  const Eigen::Vector4f& n = normal(_particles.position(0), "
      "cloth->particles().position(0));\n"
      "  Eigen::Vector4f k = kept(n) + same(n);\n"  // 11
      "}\n";                                        // 12
  const std::vector<Repair> repairs = repairsOf("sphere.cpp", sphere, "Spheres::collide(Cloth*)");
  ASSERT_EQ(repairs.size(), 1u);
  const Repair& r = repairs[0];
  EXPECT_EQ(r.cause, cause::kUndefinedBehaviour);
  ASSERT_EQ(r.lines.size(), 2u);
  EXPECT_EQ(r.lines[0].line, 1);
  EXPECT_EQ(r.lines[1].line, 3);
  EXPECT_EQ(lineOf(r.patched, 1),
            "const Eigen::Vector4f normal(const Eigen::Vector4f& a, const Eigen::Vector4f& b);");
  EXPECT_EQ(lineOf(r.patched, 3),
            "const Eigen::Vector4f normal(const Eigen::Vector4f& a, const Eigen::Vector4f& b) {");
  for (int n : {2, 4, 5, 6, 7, 8, 9, 10, 11, 12})
    EXPECT_EQ(lineOf(r.patched, n), lineOf(sphere, n));
  EXPECT_EQ(r.what,
            "lines 1 and 3 repaired (`normal` returns its local `n` by value, not a reference to "
            "it, which is gone when it returns)");
  // another stub, which does not call it: nothing
  EXPECT_TRUE(repairsOf("sphere.cpp", sphere + "void Spheres::collide() {}\n", "Spheres::collide()")
                  .empty());
}

// The local returned in one branch of a conditional (blind4's chen: `return len > 0.0f ? u : v;`,
// which g++ -O2 turns into `return v;`, so the numbers are those of an unnormalised direction):
// the branch that is its own local is found, the parameter in the other is not.
TEST(RepairProof, ALocalReturnedInOneBranchOfAConditionalIsFound) {
  const std::string cloth =
      "const Eigen::Vector4f& unitOf(const Eigen::Vector4f& v, float len) {\n"  // 1
      "  Eigen::Vector4f u = v / len;\n"                                        // 2
      "  return len > 0.0f ? u : v;\n"                                          // 3
      "}\n"                                                                     // 4
      "const Eigen::Vector4f& either(const Eigen::Vector4f& v, const Eigen::Vector4f& w) {\n"
      "  return v.x() > 0 ? v : w;\n"  // 6
      "}\n"                            // 7
      "void Cloth::computeSpringForce() {\n"
      "  const Eigen::Vector4f& dir = unitOf(_particles.position(0), 1.0f);\n"
      "  const Eigen::Vector4f& other = either(dir, dir);\n"
      "}\n";
  const std::vector<Repair> repairs = repairsOf("cloth.cpp", cloth, "Cloth::computeSpringForce");
  ASSERT_EQ(repairs.size(), 1u);
  EXPECT_EQ(lineOf(repairs[0].patched, 1),
            "const Eigen::Vector4f unitOf(const Eigen::Vector4f& v, float len) {");
  EXPECT_EQ(lineOf(repairs[0].patched, 5), lineOf(cloth, 5));
  EXPECT_EQ(repairs[0].what,
            "line 1 repaired (`unitOf` returns its local `u` by value, not a reference to it, "
            "which is gone when it returns)");
}

// A local declared without a value and first used in a compound assignment starts at zero
// (issue 38, blind2's kuan); one first assigned, or first read as a whole, is left alone.
TEST(RepairProof, AnUninitialisedSumStartsAtZero) {
  const std::string cloth =
      "void Cloth::computeSpringForce() {\n"              // 1
      "  for (const auto& spring : _springs) {\n"         // 2
      "    Eigen::Vector4f force;  // spring + damper\n"  // 3
      "    float total;\n"                                // 4
      "    Eigen::Vector4f set;\n"                        // 5
      "    int i;\n"                                      // 6
      "    set = _particles.position(0);\n"               // 7
      "    for (i = 0; i < 2; ++i) total += 1;\n"         // 8
      "    force += springCoef * set;\n"                  // 9
      "  }\n"                                             // 10
      "}\n";                                              // 11
  const std::vector<Repair> repairs = repairsOf("cloth.cpp", cloth, "Cloth::computeSpringForce");
  const Repair* r = find(repairs, cause::kUndefinedBehaviour);
  ASSERT_NE(r, nullptr);
  ASSERT_EQ(r->lines.size(), 2u);
  EXPECT_EQ(r->lines[0].line, 3);
  EXPECT_EQ(r->lines[1].line, 4);
  EXPECT_EQ(lineOf(r->patched, 3),
            "    Eigen::Vector4f force = Eigen::Vector4f::Zero();  // spring + damper");
  EXPECT_EQ(lineOf(r->patched, 4), "    float total = 0;");
  for (int n : {1, 2, 5, 6, 7, 8, 9, 10, 11}) EXPECT_EQ(lineOf(r->patched, n), lineOf(cloth, n));
  EXPECT_EQ(r->what,
            "lines 3 and 4 repaired (`force` and `total` starting at zero, not at whatever the "
            "stack held)");
}

// A passing stub with a sum it never starts (blind3 2024/kung: `float magnitude;` then
// `magnitude += ...`): the probe starts it at 1 instead; the checks that then fail fail, with
// undefined-behaviour proven on the line, and the others keep their pass. A start that changes
// nothing, or a build that fails, says nothing.
TEST(RepairProof, APassingSumThatRestsOnAnUnsetStartFails) {
  const std::string cloth =
      "void Cloth::computeSpringForce() {\n"       // 1
      "  for (const auto& spring : _springs) {\n"  // 2
      "    float magnitude;\n"                     // 3
      "    Eigen::Vector4f dir;\n"                 // 4
      "    magnitude += springCoef * 2;\n"         // 5
      "    dir += _particles.position(0);\n"       // 6
      "  }\n"                                      // 7
      "}\n";                                       // 8
  const std::optional<Repair> start =
      unsetStartProbe("cloth.cpp", cloth, "Cloth::computeSpringForce");
  ASSERT_TRUE(start.has_value());
  EXPECT_EQ(start->cause, cause::kUndefinedBehaviour);
  EXPECT_EQ(lineOf(start->patched, 3), "    float magnitude = 1;");
  EXPECT_EQ(lineOf(start->patched, 4), "    Eigen::Vector4f dir = Eigen::Vector4f::Ones();");
  EXPECT_EQ(start->what,
            "lines 3 and 4 starting `magnitude` and `dir` at 1 instead of whatever the stack held");
  EXPECT_FALSE(unsetStartProbe("cloth.cpp",
                               "void Cloth::computeSpringForce() {\n  float m = 0;\n  m += 1;\n}\n",
                               "Cloth::computeSpringForce"));

  std::vector<TestResult> tests;
  for (int k = 0; k < 4; ++k) {
    tests.push_back(makeTest("Cloth::computeSpringForce", "check " + std::to_string(k + 1), 1));
    tests.back().fraction = 1;
  }
  std::vector<TestResult> started = tests;
  started[0].fraction = started[2].fraction = 0;
  started[0].output = "expected 1, yours 2";
  std::vector<TestResult> same = tests;
  EXPECT_FALSE(applyUnsetStart(*start, true, tests, same));  // nothing changed: nothing said
  EXPECT_TRUE(same[0].passed() && same[0].causes.empty());
  EXPECT_FALSE(applyUnsetStart(*start, false, started, same));  // no build: nothing said
  ASSERT_TRUE(applyUnsetStart(*start, true, started, tests));
  for (int k : {1, 3}) EXPECT_TRUE(tests[std::size_t(k)].passed()) << k;
  for (int k : {0, 2}) {
    const TestResult& t = tests[std::size_t(k)];
    EXPECT_FALSE(t.passed()) << k;
    ASSERT_EQ(t.causes.size(), 1u);
    EXPECT_TRUE(t.causes[0].proven());
    EXPECT_EQ(t.causes[0].id, cause::kUndefinedBehaviour);
    EXPECT_EQ(t.causes[0].proof,
              "Proven: with lines 3 and 4 starting `magnitude` and `dir` at 1 instead of whatever "
              "the stack held, 2 of 4 checks fail: your numbers rest on a value your code never "
              "sets, and your build gave the course's by chance.");
    EXPECT_EQ(t.causes[0].quotes.size(), 2u);
  }
  EXPECT_NE(tests[0].output.find("expected 1, yours 2"), std::string::npos);
}

// The stub's tests before and after a repair: 4 checks, the first three failed before.
std::vector<TestResult> stubTests(const std::vector<bool>& passed,
                                  const std::vector<std::string>& causes) {
  std::vector<TestResult> tests;
  for (std::size_t k = 0; k < passed.size(); ++k) {
    TestResult t = makeTest("Spheres::collide(Cloth*)", "check " + std::to_string(k + 1), 1);
    t.fraction = passed[k] ? 1 : 0;
    if (!passed[k])
      for (const std::string& id : causes) t.addCause(id, true);
    tests.push_back(t);
  }
  return tests;
}

Repair autoRepair() {
  Repair r;
  r.file = "sphere.cpp";
  r.stub = "Spheres::collide(Cloth*)";
  r.cause = cause::kDanglingAutoExpression;
  r.lines = {{"sphere.cpp", 129, "auto N = a - b;"}};
  r.what = "line 129 repaired (its `auto` expression stored as a vector with `.eval()`)";
  return r;
}

// The example: the repair mends two checks, a third still fails, explained by a proven
// mistake of the repaired build; the plausible cause the UB produced is no longer likely.
TEST(RepairProof, AMendingRepairProvesItsCause) {
  std::vector<TestResult> tests =
      stubTests({false, false, false, true}, {cause::kNoPositionCorrection});
  std::vector<TestResult> repaired = stubTests({true, true, false, true}, {});
  repaired[2].addCause(cause::kWrongMassSplit).proof = "Proven: a split gives your numbers.";
  ASSERT_TRUE(applyRepair(autoRepair(), true, "", repaired, tests));
  const std::string line =
      "With line 129 repaired (its `auto` expression stored as a vector with `.eval()`): 3 of 4 "
      "checks pass; the other 1 is explained by `wrong-mass-split` (proven).";
  for (int k : {0, 1}) {
    ASSERT_TRUE(tests[k].names(cause::kDanglingAutoExpression));
    EXPECT_EQ(tests[k].causes.front().id, cause::kNoPositionCorrection);
    EXPECT_FALSE(tests[k].causes.front().likely);
    EXPECT_EQ(tests[k].causes.front().proof,
              "Not the mistake: with line 129 repaired (its `auto` expression stored as a vector "
              "with `.eval()`), this check passes.");
    for (const Cause& c : tests[k].causes)
      if (c.id == cause::kDanglingAutoExpression) {
        EXPECT_TRUE(c.proven());
        EXPECT_EQ(c.proof, line);
        EXPECT_EQ(c.quotes.size(), 1u);
      }
  }
  // The check still failing takes the repaired build's causes.
  ASSERT_TRUE(tests[2].names(cause::kWrongMassSplit));
  EXPECT_FALSE(tests[2].names(cause::kNoPositionCorrection));
  EXPECT_TRUE(tests[2].causes.front().proven());
  EXPECT_EQ(tests[2].causes.front().id, cause::kWrongMassSplit);
}

// Two mistakes in one stub (the first blind set's peng: `1 / 3` and a fourth stage from a half
// step): the repair mends no check alone, but every check the repaired build fails is explained
// by a proven cause that did not explain the stub as handed in, so the repair changed the numbers
// into those of the other mistake alone, and both are proven. When that cause explained the stub
// as handed in already, the repair shows nothing.
TEST(RepairProof, ARepairProvesItsCauseWithTheRepairedBuildsProvenMistakes) {
  std::vector<TestResult> tests =
      stubTests({false, false, true, true}, {cause::kNoPositionCorrection});
  std::vector<TestResult> repaired = stubTests({false, false, true, true}, {});
  for (int k : {0, 1})
    repaired[k].addCause(cause::kWrongMassSplit).proof = "Proven: a split gives your numbers.";
  ASSERT_TRUE(applyRepair(autoRepair(), true, "", repaired, tests));
  for (int k : {0, 1}) {
    bool repair_proven = false, other_proven = false;
    for (const Cause& c : tests[k].causes) {
      if (c.id == cause::kDanglingAutoExpression) {
        repair_proven = c.proven();
        EXPECT_EQ(c.proof,
                  "With line 129 repaired (its `auto` expression stored as a vector with "
                  "`.eval()`): the 2 failed checks are then explained by `wrong-mass-split` "
                  "(proven), which does not explain your numbers as handed in: this mistake and "
                  "that one together give them.");
      }
      other_proven = other_proven || (c.id == cause::kWrongMassSplit && c.proven());
      EXPECT_FALSE(c.id == cause::kNoPositionCorrection && c.likely);
    }
    EXPECT_TRUE(repair_proven) << k;
    EXPECT_TRUE(other_proven) << k;
  }

  tests = stubTests({false, false, true, true}, {});
  for (int k : {0, 1})
    tests[k].addCause(cause::kWrongMassSplit).proof = "Proven: a split gives your numbers.";
  EXPECT_FALSE(applyRepair(autoRepair(), true, "", repaired, tests));
  for (int k : {0, 1})
    EXPECT_FALSE(tests[k].names(cause::kDanglingAutoExpression) &&
                 tests[k].causes.front().id == cause::kDanglingAutoExpression);
}

// A repair that does not build, or changes nothing, disproves the cause.
TEST(RepairProof, ARepairThatDoesNotBuildOrChangesNothingDisproves) {
  std::vector<TestResult> tests =
      stubTests({false, false, true, true}, {cause::kDanglingAutoExpression});
  EXPECT_FALSE(applyRepair(autoRepair(), false, "sphere.cpp:129: error: no match", {}, tests));
  for (int k : {0, 1}) {
    EXPECT_FALSE(tests[k].causes.front().likely);
    EXPECT_EQ(tests[k].causes.front().proof,
              "Not proven: with line 129 repaired (its `auto` expression stored as a vector with "
              "`.eval()`), sphere.cpp does not build (sphere.cpp:129: error: no match), so the "
              "repair shows nothing.");
  }
  tests = stubTests({false, false, true, true}, {cause::kDanglingAutoExpression});
  EXPECT_FALSE(
      applyRepair(autoRepair(), true, "", stubTests({false, false, true, true}, {}), tests));
  EXPECT_FALSE(tests[0].causes.front().likely);
  EXPECT_EQ(tests[0].causes.front().proof,
            "Not proven: with line 129 repaired (its `auto` expression stored as a vector with "
            "`.eval()`), the same checks fail: the repair does not mend your numbers.");
}

}  // namespace
}  // namespace clothref::grader
