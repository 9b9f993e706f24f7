// Batch grading (grader/grade/batch.h, `clothref grade DIR... --out BATCHDIR`): names, shards and
// the CSV as functions; then real batches through the CLI: a row per submission with the right
// verdicts, resume after a lost marker and after kill -9, shards that concatenate to the batch.
#include "grader/grade/batch.h"

#include <gtest/gtest.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <thread>

#include "clothref/io/error.h"
#include "corpus.h"
#include "grader/grade/cause_ids.h"
#include "test_util.h"

extern char** environ;

namespace clothref::grader {
namespace {

namespace fs = std::filesystem;
using test::readText;
using test::runCli;
using test::TempDir;

const fs::path kCorpus = test::corpusDir();

std::vector<std::string> lines(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) out.push_back(line);
  return out;
}

fs::path materialise(const std::string& name, const fs::path& target) {
  return test::materialiseCase(name, target);
}

// Runs the CLI batch of `dirs` into `out` with the test's quick settings and `extra` arguments.
test::CommandResult batch(const std::vector<fs::path>& dirs, const fs::path& out,
                          const std::string& extra = "") {
  std::string args = "grade";
  for (const fs::path& dir : dirs) args += " '" + dir.string() + "'";
  args += " --out '" + out.string() + "' --no-whole-run --cache-dir '" +
          std::string(CLOTHREF_GRADER_CACHE) + "' " + extra;
  if (extra.find("--timeout") == std::string::npos) args += " --timeout 10";
  return runCli(args);
}

// CSV cells of each data line, by submission name (no field of these tests needs quoting).
std::map<std::string, std::vector<std::string>> csvRows(const std::string& csv) {
  std::map<std::string, std::vector<std::string>> rows;
  for (const std::string& line : lines(csv)) {
    std::vector<std::string> cells;
    std::string cell;
    std::istringstream in(line);
    while (std::getline(in, cell, ',')) cells.push_back(cell);
    if (line.back() == ',') cells.push_back("");
    if (!cells.empty() && cells[0] != "submission") rows[cells[0]] = cells;
  }
  return rows;
}

std::size_t column(const std::string& csv, const std::string& name) {
  const std::string header = lines(csv).front();
  std::size_t index = 0;
  for (std::size_t at = 0; at < header.size(); ++index) {
    std::size_t comma = header.find(',', at);
    if (comma == std::string::npos) comma = header.size();
    if (header.substr(at, comma - at) == name) return index;
    at = comma + 1;
  }
  ADD_FAILURE() << "no column " << name << " in " << header;
  return 0;
}

// ---------------------------------------------------------------------------------------------
// Functions

TEST(Shard, ParsesKOfNAndRefusesEverythingElse) {
  const Shard shard = parseShard("2/3");
  EXPECT_EQ(shard.index, 2);
  EXPECT_EQ(shard.count, 3);
  EXPECT_EQ(parseShard("1/1").count, 1);
  for (const char* bad : {"0/3", "4/3", "3", "1/0", "-1/3", "a/b", "1/3x", "1//3", "", "/3",
                          "99999999999/99999999999"}) {
    try {
      parseShard(bad);
      ADD_FAILURE() << "accepted '" << bad << "'";
    } catch (const InputError& error) {
      EXPECT_NE(std::string(error.what()).find("--shard"), std::string::npos) << error.what();
    }
  }
}

TEST(Shard, SlicesAreDisjointCoverEverythingAndConcatenateInOrder) {
  for (int n_entries = 0; n_entries <= 11; ++n_entries) {
    std::vector<BatchEntry> entries;
    for (int i = 0; i < n_entries; ++i)
      entries.push_back({"s" + std::to_string(100 + i), "/x/" + std::to_string(i)});
    for (int count = 1; count <= 5; ++count) {
      std::vector<std::string> joined;
      for (int k = 1; k <= count; ++k)
        for (const BatchEntry& e : shardEntries(entries, {k, count})) joined.push_back(e.name);
      std::vector<std::string> all;
      for (const BatchEntry& e : entries) all.push_back(e.name);
      EXPECT_EQ(joined, all) << n_entries << " entries, " << count << " shards";
    }
  }
}

TEST(Names, LastComponentThenParentsWhenTheyCollideSortedAndDeduplicated) {
  TempDir temp;
  for (const char* dir :
       {"2022/reference", "2024/reference", "b/alice smith", "a/bob", "c", "d/.cache"})
    fs::create_directories(temp.path() / dir);
  const std::vector<BatchEntry> entries =
      batchEntries({temp.path() / "2024/reference", temp.path() / "b/alice smith",
                    temp.path() / "2022/reference", temp.path() / "a/bob",
                    temp.path() / "a/../a/bob", temp.path() / "c/", temp.path() / "d/.cache"});
  std::vector<std::string> names;
  for (const BatchEntry& e : entries) names.push_back(e.name);
  EXPECT_EQ(names, (std::vector<std::string>{"2022-reference", "2024-reference", "_.cache",
                                             "alice_smith", "bob", "c"}));
  EXPECT_EQ(entries[0].dir, temp.path() / "2022/reference");
}

// A submission folder named like one of the batch's own outputs gets a '_' before it, as a dot
// folder does: BATCHDIR/index.html stays the class overview, BATCHDIR/grades.csv the CSV.
TEST(Names, NamesOfTheBatchsOwnOutputsAreRenamed) {
  TempDir temp;
  std::vector<fs::path> dirs;
  for (const char* name : {"index.html", "grades.csv", "grades-1-of-2.csv", "index-1-of-2.html",
                           ".cache", "INDEX.HTML", "index.htm", "grades.csv.bak"}) {
    fs::create_directories(temp.path() / name);
    dirs.push_back(temp.path() / name);
  }
  std::vector<std::string> names;
  for (const BatchEntry& e : batchEntries(dirs)) names.push_back(e.name);
  EXPECT_EQ(names, (std::vector<std::string>{"_.cache", "_INDEX.HTML", "_grades-1-of-2.csv",
                                             "_grades.csv", "_index-1-of-2.html", "_index.html",
                                             "grades.csv.bak", "index.htm"}));
}

TEST(Names, NamesThatStayEqualAreBadInput) {
  TempDir temp;
  fs::create_directories(temp.path() / "a b");
  fs::create_directories(temp.path() / "a_b");
  EXPECT_THROW(batchEntries({temp.path() / "a b", temp.path() / "a_b"}), InputError);
}

TEST(Csv, HeaderHasEveryStubRowsQuoteAndMissingStubsAreEmpty) {
  BatchRow row;
  row.name = "alice";
  row.dir = "/x/alice";
  row.edition = 2024;
  row.stub_score = {{"Cloth::initializeSpring", 7.5}, {"RungeKuttaFourth::integrate", 15}};
  row.stub_max = {{"Cloth::initializeSpring", 10}, {"RungeKuttaFourth::integrate", 15}};
  row.score = 22.5;
  row.max_score = 25;
  row.verdict = grader::Verdict::Graded;
  row.isolation = "bubblewrap (net, pid), rlimits";
  row.seconds = 12.34;
  row.causes = {
      {cause::kMissingSprings, true}, {cause::kRk4WrongWeights, false}, {cause::kDamperSign, true}};
  BatchRow refused;
  refused.name = "bob";
  refused.verdict = grader::Verdict::NotGradable;
  refused.problem = "no file";
  const std::string csv = batchCsv({row, refused}, true);
  const auto written = lines(csv);
  ASSERT_EQ(written.size(), 3u) << csv;
  std::string header = "submission,edition";
  for (const std::string& stub : stubNames()) header += "," + stub;
  // one fact per column: the likely causes and the guesses apart, the isolation in none (the
  // batch's summary says it once)
  EXPECT_EQ(written[0], header + ",total,max,verdict,causes,guesses,seconds");
  EXPECT_EQ(written[1],
            "alice,2024,7.5,,,,,,,15,22.5,25,graded,missing-springs damper-sign,rk4-wrong-weights,"
            "12.3");
  EXPECT_EQ(written[2], "bob,,,,,,,,,,0,0,not-gradable,,,0.0");
  EXPECT_EQ(csv.find("bubblewrap"), std::string::npos);
  EXPECT_EQ(batchCsv({row}, false), written[1] + "\n");
}

TEST(Csv, RowJsonRoundTripsAndRefusesAStranger) {
  BatchRow row;
  row.name = "carol";
  row.dir = "/x/carol";
  row.edition = 2022;
  row.stub_score = {{"Spheres::collide()", 4}};
  row.stub_max = {{"Spheres::collide()", 10}};
  row.score = 4;
  row.max_score = 10;
  row.verdict = grader::Verdict::Crashed;
  row.isolation = "rlimits only";
  row.seconds = 3.5;
  row.causes = {{cause::kWrongMassSplit, true}, {cause::kCrashed, false}};
  const BatchRow back = rowFromJson(nlohmann::json::parse(rowJson(row).dump()), "row.json");
  EXPECT_EQ(batchCsv({back}, true), batchCsv({row}, true));
  EXPECT_EQ(back.causes, row.causes);
  EXPECT_EQ(back.isolation, row.isolation);
  EXPECT_THROW(rowFromJson(nlohmann::json{{"submission", "x"}}, "row.json"), InputError);
}

TEST(Jobs, SubmissionsShareTheCoresWithoutOversubscribing) {
  EXPECT_EQ(perSubmissionJobs(1, 2), 2);
  EXPECT_EQ(perSubmissionJobs(2, 2), 1);
  EXPECT_EQ(perSubmissionJobs(2, 8), 4);
  EXPECT_EQ(perSubmissionJobs(16, 8), 1);  // never 0
  for (int jobs = 1; jobs <= 8; ++jobs) EXPECT_LE(jobs * perSubmissionJobs(jobs, 8), 8);
}

// ---------------------------------------------------------------------------------------------
// The CLI

TEST(Cli, BadShardOrBatchOptionsWithoutOutAreOneLineExitTwoAndWriteNothing) {
  TempDir temp;
  const fs::path submission = kCorpus / "2022" / "reference";
  for (const char* shard : {"0/2", "3/2", "x", "''", "1/", "/2", "1/2/3", "-1/2"}) {
    const auto run = batch({submission}, temp.path() / "out", std::string("--shard ") + shard);
    EXPECT_EQ(run.exit_code, 2) << run.output;
    EXPECT_EQ(lines(run.output).size(), 1u) << run.output;
    EXPECT_NE(run.output.find("--shard"), std::string::npos) << run.output;
    EXPECT_FALSE(fs::exists(temp.path() / "out"));
  }
  const auto run = runCli("grade '" + submission.string() + "' --jobs 2");
  EXPECT_EQ(run.exit_code, 2) << run.output;
  EXPECT_NE(run.output.find("--out"), std::string::npos) << run.output;
}

// --timeout takes seconds in (0, 1 day]: NaN, infinity, 0, negative and 1e30 are one short line.
TEST(Cli, TimeoutMustBeAPositiveNumberOfSecondsUpToADay) {
  TempDir temp;
  const fs::path submission = kCorpus / "2022" / "reference";
  for (const char* timeout : {"nan", "inf", "0", "-1", "1e30", "86401", "9.3e18", "ten"}) {
    const auto run = runCli("grade '" + submission.string() + "' --timeout " + timeout +
                            " --results '" + temp.file("r.json") + "'");
    EXPECT_EQ(run.exit_code, 2) << timeout << ": " << run.output;
    EXPECT_EQ(lines(run.output).size(), 1u) << run.output;
    EXPECT_NE(run.output.find("--timeout"), std::string::npos) << run.output;
    EXPECT_LT(run.output.size(), 160u) << run.output;
    EXPECT_FALSE(fs::exists(temp.file("r.json")));
  }
}

// --max-file-bytes is a real option: under it every file of the reference is refused (nothing to
// grade, exit 2, one line); 0 is refused as an option.
TEST(Cli, MaxFileBytesIsARealOption) {
  TempDir temp;
  const fs::path submission = kCorpus / "2022" / "reference";
  const auto tiny = runCli("grade '" + submission.string() + "' --max-file-bytes 10 --results '" +
                           temp.file("r.json") + "'");
  EXPECT_EQ(tiny.exit_code, 2) << tiny.output;
  EXPECT_NE(tiny.output.find("none of cloth.cpp"), std::string::npos) << tiny.output;
  EXPECT_FALSE(fs::exists(temp.file("r.json")));
  const auto zero = runCli("grade '" + submission.string() + "' --max-file-bytes 0");
  EXPECT_EQ(zero.exit_code, 2) << zero.output;
  EXPECT_NE(zero.output.find("--max-file-bytes"), std::string::npos) << zero.output;
}

// A path that does not exist is a typo of the command: the batch stops before grading (exit 2),
// naming it with the reason, and writes nothing.
TEST(Cli, ABatchStopsBeforeGradingAtAPathThatDoesNotExist) {
  TempDir temp;
  const auto run = runCli("grade '" + (kCorpus / "2022" / "reference").string() + "' '" +
                          temp.file("no-such-student") + "' --out '" + temp.file("batch") + "'");
  EXPECT_EQ(run.exit_code, 2) << run.output;
  EXPECT_NE(run.output.find("no-such-student: No such file or directory"), std::string::npos)
      << run.output;
  EXPECT_EQ(std::count(run.output.begin(), run.output.end(), '\n'), 1) << run.output;
  EXPECT_FALSE(fs::exists(temp.path() / "batch" / "grades.csv"));
  EXPECT_FALSE(fs::exists(temp.path() / "batch" / "reference"));
}

// Named outputs are checked before grading: a folder that does not exist is "No such file or
// directory" (not "not a directory"), a named output that is a symbolic link is refused (never
// written through), each in one line, at once, and nothing is written.
TEST(Cli, NamedOutputsAreCheckedBeforeGrading) {
  TempDir temp;
  test::writeText(temp.path() / "target.json", "keep me\n");
  fs::create_symlink(temp.path() / "target.json", temp.path() / "link.json");
  const std::string submission = (kCorpus / "2022" / "reference").string();
  const struct {
    std::string args, message;
  } cases[] = {
      {"--html /nonexistent-dir/r.html",
       "--html /nonexistent-dir/r.html: /nonexistent-dir: No such file or directory"},
      {"--results '" + temp.file("link.json") + "'",
       "a symbolic link; outputs are never written through a link"},
      {"--report '" + temp.file("target.json/x.md") + "'", "Not a directory"},
      {"--out '" + temp.file("b") + "' --csv /nonexistent-dir/g.csv",
       "/nonexistent-dir: No such file or directory"},
  };
  for (const auto& c : cases) {
    const auto start = std::chrono::steady_clock::now();
    const auto run = runCli("grade '" + submission + "' " + c.args);
    EXPECT_EQ(run.exit_code, 2) << c.args << ": " << run.output;
    EXPECT_NE(run.output.find(c.message), std::string::npos) << run.output;
    EXPECT_EQ(std::count(run.output.begin(), run.output.end(), '\n'), 1) << run.output;
    EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(1)) << c.args;
  }
  EXPECT_EQ(readText(temp.path() / "target.json"), "keep me\n");
  EXPECT_FALSE(fs::exists(temp.path() / "b"));
}

// A folder holding several whole submissions is refused with one line naming them, alone and in a
// batch, unless --one-submission says to grade it as one.
TEST(Cli, AFolderOfSeveralSubmissionsIsRefusedUnlessAskedFor) {
  TempDir temp;
  const fs::path subs = temp.path() / "subs";
  for (const char* name : {"alice", "bob", "carol"}) materialise("2022/reference", subs / name);
  const auto alone =
      runCli("grade '" + subs.string() + "' --results '" + temp.file("r.json") + "'");
  EXPECT_EQ(alone.exit_code, 2) << alone.output;
  EXPECT_NE(
      alone.output.find("3 submissions below " + subs.string() +
                        " (alice, bob, carol): give them as " + subs.string() + "/* with --out"),
      std::string::npos)
      << alone.output;
  EXPECT_EQ(std::count(alone.output.begin(), alone.output.end(), '\n'), 1) << alone.output;
  EXPECT_FALSE(fs::exists(temp.file("r.json")));
  const auto asked =
      runCli("grade '" + subs.string() + "' --one-submission --no-whole-run --cache-dir '" +
             std::string(CLOTHREF_GRADER_CACHE) + "' --results '" + temp.file("r.json") + "'");
  EXPECT_EQ(asked.exit_code, 0) << asked.output;
  // the choice is said on the terminal: the first copy of each name, the others found
  EXPECT_NE(asked.output.find("clothref grade: cloth.cpp: used alice/"), std::string::npos)
      << asked.output;
  EXPECT_NE(asked.output.find("also found bob/"), std::string::npos) << asked.output;
  EXPECT_NE(asked.output.find(": 80 / 80, verdict graded"), std::string::npos) << asked.output;
  const auto batch = runCli("grade '" + subs.string() + "' --out '" + temp.file("batch") +
                            "' --no-whole-run --quiet");
  EXPECT_EQ(batch.exit_code, 0) << batch.output;
  const nlohmann::json row =
      nlohmann::json::parse(readText(temp.path() / "batch" / "subs" / "row.json"));
  EXPECT_EQ(row["verdict"], "not-gradable");
  EXPECT_NE(row["problem"].get<std::string>().find("3 submissions below"), std::string::npos);
}

// A batch: the reference, a mutant, a folder without student files. Every one gets a row with its
// verdict; then resume, shards and --regrade on the same submissions.
class Batch : public ::testing::Test {
 protected:
  void SetUp() override {
    temp_.closeToOthers();
    dirs_ = {materialise("2022/reference", temp_.path() / "in" / "reference"),
             materialise("2022/force-assign", temp_.path() / "in" / "force-assign"),
             temp_.path() / "in" / "nothing-here"};
    fs::create_directories(dirs_.back());
    test::writeText(dirs_.back() / "README.txt", "forgot to upload\n");
  }
  TempDir temp_;
  std::vector<fs::path> dirs_;
};

TEST_F(Batch, RowPerSubmissionRightVerdictsResumeSkipsGradedAndRegradesHalfGraded) {
  const fs::path out = temp_.path() / "out";
  const auto first = batch(dirs_, out, "--jobs 2");
  ASSERT_EQ(first.exit_code, 0) << first.output;
  const std::string csv = readText(out / "grades.csv");
  const auto rows = csvRows(csv);
  ASSERT_EQ(rows.size(), 3u) << csv;
  const std::size_t verdict = column(csv, "verdict"), total = column(csv, "total"),
                    max = column(csv, "max"), forces = column(csv, "Cloth::computeSpringForce"),
                    springs = column(csv, "Cloth::initializeSpring");
  EXPECT_EQ(rows.at("reference")[verdict], "graded");
  EXPECT_EQ(rows.at("reference")[total], rows.at("reference")[max]);
  EXPECT_EQ(rows.at("reference")[max], "80");
  EXPECT_EQ(rows.at("force-assign")[verdict], "graded");
  EXPECT_LT(std::stod(rows.at("force-assign")[forces]), 20.0);
  EXPECT_EQ(rows.at("force-assign")[springs], "15");
  EXPECT_EQ(rows.at("nothing-here")[verdict], "not-gradable");
  EXPECT_EQ(rows.at("nothing-here")[total], "0");
  // Rows sorted by name, every submission with its folder.
  std::vector<std::string> order;
  for (const auto& line : lines(csv)) order.push_back(line.substr(0, line.find(',')));
  EXPECT_EQ(order,
            (std::vector<std::string>{"submission", "force-assign", "nothing-here", "reference"}));
  for (const char* name : {"reference", "force-assign", "nothing-here"})
    for (const char* file : {"results.json", "report.md", "row.json"})
      EXPECT_TRUE(fs::exists(out / name / file)) << name << "/" << file;
  EXPECT_NE(readText(out / "nothing-here" / "report.md").find("none of cloth.cpp"),
            std::string::npos);
  // the last lines: the submission whose verdict is not `graded`, how student code ran (once for
  // the batch: the CSV has no column for it), then where the CSV and the class overview are
  const std::vector<std::string> said = lines(first.output);
  ASSERT_GE(said.size(), 4u) << first.output;
  // before them, where the batch's time went: the graded submissions, slowest first, with their
  // compile and probe seconds (issue 39); the refused folder is not among them
  const std::size_t slowest = first.output.find("clothref grade: the slowest:\n");
  ASSERT_NE(slowest, std::string::npos) << first.output;
  EXPECT_LT(slowest, first.output.find(" with a verdict other than")) << first.output;
  const std::string slow_lines = first.output.substr(slowest);
  EXPECT_NE(slow_lines.find("  reference: "), std::string::npos) << first.output;
  EXPECT_NE(slow_lines.find("compile "), std::string::npos) << first.output;
  EXPECT_EQ(slow_lines.find("  nothing-here: 0"), std::string::npos) << first.output;
  EXPECT_NE(said[said.size() - 4].find("1 with a verdict other than 'graded':"), std::string::npos)
      << first.output;
  EXPECT_EQ(said[said.size() - 3], "  nothing-here: not-gradable") << first.output;
  const std::string ran = "clothref grade: student code ran with: ";
  EXPECT_EQ(said[said.size() - 2].rfind(ran, 0), 0u) << first.output;
  EXPECT_EQ(first.output.find(ran), first.output.rfind(ran)) << first.output;
  EXPECT_EQ(csv.find(said[said.size() - 2].substr(ran.size())), std::string::npos) << csv;
  EXPECT_EQ(said.back(), "clothref grade: CSV " + (out / "grades.csv").string() +
                             "; class overview " + (out / "index.html").string())
      << first.output;

  // Resume: the mutant lost its marker (as if killed between its results and its row); the
  // others keep theirs untouched.
  const auto reference_time = fs::last_write_time(out / "reference" / "row.json");
  const std::string reference_row = readText(out / "reference" / "row.json");
  const auto results_time = fs::last_write_time(out / "force-assign" / "results.json");
  fs::remove(out / "force-assign" / "row.json");
  fs::remove(out / "grades.csv");
  const auto second = batch(dirs_, out, "--jobs 2");
  ASSERT_EQ(second.exit_code, 0) << second.output;
  EXPECT_NE(second.output.find("1 graded now, 2 already graded"), std::string::npos)
      << second.output;
  EXPECT_EQ(fs::last_write_time(out / "reference" / "row.json"), reference_time);
  EXPECT_EQ(readText(out / "reference" / "row.json"), reference_row);
  EXPECT_TRUE(fs::exists(out / "force-assign" / "row.json"));
  EXPECT_NE(fs::last_write_time(out / "force-assign" / "results.json"), results_time);
  const auto resumed = csvRows(readText(out / "grades.csv"));
  ASSERT_EQ(resumed.size(), 3u);
  EXPECT_EQ(resumed.at("force-assign")[forces], rows.at("force-assign")[forces]);
  EXPECT_EQ(resumed.at("reference"), rows.at("reference"));

  // --regrade: every marker is written again.
  const auto third = batch(dirs_, out, "--regrade --quiet");
  ASSERT_EQ(third.exit_code, 0) << third.output;
  // --quiet: nothing but what the grader says of the machine (a uid slot another grader holds,
  // e.g. the gradescope test's beside this one)
  std::istringstream quiet(third.output);
  for (std::string line; std::getline(quiet, line);)
    EXPECT_EQ(line.rfind("clothref: uid slot ", 0), 0u) << third.output;
  EXPECT_NE(fs::last_write_time(out / "reference" / "row.json"), reference_time);
}

// Inside BATCHDIR nothing is written through a link: a link planted in place of an output file
// is replaced by the file (its target untouched); a link in place of a submission's folder stops
// the batch before grading, naming it; a submission folder given as a link is not followed (a
// not-gradable row).
TEST_F(Batch, NothingIsWrittenOrReadThroughALinkInsideTheBatchFolder) {
  const fs::path out = temp_.path() / "out", elsewhere = temp_.path() / "elsewhere";
  fs::create_directories(out);
  fs::create_directories(elsewhere);
  test::writeText(elsewhere / "target.csv", "keep me\n");
  fs::create_symlink(elsewhere / "target.csv", out / "grades.csv");
  fs::create_symlink(elsewhere / "target.csv", out / "index.html");
  fs::create_symlink(elsewhere, out / "reference");
  const auto refused = batch(dirs_, out);
  EXPECT_EQ(refused.exit_code, 2) << refused.output;
  EXPECT_NE(refused.output.find((out / "reference").string() +
                                ": not a folder of the batch (a symbolic link"),
            std::string::npos)
      << refused.output;
  EXPECT_EQ(std::distance(fs::directory_iterator(elsewhere), fs::directory_iterator()), 1);
  fs::remove(out / "reference");
  // a submission given as a link to a real one: a row saying so, its target not graded
  fs::create_symlink(dirs_[0], temp_.path() / "in" / "linked");
  std::vector<fs::path> with_link = dirs_;
  with_link.push_back(temp_.path() / "in" / "linked/");
  const auto graded = batch(with_link, out, "--jobs 2");
  ASSERT_EQ(graded.exit_code, 0) << graded.output;
  EXPECT_EQ(readText(elsewhere / "target.csv"), "keep me\n");
  EXPECT_FALSE(fs::exists(elsewhere / "results.json"));
  EXPECT_FALSE(fs::is_symlink(out / "grades.csv"));
  EXPECT_FALSE(fs::is_symlink(out / "index.html"));
  EXPECT_NE(readText(out / "grades.csv").find("reference,2022"), std::string::npos);
  const nlohmann::json row = nlohmann::json::parse(readText(out / "linked" / "row.json"));
  EXPECT_EQ(row["verdict"], "not-gradable");
  EXPECT_NE(
      row["problem"].get<std::string>().find("a symbolic link (a submission folder given as a "
                                             "link is not followed)"),
      std::string::npos)
      << row.dump();
}

TEST_F(Batch, ShardsAreDisjointAndTheirCsvsConcatenateToTheWholeBatch) {
  const fs::path whole = temp_.path() / "whole", sharded = temp_.path() / "sharded";
  ASSERT_EQ(batch(dirs_, whole, "--jobs 2").exit_code, 0);
  std::string joined;
  std::set<std::string> seen;
  for (int k = 1; k <= 3; ++k) {
    const std::string shard = std::to_string(k) + "/3";
    const auto run = batch(dirs_, sharded, "--shard " + shard + (k > 1 ? " --csv-no-header" : ""));
    ASSERT_EQ(run.exit_code, 0) << run.output;
    EXPECT_NE(run.output.find("1 graded now, 0 already graded"), std::string::npos)
        << shard << ": " << run.output;  // each shard grades only its own third
    const std::string csv = readText(sharded / ("grades-" + std::to_string(k) + "-of-3.csv"));
    for (const auto& [name, cells] : csvRows(csv)) EXPECT_TRUE(seen.insert(name).second) << name;
    joined += csv;
  }
  // Same rows, same order; only the wall time may differ between the two gradings.
  const auto strip_seconds = [](const std::string& csv) {
    std::string out;
    for (const std::string& line : lines(csv)) out += line.substr(0, line.rfind(',')) + "\n";
    return out;
  };
  EXPECT_EQ(strip_seconds(joined), strip_seconds(readText(whole / "grades.csv")));
}

// kill -9 in the middle of a batch: a rerun skips what was finished and grades the rest. The
// last submission spins in computeSpringForce until the probe's time limit, so the batch is
// certainly still running when the first marker appears.
TEST_F(Batch, RerunAfterKillNineSkipsFinishedSubmissions) {
  const fs::path out = temp_.path() / "out";
  const fs::path spins = materialise("2022/reference", temp_.path() / "in" / "zz-spins");
  std::string cloth = readText(spins / "cloth.cpp");
  const std::string function = "void Cloth::computeSpringForce() {";
  ASSERT_NE(cloth.find(function), std::string::npos);
  cloth.insert(cloth.find(function) + function.size(),
               "\n  for (volatile int spin = 1; spin;) {\n  }\n");
  test::writeText(spins / "cloth.cpp", cloth);
  std::vector<fs::path> dirs = dirs_;
  dirs.push_back(spins);
  const std::string timeout = "3";
  std::vector<std::string> args = {CLOTHREF_BIN, "grade"};
  for (const fs::path& dir : dirs) args.push_back(dir.string());
  for (const std::string& a :
       std::vector<std::string>{"--out", out.string(), "--no-whole-run", "--timeout", timeout,
                                "--cache-dir", CLOTHREF_GRADER_CACHE, "--quiet"})
    args.push_back(a);
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  pid_t pid = 0;
  ASSERT_EQ(posix_spawn(&pid, argv[0], nullptr, nullptr, argv.data(), environ), 0);
  // Sorted order with one job: force-assign first. Wait for its marker, then kill.
  const fs::path first_marker = out / "force-assign" / "row.json";
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::minutes(5);
  int status = 0;
  bool exited = false;
  while (!fs::exists(first_marker) && std::chrono::steady_clock::now() < deadline) {
    if (waitpid(pid, &status, WNOHANG) == pid) {
      exited = true;
      break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  ASSERT_TRUE(fs::exists(first_marker));
  ASSERT_FALSE(exited);
  kill(pid, SIGKILL);
  waitpid(pid, &status, 0);
  const auto marker_time = fs::last_write_time(first_marker);
  EXPECT_FALSE(fs::exists(out / "grades.csv"));  // killed before the end
  EXPECT_FALSE(fs::exists(out / "zz-spins" / "row.json"));

  const auto rerun = batch(dirs, out, "--timeout " + timeout);
  ASSERT_EQ(rerun.exit_code, 0) << rerun.output;
  EXPECT_EQ(fs::last_write_time(first_marker), marker_time);
  const auto rows = csvRows(readText(out / "grades.csv"));
  EXPECT_EQ(rows.size(), 4u);
  EXPECT_TRUE(rows.count("zz-spins"));
  EXPECT_NE(rerun.output.find("already graded"), std::string::npos) << rerun.output;
  EXPECT_EQ(rerun.output.find(", 0 already graded"), std::string::npos) << rerun.output;
}

// The adversarial suite (tests/grader/adversarial, its expected.json per case) in one batch with
// the reference: the reference scores 100 %, every case gets its verdict and loses points where
// its file says, and none of them stops the batch.
TEST(AdversarialBatch, ReferenceAtFullMarksEveryCaseWithItsVerdict) {
  TempDir temp;
  temp.closeToOthers();
  const fs::path suite = fs::path(CLOTHREF_SOURCE_DIR) / "tests" / "grader" / "adversarial";
  const fs::path results_dir = temp.path() / "student-results";  // what write-results attacks
  fs::create_directories(results_dir);
  std::map<std::string, nlohmann::json> expected;
  std::vector<fs::path> dirs = {materialise("2022/reference", temp.path() / "in" / "reference")};
  for (const auto& entry : fs::directory_iterator(suite)) {
    if (!fs::exists(entry.path() / "expected.json")) continue;
    const std::string name = entry.path().filename().string();
    std::ifstream in(entry.path() / "expected.json");
    expected[name] = nlohmann::json::parse(in);
    const fs::path dir = temp.path() / "in" / name;
    fs::create_directories(dir);
    const fs::path base = kCorpus / expected[name]["base"].get<std::string>();
    for (const char* file : {"cloth.cpp", "sphere.cpp", "integrator.cpp"}) {
      const fs::path own = entry.path() / file;
      std::string text = readText(fs::exists(own) ? own : test::corpusFile(base, file));
      // The suite's placeholders (adversarial_test.cpp fills them the same way).
      const std::map<std::string, std::string> fill = {{"@MARKER@", "bat-" + name.substr(0, 10)},
                                                       {"@SOURCE_DIR@", CLOTHREF_SOURCE_DIR},
                                                       {"@RESULTS_DIR@", results_dir.string()}};
      for (const auto& [from, to] : fill)
        for (std::size_t at = 0; (at = text.find(from, at)) != std::string::npos;)
          text.replace(at, from.size(), to);
      test::writeText(dir / file, text);
    }
    dirs.push_back(dir);
  }
  ASSERT_GE(expected.size(), 10u) << "the adversarial suite is missing";

  const fs::path out = temp.path() / "out";
  const auto run = batch(dirs, out, "--jobs 2 --timeout 3");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  const std::string csv = readText(out / "grades.csv");
  const auto rows = csvRows(csv);
  ASSERT_EQ(rows.size(), expected.size() + 1) << csv;
  const std::size_t verdict = column(csv, "verdict"), total = column(csv, "total"),
                    max = column(csv, "max");
  EXPECT_EQ(rows.at("reference")[verdict], "graded");
  EXPECT_EQ(rows.at("reference")[total], rows.at("reference")[max]);
  EXPECT_EQ(rows.at("reference")[max], "80");
  for (const auto& [name, want] : expected) {
    SCOPED_TRACE(name);
    const auto& row = rows.at(name);
    std::ifstream in(out / name / "results.json");
    const nlohmann::json results = nlohmann::json::parse(in);
    const bool boxed =
        results["extra_data"]["isolation"].get<std::string>().rfind("bubblewrap", 0) == 0;
    const std::string verdict_wanted = !boxed && want.contains("verdict_rlimits")
                                           ? want["verdict_rlimits"].get<std::string>()
                                           : want["verdict"].get<std::string>();
    EXPECT_EQ(row[verdict], verdict_wanted);
    for (const auto& stub : want.value("loses", nlohmann::json::array()))
      EXPECT_LT(results["extra_data"]["stub_scores"][stub.get<std::string>()].get<double>(),
                results["extra_data"]["stub_max"][stub.get<std::string>()].get<double>())
          << stub;
    if (want.value("full_marks", false) && verdict_wanted == want["verdict"].get<std::string>()) {
      EXPECT_EQ(row[total], "80");
    }
  }
  EXPECT_FALSE(fs::exists(results_dir / "forged.json"));
}

}  // namespace
}  // namespace clothref::grader
