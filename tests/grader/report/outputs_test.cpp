// The writers: Gradescope's results.json fields, JUnit XML that stays well-formed, every output
// valid UTF-8 whatever bytes a submission put in the report; through the CLI, a grade whose
// outputs cannot all be written writes none and claims nothing.
#include "grader/grade/report/outputs.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <tuple>

#include "grader/grade/batch.h"
#include "grader/grade/cause_ids.h"
#include "grader/grade/report/html_report.h"
#include "grader/grade/text.h"
#include "pages/html.h"
#include "test_util.h"

namespace clothref::grader {
namespace {

// The pages' own escaping: how a stub or check name reads in report.html.
std::string pagesEscape(const std::string& text) { return pages::escapeHtml(text); }

std::size_t countOf(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

GradeReport sampleReport() {
  GradeReport report;
  report.submission = "sub";
  report.edition = 2022;
  TestResult passed = makeTest("RungeKuttaFourth::integrate", "convergence order", 1);
  passed.fraction = 1;
  passed.max_score = passed.score = 3;
  TestResult failed = makeTest("Spheres::collide(Cloth*)", "approaching pair", 1);
  failed.max_score = 2;
  failed.output = "expected <1> & got \"2\"\x01";
  failed.causes = {
      Cause{cause::kNoApproachCheck, true, {}, {}, "The impulse is applied.", {}, {}, {}}};
  report.tests = {passed, failed};
  report.score = 3;
  report.max_score = 5;
  return report;
}

TEST(ResultsJson, GradescopeFields) {
  const auto json = resultsJson(sampleReport());
  EXPECT_EQ(json["score"], 3.0);
  ASSERT_EQ(json["tests"].size(), 2u);
  const auto& test = json["tests"][1];
  EXPECT_EQ(test["name"], "Spheres::collide(Cloth*): approaching pair");
  EXPECT_EQ(test["status"], "failed");
  EXPECT_EQ(test["max_score"], 2.0);
  EXPECT_EQ(test["output_format"], "md");
  EXPECT_EQ(test["visibility"], "visible");
  EXPECT_EQ(test["tags"],
            nlohmann::ordered_json({"Spheres::collide(Cloth*)", cause::kNoApproachCheck}));
  EXPECT_EQ(json["tests"][0]["status"], "passed");
}

// The rubric's visibility reaches each test of results.json; the top-level summary does not name
// a failed test (one line per stub).
TEST(ResultsJson, EachTestHasTheVisibilityTheRubricGave) {
  GradeReport report = sampleReport();
  report.tests[1].visibility = "after_due_date";
  const auto json = resultsJson(report);
  EXPECT_EQ(json["tests"][0]["visibility"], "visible");
  EXPECT_EQ(json["tests"][1]["visibility"], "after_due_date");
  const auto html = withHtmlSummary(json, report);
  EXPECT_EQ(html["output"].get<std::string>().find("approaching pair"), std::string::npos);
  EXPECT_EQ(html["output"].get<std::string>().find("approaching pair"), std::string::npos);
}

TEST(JunitXml, EscapesFeedback) {
  const std::string xml = junitXml(sampleReport());
  EXPECT_NE(xml.find("failures=\"1\""), std::string::npos);
  EXPECT_NE(xml.find("expected &lt;1&gt; &amp; got &quot;2&quot;\\x01"), std::string::npos) << xml;
  EXPECT_EQ(xml.find('\x01'), std::string::npos);
  EXPECT_NE(xml.find("classname=\"RungeKuttaFourth::integrate\" name=\"convergence order\""),
            std::string::npos);
}

// A likely cause shows the catalogue's text, why and example (a code block) on the first failed
// test of its stub and visibility that names it, and afterwards its id and the test that explained
// it, no text again; a guess shows its text only. results.json and JUnit show the same blocks
// (testTexts); report.md says each cause once for its stub.
TEST(CauseMarkdown, ALikelyCauseExplainsItselfOnceAGuessStaysShort) {
  GradeReport report = sampleReport();
  const Cause likely{cause::kBackupAlias,
                     true,
                     {},
                     {},
                     "Your backup is a view.",
                     "The backup follows the live state.",
                     "auto b = particles;  // mistake\nstd::vector<Particles> b;  // fix",
                     {}};
  Cause guess = likely;
  guess.id = cause::kUnknown;
  guess.likely = false;
  TestResult first = makeTest("ImplicitEuler::integrate", "one step", 1);
  first.causes = {likely, guess};
  TestResult again = makeTest("ImplicitEuler::integrate", "two steps", 1);
  again.causes = {likely};
  TestResult hidden = again;
  hidden.check = "hidden step";
  hidden.visibility = "hidden";
  report.tests = {first, again, hidden};
  const std::vector<TestText> texts = testTexts(cleaned(report));
  ASSERT_EQ(texts.size(), 3u);
  ASSERT_EQ(texts[0].likely.size(), 1u);
  ASSERT_EQ(texts[0].guesses.size(), 1u);
  EXPECT_EQ(texts[0].likely[0],
            "**Likely cause** (`backup-alias`): Your backup is a view.\n\n"
            "**Why**: The backup follows the live state.\n\n"
            "The mistake and its fix, in short:\n\n"
            "```\nauto b = particles;  // mistake\nstd::vector<Particles> b;  // fix\n```\n");
  EXPECT_EQ(texts[0].guesses[0],
            "**Possible cause (a guess)** (`unknown`): Your backup is a view.\n");
  EXPECT_EQ(texts[1].likely[0],
            "**Likely cause** (`backup-alias`): explained under \u201cImplicitEuler::integrate: "
            "one step\u201d above.\n");
  EXPECT_EQ(texts[2].likely[0], texts[0].likely[0]);  // never refers to a test it cannot see
  // the same blocks in results.json and JUnit; report.md: the cause once, for its stub
  const std::string md = markdownReport(report);
  const auto json = resultsJson(report);
  const std::string xml = junitXml(report);
  for (std::size_t k = 0; k < texts.size(); ++k)
    EXPECT_EQ(json["tests"][k]["output"], texts[k].markdown()) << k;
  EXPECT_EQ(countOf(md, texts[0].likely[0]), 1u) << md;
  EXPECT_EQ(countOf(md, "The backup follows the live state."), 1u) << md;
  EXPECT_NE(xml.find("std::vector&lt;Particles&gt; b;  // fix"), std::string::npos) << xml;
}

// A stub that lost points, as a student reads it: its points and the rule, what is wrong, the
// A symptom (`unstable`, `non-finite`, `wrong-order`) beside a cause proven on the same check is
// left out of every output: the proven cause's model gave that check's numbers (issue 38: a blind
// midpoint told `unstable` as likely beside its proven `corrector-start-velocity`). Beside an
// unproven cause, or alone, it stays.
TEST(AllWriters, ASymptomBesideAProvenCauseIsLeftOut) {
  GradeReport report = sampleReport();
  Cause proven{cause::kCorrectorStartVelocity, true, {}, {}, "The corrector uses v0.", {}, {}, {}};
  proven.proof = "Proven: the course's midpoint whose corrector uses v0 gives your numbers.";
  report.tests[1].causes = {proven,
                            Cause{cause::kUnstable, true, {}, {}, "It blows up.", {}, {}, {}},
                            Cause{cause::kNonFinite, true, {}, {}, "NaN.", {}, {}, {}}};
  TestResult unproven = makeTest("ImplicitEuler::integrate", "one step on a random state", 1);
  unproven.max_score = 1;
  unproven.causes = {Cause{cause::kHeunMethod, true, {}, {}, "Heun.", {}, {}, {}},
                     Cause{cause::kUnstable, true, {}, {}, "It blows up.", {}, {}, {}}};
  report.tests.push_back(unproven);
  const GradeReport clean = cleaned(report);
  ASSERT_EQ(clean.tests.size(), 3u);
  EXPECT_EQ(clean.tests[1].causeIds(), std::vector<std::string>{cause::kCorrectorStartVelocity});
  EXPECT_EQ(clean.tests[2].causeIds(),
            (std::vector<std::string>{cause::kHeunMethod, cause::kUnstable}));
  const nlohmann::ordered_json json = resultsJson(report);
  ASSERT_EQ(json["tests"].size(), 3u);
  EXPECT_EQ(json["tests"][1]["extra_data"]["causes"].size(), 1u) << json.dump();
  EXPECT_EQ(json["tests"][2]["extra_data"]["causes"].size(), 2u) << json.dump();
  EXPECT_EQ(json.dump().find(cause::kNonFinite), std::string::npos) << json.dump();
  EXPECT_NE(markdownReport(report).find("Proven: the course's midpoint"), std::string::npos);
}

// failed checks as a table (check, expected, yours, by how much), the first failed check in full;
// a stub whose checks all passed is named once.
// How a probe's run ended (`crashed`, `timed-out`, `undefined-behaviour`: read, so likely) beside
// another likely cause of the same check is left out of every output: the named cause is what
// made it end so. Alone, it stays.
TEST(AllWriters, HowARunEndedBesideTheCauseThatMadeItIsLeftOut) {
  GradeReport report = sampleReport();
  report.tests[1].causes = {
      Cause{
          cause::kDanglingAutoExpression, true, {}, {}, "An auto holds an expression.", {}, {}, {}},
      Cause{cause::kCrashed, true, {}, {}, "It crashed.", {}, {}, {}},
      Cause{cause::kTimedOut, true, {}, {}, "It ran too long.", {}, {}, {}}};
  TestResult alone = makeTest("ImplicitEuler::integrate", "one step on a random state", 1);
  alone.max_score = 1;
  alone.causes = {Cause{cause::kCrashed, true, {}, {}, "It crashed.", {}, {}, {}}};
  report.tests.push_back(alone);
  const GradeReport clean = cleaned(report);
  ASSERT_EQ(clean.tests.size(), 3u);
  EXPECT_EQ(clean.tests[1].causeIds(), std::vector<std::string>{cause::kDanglingAutoExpression});
  EXPECT_EQ(clean.tests[2].causeIds(), std::vector<std::string>{cause::kCrashed});
  const std::string md = markdownReport(report);
  const std::string json = resultsJson(report).dump();
  const std::string xml = junitXml(report);
  const std::string html = studentReportHtml(report, {});
  for (const std::string& out : {md, json, xml, html}) {
    EXPECT_NE(out.find(cause::kDanglingAutoExpression), std::string::npos) << out;
    EXPECT_EQ(out.find(cause::kTimedOut), std::string::npos) << out;
    // `crashed` only for the check that names nothing else
    EXPECT_NE(out.find(cause::kCrashed), std::string::npos) << out;
  }
  EXPECT_EQ(countOf(md, "(`crashed`)"), 1u) << md;
  BatchEntry entry;
  entry.name = "sub";
  const BatchRow row = rowOf(entry, report);
  EXPECT_EQ(row.causes, (std::vector<std::pair<std::string, bool>>{
                            {cause::kDanglingAutoExpression, true}, {cause::kCrashed, true}}));
}

TEST(MarkdownReport, AStubSaysItsPointsWhatIsWrongAndItsFailedChecksAsATable) {
  GradeReport report = sampleReport();
  report.tests[1].output =
      "State tried:\n\n- sphere 0 (mass 125), before the call: x (0, 0.5, 0) m\n"
      "  - x after the call: expected (0, 0.5, 0) m, yours (0, 0.5, 0) m: the same within the "
      "tolerance\n"
      "  - v after the call: expected (0, **0.2**, 0) m/s, yours (0, **-1**, 0) m/s\n"
      "    - y differs by 1.2 = 1e+05 x the tolerance (1.2e-05)\n";
  report.stub_score = {{"Spheres::collide(Cloth*)", 0}, {"RungeKuttaFourth::integrate", 3}};
  report.stub_max = {{"Spheres::collide(Cloth*)", 2}, {"RungeKuttaFourth::integrate", 3}};
  const std::string md = markdownReport(report);
  EXPECT_NE(md.find("\n## Spheres::collide(Cloth*)\n\n**0 / 2**, 0 of 1 checks passed: scored per "
                    "check (each failed check loses its own points).\n"),
            std::string::npos)
      << md;
  EXPECT_NE(md.find("| failed check | expected | yours | by how much |\n|---|---|---|---|\n"
                    "| approaching pair: sphere 0: v after the call | (0, **0.2**, 0) m/s | (0, "
                    "**-1**, 0) m/s | y differs by 1.2 = 1e+05 x the tolerance (1.2e-05) |\n"),
            std::string::npos)
      << md;
  EXPECT_NE(md.find("The first failed check in full (approaching pair):\n\nState tried:"),
            std::string::npos)
      << md;
  EXPECT_NE(md.find("## Every check passed\n\n`RungeKuttaFourth::integrate`."), std::string::npos)
      << md;
  EXPECT_EQ(countOf(md, "**Likely cause** (`no-approach-check`)"), 1u) << md;
}

// One helper that pins particles in all four integrators: the why and example once, under the
// first stub; the later stubs keep their head and proof and refer to it. A stub whose checks are
// shown later never refers to one shown earlier than it.
TEST(MarkdownReport, ACausesWhyIsGivenOnceAcrossStubsShownTogether) {
  GradeReport report;
  report.submission = "sub";
  report.edition = 2024;
  for (const char* stub :
       {"ExplicitEuler::integrate", "ImplicitEuler::integrate", "MidpointEuler::integrate"}) {
    TestResult t = makeTest(stub, "one step on a random state", 1);
    t.max_score = 1;
    t.causes = {
        Cause{cause::kIntegratorPinsParticles, true, {}, {}, "Holds particles.", {}, {}, {}}};
    t.causes[0].why = "Fixed particles have mass 0.";
    t.causes[0].example = "p->velocity(0).setZero();  // mistake";
    t.causes[0].proof = std::string("Proven: ") + stub + ".";
    report.tests.push_back(t);
  }
  report.tests[2].visibility = "after_published";
  const std::string md = markdownReport(report);
  EXPECT_EQ(countOf(md, "**Why**: Fixed particles have mass 0."), 2u) << md;
  EXPECT_EQ(countOf(md, "p->velocity(0).setZero();  // mistake"), 2u) << md;
  EXPECT_EQ(countOf(md,
                    "**Why**, and the mistake with its fix: as under "
                    "`ExplicitEuler::integrate` above."),
            1u)
      << md;
  for (const char* stub :
       {"ExplicitEuler::integrate", "ImplicitEuler::integrate", "MidpointEuler::integrate"})
    EXPECT_EQ(countOf(md, std::string("Proven: ") + stub + "."), 1u) << md;
  const std::size_t implicit = md.find("## ImplicitEuler::integrate");
  const std::size_t midpoint = md.find("## MidpointEuler::integrate");
  ASSERT_NE(implicit, std::string::npos);
  ASSERT_NE(midpoint, std::string::npos);
  EXPECT_NE(md.find("as under `ExplicitEuler::integrate`", implicit), std::string::npos);
  EXPECT_EQ(md.find("as under", midpoint), std::string::npos);  // shown later: its own why
}

TEST(AllWriters, StateTheVerdictAndTheIsolation) {
  GradeReport report = sampleReport();
  report.verdict = grader::Verdict::TimedOut;
  report.isolation = "rlimits, uid 65534 <x>";
  const auto json = resultsJson(report);
  EXPECT_EQ(json["extra_data"]["verdict"], "timed-out");
  EXPECT_EQ(json["extra_data"]["isolation"], "rlimits, uid 65534 <x>");
  EXPECT_NE(json["output"].get<std::string>().find("Verdict: timed-out"), std::string::npos);
  const std::string xml = junitXml(report);
  EXPECT_NE(xml.find("<property name=\"verdict\" value=\"timed-out\"/>"), std::string::npos);
  EXPECT_NE(xml.find("<property name=\"isolation\" value=\"rlimits, uid 65534 &lt;x&gt;\"/>"),
            std::string::npos);
  const std::string markdown = markdownReport(report);
  EXPECT_NE(markdown.find("Verdict: **timed-out**"), std::string::npos);
  EXPECT_NE(markdown.find("Student code ran with: rlimits, uid 65534 <x>."), std::string::npos);
}

// The bytes real submissions bring: Big5 and CP950 comments, Latin-1, lone continuation bytes,
// NUL, terminal escapes, C1 controls and U+FFFE, in every text field a report has.
// One kind per line, as quoted source lines come.
const std::string kNasty =
    std::string("big5 \xA4\xA4\xA4\xE5\neuro \xA3\xE1\nlatin1 caf\xE9 au lait\n") +
    "lone \x80\xBF\nnul " + std::string(1, '\0') +
    "\nesc \x1B[31m | c1 \xC2\x9B | bell \x07 | fffe \xEF\xBF\xBE";

GradeReport nastyReport() {
  GradeReport report = sampleReport();
  report.submission = "sub\n\xFF\x1B]0;x\x07";
  report.edition_source = kNasty;
  report.verdict = grader::Verdict::Crashed;
  report.isolation = kNasty;
  UsedFile file;
  file.name = "cloth.cpp";
  file.path = "dir \xB3\x5C/" + kNasty + "/cloth.cpp";
  file.problem = "cloth.cpp:3: error: " + kNasty + "\n    3 | // " + kNasty + "\n";
  report.files = {file};
  report.notes = {kNasty, "stderr: " + kNasty};
  report.tests[1].output = "The probe process crashed.\n\n```\n" + kNasty + "\n```";
  report.tests[1].check = "check " + kNasty;
  return report;
}

// What XML 1.0 allows: tab, newline, carriage return and no other C0 control, valid UTF-8 and no
// U+FFFE / U+FFFF.
bool xmlCharactersOk(const std::string& text) {
  for (unsigned char c : text)
    if (c < 0x20 && c != '\t' && c != '\n' && c != '\r') return false;
  return isValidUtf8(text) && text.find("\xEF\xBF\xBE") == std::string::npos &&
         text.find("\xEF\xBF\xBF") == std::string::npos;
}

TEST(AllWriters, AnyBytesInValidUtf8OutAndTheReportSaysWhatWasDecoded) {
  const GradeReport report = nastyReport();
  // Strict: nlohmann's dump throws on invalid UTF-8, so this is the writer's own doing.
  std::string json_text;
  ASSERT_NO_THROW(json_text = resultsJson(report).dump(2));
  EXPECT_TRUE(isValidUtf8(json_text));
  const nlohmann::json json = nlohmann::json::parse(json_text);
  const std::string output = json["output"].get<std::string>();
  EXPECT_NE(output.find("\xE4\xB8\xAD\xE6\x96\x87"), std::string::npos) << output;  // 中文
  EXPECT_NE(output.find("lines decoded from Big5 (CP950) to UTF-8"), std::string::npos) << output;
  EXPECT_NE(output.find("replaced by U+FFFD"), std::string::npos) << output;
  const std::string xml = junitXml(report);
  EXPECT_TRUE(xmlCharactersOk(xml)) << xml;
  EXPECT_NE(xml.find("\xE2\x82\xAC"), std::string::npos);  // CP950's euro sign, decoded
  for (const std::string& text : {markdownReport(report), summaryLine(report)}) {
    EXPECT_TRUE(isValidUtf8(text)) << text;
    EXPECT_EQ(text.find('\x1B'), std::string::npos) << text;
    EXPECT_EQ(text.find('\0'), std::string::npos) << text;
    EXPECT_EQ(text.find("\xC2\x9B"), std::string::npos) << text;
  }
  EXPECT_EQ(summaryLine(report).find('\n'), std::string::npos);
  EXPECT_EQ(
      markdownReport(report).rfind("# Grading report: `sub\\x0A\xEF\xBF\xBD\\x1B]0;x\\x07`\n", 0),
      0u)
      << markdownReport(report);
}

// The batch's own outputs: row.json and the CSV from a report and a not-gradable folder name.
TEST(AllWriters, BatchRowAndCsvAreValidUtf8OnOneLine) {
  BatchEntry entry{"sub_", "in/\xFF\x1B[2J" + kNasty};
  const BatchRow row = rowOf(entry, nastyReport());
  std::string json_text;
  ASSERT_NO_THROW(json_text = rowJson(row).dump(2));
  EXPECT_TRUE(isValidUtf8(json_text));
  const std::string csv = batchCsv({row}, true);
  EXPECT_TRUE(isValidUtf8(csv)) << csv;
  EXPECT_EQ(csv.find('\x1B'), std::string::npos) << csv;
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 2) << csv;  // header and one row
}

// A grade whose JUnit cannot be written when the outputs are written (a name longer than the
// file system allows passes the check made before grading and fails at the write, as a full disk
// would; no device path is written by a test) writes none of its outputs and does not print
// "graded ... 80 / 80" as if it had: exit 2, one line (besides a uid slot skipped because another
// grader, e.g. the gradescope test's, holds it: what the grader says of the machine).
TEST(Cli, AnOutputThatCannotBeWrittenLeavesNoneAndClaimsNothing) {
  test::TempDir temp;
  const std::string junit = temp.file(std::string(300, 'j') + ".xml");
  const auto run = test::runCli(
      "grade '" + std::string(CLOTHREF_SOURCE_DIR) + "/tools/grader/reference/2022' --results '" +
      temp.file("r.json") + "' --junit '" + junit + "' --report '" + temp.file("r.md") +
      "' --no-whole-run --timeout 10 --cache-dir '" + std::string(CLOTHREF_GRADER_CACHE) + "'");
  EXPECT_EQ(run.exit_code, 2) << run.output;
  EXPECT_EQ(run.output.find("graded"), std::string::npos) << run.output;
  std::istringstream lines(run.output);
  int said = 0;
  for (std::string line; std::getline(lines, line);)
    said += line.rfind("clothref: uid slot ", 0) != 0;
  EXPECT_EQ(said, 1) << run.output;
  EXPECT_NE(run.output.find("jjjj"), std::string::npos) << run.output;
  EXPECT_FALSE(std::filesystem::exists(temp.file("r.json")));
  EXPECT_FALSE(std::filesystem::exists(temp.file("r.md")));
  for (const auto& entry : std::filesystem::directory_iterator(temp.path()))
    ADD_FAILURE() << "left behind: " << entry.path();
}

TEST(Cli, AnyBytesInTheSubmissionGiveValidOutputsInASingleGradeAndInABatch) {
  test::TempDir temp;
  temp.closeToOthers();
  const std::filesystem::path reference =
      std::filesystem::path(CLOTHREF_SOURCE_DIR) / "tools/grader/reference/2022";
  const std::filesystem::path dir = temp.path() / "sub\xFF\x1B[31mred";
  std::filesystem::create_directories(dir / "old\xA4\xA4");
  const std::string big5 = "// \xA4\xA4\xA4\xE5\xB5\xF9\xB8\xD1\n";  // 中文註解
  test::writeText(dir / "cloth.cpp", big5 + test::readText(reference / "cloth.cpp"));
  test::writeText(dir / "old\xA4\xA4" / "cloth.cpp", "// stray\n");
  test::writeText(dir / "sphere.cpp", big5 + test::readText(reference / "sphere.cpp") +
                                          "int broken = ; // \xA4\xA4\xA4\xE5\n");
  test::writeText(
      dir / "integrator.cpp",
      big5 + test::readText(reference / "integrator.cpp") +
          "#include <cstdio>\n#include <cstdlib>\n"
          "static const int noisy = [] {\n"
          "  std::fwrite(\"nul \\0 esc \\x1b[2J bad \\xff\\xfe \\xa4\\xa4\\xa4\\xe5\\n\", 1, 27, "
          "stderr);\n"
          "  std::abort();\n"
          "}();\n");
  const std::string common =
      " --no-whole-run --timeout 10 --cache-dir '" + std::string(CLOTHREF_GRADER_CACHE) + "'";
  const auto single = test::runCli("grade '" + dir.string() + "' --results '" +
                                   temp.file("r.json") + "' --junit '" + temp.file("j.xml") +
                                   "' --report '" + temp.file("r.md") + "'" + common);
  ASSERT_EQ(single.exit_code, 0) << single.output;
  EXPECT_EQ(single.output.find('\x1B'), std::string::npos) << single.output;
  EXPECT_TRUE(isValidUtf8(single.output)) << single.output;
  const auto batch =
      test::runCli("grade '" + dir.string() + "' --out '" + temp.file("batch") + "'" + common);
  ASSERT_EQ(batch.exit_code, 0) << batch.output;
  EXPECT_EQ(batch.output.find('\x1B'), std::string::npos) << batch.output;
  std::filesystem::path folder;
  for (const auto& entry : std::filesystem::directory_iterator(temp.path() / "batch"))
    if (entry.is_directory() && entry.path().filename().string()[0] != '.') folder = entry.path();
  ASSERT_FALSE(folder.empty());
  for (const std::filesystem::path& file :
       {std::filesystem::path(temp.file("r.json")), std::filesystem::path(temp.file("j.xml")),
        std::filesystem::path(temp.file("r.md")), folder / "results.json", folder / "report.md",
        folder / "row.json", temp.path() / "batch" / "grades.csv"}) {
    const std::string text = test::readText(file);
    ASSERT_FALSE(text.empty()) << file;
    EXPECT_TRUE(xmlCharactersOk(text)) << file << ":\n" << text;
    EXPECT_EQ(text.find('\x1B'), std::string::npos) << file;
    if (file.extension() == ".json") {
      EXPECT_NO_THROW({
        const nlohmann::json parsed = nlohmann::json::parse(text);
        EXPECT_FALSE(parsed.is_discarded());
      }) << file;
      EXPECT_NE(text.find("\\\\x1B[31mred"), std::string::npos) << file;  // JSON of "\x1B"
    }
  }
  for (const std::filesystem::path& file :
       {std::filesystem::path(temp.file("r.json")), std::filesystem::path(temp.file("r.md")),
        std::filesystem::path(temp.file("j.xml")), folder / "report.md"}) {
    const std::string text = test::readText(file);
    EXPECT_NE(text.find("\xE4\xB8\xAD\xE6\x96\x87"), std::string::npos) << file << text;  // 中文
    EXPECT_NE(text.find("decoded from Big5 (CP950)"), std::string::npos) << file;
  }
}

// ---- Quotes point at the right lines, once per stub

std::size_t occurrences(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

// Three integrators hold the same pattern (an `auto` Eigen expression over the state); midpoint and
// RK4 crash, implicit does not. Each crashed stub's dangling-auto cause quotes its own line only,
// on its first failed test only; the stub that did not crash gets no such cause.
TEST(Quotes, ACauseQuotesOnlyTheLinesOfTheStubItGradesOncePerStub) {
  test::TempDir temp;
  const std::filesystem::path reference =
      std::filesystem::path(CLOTHREF_SOURCE_DIR) / "tools/grader/reference/2022";
  const std::filesystem::path dir = temp.path() / "sub";
  std::filesystem::create_directories(dir);
  for (const char* file : {"cloth.cpp", "sphere.cpp"})
    std::filesystem::copy_file(reference / file, dir / file);
  std::string integrator = "#include <cstdlib>\n" + test::readText(reference / "integrator.cpp");
  const std::string backup = "  for (const auto &p : particles) backup.push_back(*p);\n";
  const auto pattern = [](const std::string& name, bool crash) {
    return "  auto " + name +
           " = particles[0]->position(0) - particles[0]->velocity(0);\n  (void)" + name + ";\n" +
           (crash ? "  std::abort();\n" : "");
  };
  std::size_t at = 0;
  for (const auto& [name, crash] :
       {std::pair{"implicit_diff", false}, std::pair{"midpoint_diff", true},
        std::pair{"rk4_diff", true}}) {
    at = integrator.find(backup, at);
    ASSERT_NE(at, std::string::npos) << name;
    at += backup.size();
    integrator.insert(at, pattern(name, crash));
  }
  test::writeText(dir / "integrator.cpp", integrator);
  const auto line_of = [&](const std::string& name) {
    const std::size_t where = integrator.find("auto " + name);
    return std::to_string(1 +
                          std::count(integrator.begin(), integrator.begin() + long(where), '\n'));
  };
  const auto run = test::runCli("grade '" + dir.string() + "' --results '" + temp.file("r.json") +
                                "' --no-whole-run --timeout 10 --cache-dir '" +
                                std::string(CLOTHREF_GRADER_CACHE) + "'");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  const nlohmann::json results = nlohmann::json::parse(test::readText(temp.file("r.json")));
  std::map<std::string, std::string> outputs;  // stub -> its tests' outputs, joined
  std::map<std::string, int> named;            // stub -> tests naming dangling-auto-expression
  for (const auto& test : results["tests"]) {
    const std::string stub = test["tags"][0];
    outputs[stub] += test["output"].get<std::string>();
    for (std::size_t k = 1; k < test["tags"].size(); ++k)
      named[stub] += test["tags"][k] == cause::kDanglingAutoExpression;
  }
  for (const auto& [stub, own, others] :
       {std::tuple{"MidpointEuler::integrate", "midpoint_diff",
                   std::vector{"rk4_diff", "implicit_diff"}},
        std::tuple{"RungeKuttaFourth::integrate", "rk4_diff",
                   std::vector{"midpoint_diff", "implicit_diff"}}}) {
    EXPECT_EQ(named[stub], 6) << stub;  // every test of the crashed stub names the cause
    EXPECT_EQ(occurrences(outputs[stub], "integrator.cpp:" + line_of(own) + ": auto " + own), 1u)
        << stub << ":\n"
        << outputs[stub];  // its own line, once
    for (const char* other : others)
      EXPECT_EQ(outputs[stub].find(other), std::string::npos) << stub << " quotes " << other;
  }
  EXPECT_EQ(named["ImplicitEuler::integrate"], 0);
  EXPECT_EQ(outputs["ImplicitEuler::integrate"].find("implicit_diff"), std::string::npos);
}

// ---- One truth in every output

// The first group of every match of `pattern` in `text`, in order.
std::vector<std::string> matches(const std::string& text, const std::regex& pattern) {
  std::vector<std::string> ids;
  for (auto it = std::sregex_iterator(text.begin(), text.end(), pattern);
       it != std::sregex_iterator(); ++it)
    ids.push_back((*it)[1].str());
  return ids;
}

// The cause ids a Markdown text names ("**Likely cause** (`id`)", "**Possible cause (a guess)**
// (`id`)"), in order.
std::vector<std::string> markdownCauses(const std::string& text) {
  static const std::regex cause(
      R"(\*\*(?:Likely cause|Possible cause \(a guess\))\*\* \(`([^`]+)`\))");
  return matches(text, cause);
}

// The same from a test output results.json gives as HTML (a check with a picture).
std::vector<std::string> htmlCauses(const std::string& text) {
  static const std::regex cause(
      R"(<strong>(?:Likely cause|Possible cause \(a guess\))</strong> \(<code>([^<]+)</code>\))");
  return matches(text, cause);
}

std::string unescapeXml(std::string text) {
  for (const auto& [from, to] : {std::pair{"&lt;", "<"}, std::pair{"&gt;", ">"},
                                 std::pair{"&quot;", "\""}, std::pair{"&amp;", "&"}})
    for (std::size_t at; (at = text.find(from)) != std::string::npos;)
      text.replace(at, std::string(from).size(), to);
  return text;
}

// Three submissions of the realistic corpus graded alone (results.json, report.md, report.html,
// JUnit) and as a batch (the CSV, row.json, the class overview): every output names the same
// causes for every check, in the same order, and the same points, rounded to 0.001 alike.
TEST(OneTruth, EveryOutputNamesTheSameCausesAndTheSamePoints) {
  test::TempDir temp;
  temp.closeToOthers();
  const std::filesystem::path corpus =
      std::filesystem::path(CLOTHREF_SOURCE_DIR) / "tests/grader/corpus";
  const std::vector<std::filesystem::path> dirs = {
      corpus / "2022/big5-shear-aliased-midpoint-first",
      corpus / "2024/swapped-damper-sign-per-body-midpoint",
      corpus / "2022/float-half-sixth-position-full-velocity"};
  const std::string common =
      " --timeout 10 --cache-dir '" + std::string(CLOTHREF_GRADER_CACHE) + "'";
  std::string batch_args = "grade";
  for (const auto& dir : dirs) batch_args += " '" + dir.string() + "'";
  const auto batch =
      test::runCli(batch_args + " --out '" + temp.file("batch") + "' --jobs 2" + common);
  ASSERT_EQ(batch.exit_code, 0) << batch.output;
  const std::string csv = test::readText(temp.path() / "batch" / "grades.csv");
  const std::string index = test::readText(temp.path() / "batch" / "index.html");
  const std::string data_open = "<script type=\"application/json\" id=\"class-data\">";
  const std::size_t data_at = index.find(data_open);
  ASSERT_NE(data_at, std::string::npos);
  const nlohmann::json overview = nlohmann::json::parse(index.substr(
      data_at + data_open.size(), index.find("</script>", data_at) - data_at - data_open.size()));
  for (const auto& dir : dirs) {
    const std::string name = dir.filename().string();
    SCOPED_TRACE(name);
    const std::string prefix = temp.file(name);
    const auto single = test::runCli("grade '" + dir.string() + "' --results '" + prefix +
                                     ".json' --report '" + prefix + ".md' --junit '" + prefix +
                                     ".xml' --html '" + prefix + ".html'" + common);
    ASSERT_EQ(single.exit_code, 0) << single.output;
    const nlohmann::json results = nlohmann::json::parse(test::readText(prefix + ".json"));
    const nlohmann::json batch_results =
        nlohmann::json::parse(test::readText(temp.path() / "batch" / name / "results.json"));
    const std::string md = test::readText(prefix + ".md");
    const std::string xml = test::readText(prefix + ".xml");
    const std::string html = test::readText(prefix + ".html");
    const nlohmann::json row =
        nlohmann::json::parse(test::readText(temp.path() / "batch" / name / "row.json"));
    // no scratch path of the grader in any of them (report.html embedded the whole run's)
    for (const std::string& text : {md, xml, html, results.dump(), batch_results.dump(),
                                    test::readText(temp.path() / "batch" / name / "report.html")})
      for (const char* scratch : {"clothref-grade-", "clothref-report-", "/src-cloth/"})
        EXPECT_EQ(text.find(scratch), std::string::npos) << scratch;
    // points: one rounding everywhere
    const std::string total = points(results["score"].get<double>());
    EXPECT_EQ(points(batch_results["score"].get<double>()), total);
    EXPECT_EQ(points(row["total"].get<double>()), total);
    EXPECT_NE(csv.find("\n" + name + ","), std::string::npos);
    const std::string csv_row = csv.substr(csv.find("\n" + name + ",") + 1);
    EXPECT_NE(csv_row.substr(0, csv_row.find('\n')).find("," + total + ","), std::string::npos)
        << csv_row;
    EXPECT_NE(md.find("**Code score " + total + " / "), std::string::npos);
    EXPECT_NE(html.find("<strong>Score " + total + " / "), std::string::npos);
    EXPECT_NE(xml.find("<property name=\"score\" value=\"" + total + "\"/>"), std::string::npos);
    bool in_overview = false;
    for (const auto& s : overview["submissions"])
      if (s["submission"] == name) {
        in_overview = true;
        EXPECT_EQ(points(s["total"].get<double>()), total);
      }
    EXPECT_TRUE(in_overview);
    // causes, check by check
    std::set<std::string> overview_causes, named_causes;
    for (const auto& s : overview["submissions"])
      if (s["submission"] == name)
        for (const auto& c : s["causes"]) overview_causes.insert(c["id"].get<std::string>());
    ASSERT_EQ(results["tests"].size(), batch_results["tests"].size());
    for (std::size_t k = 0; k < results["tests"].size(); ++k) {
      const auto& t = results["tests"][k];
      const std::string test_name = t["name"];
      SCOPED_TRACE(test_name);
      std::vector<std::string> tags;
      for (std::size_t j = 1; j < t["tags"].size(); ++j) tags.push_back(t["tags"][j]);
      std::vector<std::string> extra;
      if (t.contains("extra_data") && t["extra_data"].contains("causes"))
        for (const auto& c : t["extra_data"]["causes"]) extra.push_back(c["id"]);
      EXPECT_EQ(extra, tags);
      EXPECT_EQ(batch_results["tests"][k]["tags"], t["tags"]);
      std::vector<std::string> in_text =
          t["output_format"] == "html" ? htmlCauses(t["output"]) : markdownCauses(t["output"]);
      std::sort(in_text.begin(), in_text.end());
      std::vector<std::string> sorted_tags = tags;
      std::sort(sorted_tags.begin(), sorted_tags.end());
      EXPECT_EQ(in_text, sorted_tags) << t["output"];
      for (const auto& id : tags) named_causes.insert(id);
      const std::string stub = t["tags"][0];
      const std::string check = test_name.substr(stub.size() + 2);
      // report.md: the stub's section names every cause of its failed checks, once
      if (t["status"] == "failed" && test_name.find("whole run") == std::string::npos) {
        const std::size_t section = md.find("\n## " + stub + "\n");
        ASSERT_NE(section, std::string::npos) << stub;
        const std::size_t end = md.find("\n## ", section + 1);
        std::vector<std::string> md_causes = markdownCauses(md.substr(section, end - section));
        std::set<std::string> stub_causes;
        for (const auto& u : results["tests"])
          if (u["tags"][0] == stub && u["status"] == "failed")
            for (std::size_t j = 1; j < u["tags"].size(); ++j) stub_causes.insert(u["tags"][j]);
        EXPECT_EQ(std::set<std::string>(md_causes.begin(), md_causes.end()), stub_causes);
        EXPECT_EQ(md_causes.size(), stub_causes.size()) << "a cause said twice in " << stub;
        // JUnit: the failure of the same testcase
        const std::string open = "classname=\"" + unescapeXml(stub) + "\" name=\"" + check + "\">";
        std::string junit_case;
        for (std::size_t at = xml.find("<testcase "); at != std::string::npos;
             at = xml.find("<testcase ", at + 1)) {
          const std::string one = unescapeXml(xml.substr(at, xml.find("</testcase>", at) - at));
          if (one.find(open) != std::string::npos) junit_case = one;
        }
        ASSERT_FALSE(junit_case.empty()) << open;
        std::vector<std::string> junit_causes = markdownCauses(junit_case);
        std::sort(junit_causes.begin(), junit_causes.end());
        EXPECT_EQ(junit_causes, sorted_tags);
      }
      // report.html: the badges of the check, in its stub's section
      const std::size_t section = html.find("<h2 id=\"" + pagesEscape(stub) + "\">");
      ASSERT_NE(section, std::string::npos) << stub;
      const std::size_t summary = html.find(" " + pagesEscape(check) + " \xE2\x80\x94", section);
      ASSERT_NE(summary, std::string::npos) << check;
      const std::string badges = html.substr(summary, html.find("</summary>", summary) - summary);
      std::vector<std::string> html_causes;
      static const std::regex badge(R"(<span class="gr-cause[^"]*"[^>]*>([^<?]+)\??</span>)");
      for (auto it = std::sregex_iterator(badges.begin(), badges.end(), badge);
           it != std::sregex_iterator(); ++it)
        html_causes.push_back((*it)[1].str());
      EXPECT_EQ(html_causes, tags);
    }
    EXPECT_EQ(overview_causes, named_causes);
  }
}

// ---- Causes and numbers, read the same way everywhere

// A check's likely causes and its guesses, in every output: each cause a block of its own after a
// blank line (Markdown: results.json, report.md, JUnit) or a paragraph in a group of its own
// (HTML: results.json's check with a picture, report.html), the guesses after the likely ones.
TEST(AllWriters, LikelyCausesAndGuessesAreBlocksOfTheirOwnInEveryOutput) {
  GradeReport report = sampleReport();
  TestResult& t = report.tests[1];
  t.output = "Expected 1, yours 2.";
  t.causes = {
      Cause{cause::kNoApproachCheck, true, "Measured: 3 of 4.", {}, "The impulse.", {}, {}, {}},
      Cause{cause::kWrongMassSplit, true, {}, {}, "The split.", {}, {}, {}},
      Cause{cause::kUnknown, false, {}, {}, "No known mistake.", {}, {}, {}}};
  t.sketch.bodies.push_back({"sphere 0", {0, 0.5f, 0}, 0.5f, {0, -1, 0}, {0, 0, 0}, {0, -1, 0}});
  const std::string md_blocks =
      "Expected 1, yours 2.\n\n**Likely cause** (`no-approach-check`): The impulse.\n\nMeasured: "
      "3 of 4.\n\n**Likely cause** (`wrong-mass-split`): The split.\n\n**Possible cause (a "
      "guess)** (`unknown`): No known mistake.\n";
  const auto json = resultsJson(report);
  EXPECT_EQ(json["tests"][1]["output"], md_blocks);
  // report.md: the stub's causes, the likely ones then the guesses, each a block of its own
  const std::string md_causes = md_blocks.substr(md_blocks.find("**Likely cause**"));
  EXPECT_NE(markdownReport(report).find(md_causes), std::string::npos) << markdownReport(report);
  EXPECT_NE(unescapeXml(junitXml(report)).find(md_blocks), std::string::npos);
  for (const std::string& html :
       {withHtmlSummary(json, report)["tests"][1]["output"].get<std::string>(),
        studentReportHtml(report, nullptr)}) {
    const std::size_t likely = html.find("<div class=\"gr-likely\"><p><strong>Likely cause");
    const std::size_t second = html.find("</p>\n<p><strong>Likely cause</strong> (<code>wrong");
    const std::size_t guesses =
        html.find("</div>\n<div class=\"gr-guesses\"><p><strong>Possible cause (a guess)");
    EXPECT_NE(likely, std::string::npos) << html;
    EXPECT_LT(likely, second);
    EXPECT_LT(second, guesses);
    EXPECT_NE(guesses, std::string::npos) << html;
  }
}

// Every report says once how its numbers read: results.json's summary, report.md.
TEST(AllWriters, EveryReportSaysHowNumbersRead) {
  const std::string legend = kNumberLegend;
  EXPECT_NE(resultsJson(sampleReport())["output"].get<std::string>().find(legend),
            std::string::npos);
  EXPECT_NE(markdownReport(sampleReport()).find(legend), std::string::npos);
}

}  // namespace
}  // namespace clothref::grader
