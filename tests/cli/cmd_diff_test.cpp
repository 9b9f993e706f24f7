// `clothref diff` on hostile input (tools/clothref/cmd_diff.cpp and the trace reader behind it):
// multi-member and padded gzip, a gzip bomb in the header, unknown and duplicate keys, a stale
// per-step hash, and standard input that is used twice, closed or a directory. Each ends in the
// normal result or one line on stderr and exit 2.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "clothref/io/gzip_stream.h"
#include "test_util.h"

namespace clothref {
namespace {

namespace fs = std::filesystem;

int lineCount(const std::string& text) { return int(std::count(text.begin(), text.end(), '\n')); }

class DiffCli : public ::testing::Test {
 protected:
  void SetUp() override {
    ASSERT_EQ(
        test::runCli("trace --scene small-cloth --steps 60 --stride 10 -o " + trace_).exit_code, 0);
    text_ = test::readText(trace_);
    std::istringstream in(text_);
    for (std::string line; std::getline(in, line);) lines_.push_back(line);
    ASSERT_EQ(lines_.size(), 8u);  // header and steps 0, 10, ..., 60
  }

  // Runs `clothref diff ARGS` and expects exit 2 with one line starting "clothref: <start>"
  // and containing `problem`.
  void expectBadInput(const std::string& args, const std::string& start,
                      const std::string& problem) {
    const test::CommandResult run = test::runCli("diff " + args);
    EXPECT_EQ(run.exit_code, 2) << args << ": " << run.output;
    EXPECT_EQ(run.output.rfind("clothref: " + start, 0), 0u) << args << ": " << run.output;
    EXPECT_NE(run.output.find(problem), std::string::npos) << args << ": " << run.output;
    EXPECT_EQ(lineCount(run.output), 1) << run.output;
  }

  // The trace with line `index` (0 = header) replaced by `line`, written to `name`.
  std::string withLine(const std::string& name, std::size_t index, const std::string& line) {
    std::vector<std::string> lines = lines_;
    lines.at(index) = line;
    test::writeLines(dir_.file(name), lines);
    return dir_.file(name);
  }

  test::TempDir dir_;
  std::string trace_ = dir_.file("s.jsonl");
  std::string text_;
  std::vector<std::string> lines_;
};

// (head -n3 | gzip; tail -n+4 | gzip) > multi.gz reads like the plain trace, from a file and from
// standard input; gzip followed by zero padding or text is refused (all of them used to loop
// forever at 100 % CPU).
TEST_F(DiffCli, MultiMemberGzipReadsLikeZcatAndTrailingBytesAreRefused) {
  const std::size_t cut = text_.find('\n', text_.find('\n', text_.find('\n') + 1) + 1) + 1;
  const std::string multi = test::gzipMember(text_.substr(0, cut)) + test::gzipMember("") +
                            test::gzipMember(text_.substr(cut)) + test::gzipMember("");
  test::writeText(dir_.file("multi.gz"), multi);
  for (const std::string& args :
       {dir_.file("multi.gz") + " " + trace_, "- " + trace_ + " < " + dir_.file("multi.gz")}) {
    const test::CommandResult run = test::runCli("diff " + args);
    EXPECT_EQ(run.exit_code, 0) << args << ": " << run.output;
    EXPECT_EQ(run.output.rfind("identical:", 0), 0u) << run.output;
    EXPECT_NE(run.output.find("7 steps"), std::string::npos) << run.output;
  }
  for (const std::string& trailer : {std::string(4, '\0'), std::string("junk\n")}) {
    test::writeText(dir_.file("padded.gz"), multi + trailer);
    expectBadInput(dir_.file("padded.gz") + " " + trace_, dir_.file("padded.gz") + ":8: ",
                   "trailing bytes after the gzip data (not another gzip member)");
    expectBadInput("- " + trace_ + " < " + dir_.file("padded.gz"),
                   "standard input:8: ", "trailing bytes after the gzip data");
  }
}

// A 120 MB header line in a ~120 kB gzip (a scene holding a 6e7-element array) is refused by its
// length before any JSON parsing, in little memory; it used to take 7.7 GB at 240 MB.
TEST_F(DiffCli, HeaderGzipBombIsRefusedByLengthBeforeParsing) {
  const std::size_t at = lines_[0].find("\"scene\":{") + 9;
  std::string header = lines_[0].substr(0, at) + "\"junk\":[";
  for (int i = 0; i < 60'000'000; ++i) header += "0,";
  header += "0]," + lines_[0].substr(at);
  std::ofstream(dir_.file("bomb.jsonl.gz"), std::ios::binary)
      << test::gzipMember(header + "\n" + text_.substr(text_.find('\n') + 1));
  header.clear();
  header.shrink_to_fit();
  ASSERT_LT(fs::file_size(dir_.file("bomb.jsonl.gz")), 1'000'000u);

  const test::ProcessResult run =
      test::runCliDirect({"diff", dir_.file("bomb.jsonl.gz"), trace_}, dir_.path());
  EXPECT_EQ(run.exit_code, 2) << run.stderr_text;
  EXPECT_EQ(run.stderr_text, "clothref: " + dir_.file("bomb.jsonl.gz") +
                                 ":1: header line longer than 4194304 bytes (raise the limit "
                                 "with --max-header-bytes)\n");
  EXPECT_LT(run.max_rss_kb, 100'000) << "peak memory, KiB";
}

// Unknown keys inside the header's scene (any depth) and in step lines, and a key repeated in
// the header, are refused: the trace is never half understood.
TEST_F(DiffCli, UnknownAndDuplicateKeysAreRefused) {
  const std::string& header = lines_[0];
  auto edited = [&header](const std::string& find, const std::string& replace) {
    std::string line = header;
    const std::size_t at = line.find(find);
    EXPECT_NE(at, std::string::npos) << find;
    return line.replace(at, find.size(), replace);
  };
  expectBadInput(
      withLine("u1.jsonl", 0, edited("\"spring_coef\"", "\"spring_cof\":5,\"spring_coef\"")) + " " +
          trace_,
      dir_.file("u1.jsonl") + ":1: header: ", "/scene/cloth/spring_cof: unknown key");
  expectBadInput(
      withLine("u2.jsonl", 0, edited("\"radius\"", "\"colour\":\"red\",\"radius\"")) + " " + trace_,
      dir_.file("u2.jsonl") + ":1: header: ", "/scene/spheres/items/0/colour: unknown key");
  expectBadInput(withLine("d1.jsonl", 0, edited("\"integrator\"", "\"stride\":1,\"integrator\"")) +
                     " " + trace_,
                 dir_.file("d1.jsonl") + ":1: header: ", "/stride: duplicate key");
  expectBadInput(
      withLine("d2.jsonl", 0, edited("\"spring_coef\"", "\"damper_coef\":1,\"spring_coef\"")) +
          " " + trace_,
      dir_.file("d2.jsonl") + ":1: header: ", "/scene/cloth/damper_coef: duplicate key");
  std::string step = lines_[2];
  step.replace(step.find("\"velocity\""), 10, "\"mass\":[],\"velocity\"");
  expectBadInput(withLine("u3.jsonl", 2, step) + " " + trace_,
                 dir_.file("u3.jsonl") + ":3: ", "/bodies/cloth/mass: unknown key");
  step = lines_[2];
  step.insert(step.size() - 1, ",\"energy\":1");
  expectBadInput(withLine("u4.jsonl", 2, step) + " " + trace_,
                 dir_.file("u4.jsonl") + ":3: ", "/energy: unknown key");
}

// A step whose hash does not match its values is corrupt, whatever the other trace holds: here
// the other trace carries the same edit and differs only by a space (it used to be "identical").
TEST_F(DiffCli, StaleHashIsCorruptWhateverTheOtherSideHolds) {
  std::string step = lines_[3];
  const std::size_t at = step.find("\"position\":[[") + 13;
  const std::size_t end = step.find(',', at);
  const std::string value = step.substr(at, end - at);
  step.replace(at, end - at, value == "1" ? "2" : "1");  // a value changed, the hash kept
  const std::string edited = withLine("edited.jsonl", 3, step);
  step.replace(step.find("\"bodies\":"), 9, "\"bodies\": ");
  const std::string spaced = withLine("spaced.jsonl", 3, step);
  expectBadInput(edited + " " + spaced, edited + ":4: ",
                 "/hash: does not match the step's own values (a corrupt or edited record)");
  expectBadInput(trace_ + " " + edited, edited + ":4: ", "/hash: does not match");
}

// "-" once is standard input; twice is refused; a directory or a closed standard input is named
// as such, not as an empty file.
TEST_F(DiffCli, StandardInputTwiceClosedOrADirectoryIsNamed) {
  expectBadInput("- - < " + trace_, "", "A and B are both standard input");
  expectBadInput(dir_.path().string() + " " + trace_, dir_.path().string() + ": ",
                 "a directory, not a trace file");
  expectBadInput("- " + trace_ + " < " + dir_.path().string(),
                 "standard input: ", "a directory, not a trace");
  expectBadInput("- " + trace_ + " <&-", "standard input: ", "closed");
  // also when a file opened before it would have taken descriptor 0 (and been read as "-")
  expectBadInput(trace_ + " - <&-", "standard input: ", "closed");
  // an empty file is still called one
  test::writeText(dir_.file("empty.jsonl"), "");
  expectBadInput(dir_.file("empty.jsonl") + " " + trace_,
                 dir_.file("empty.jsonl") + ":1: ", "empty file");
}

// Control characters in a scene name (an informational header difference) and in a key (an
// error message) reach the terminal escaped; they used to be echoed raw.
TEST_F(DiffCli, ControlCharactersInNamesAreEscapedOnTheTerminal) {
  std::string header = lines_[0];
  const std::string name = "\"name\":\"small-cloth\"";
  header.replace(header.find(name), name.size(), "\"name\":\"\\u001b[2J\\u009b31m\\u007f\"");
  const test::CommandResult info =
      test::runCli("diff " + withLine("n.jsonl", 0, header) + " " + trace_);
  EXPECT_EQ(info.exit_code, 0) << info.output;
  EXPECT_NE(info.output.find("/scene/name: \"\\u001b[2J\\u009b31m\\x7f\" vs \"small-cloth\""),
            std::string::npos)
      << info.output;
  header = lines_[0];
  header.replace(header.find(name), name.size(), name + ",\"\\u001b]0;owned\\u0007\":1");
  expectBadInput(withLine("k.jsonl", 0, header) + " " + trace_,
                 dir_.file("k.jsonl") + ":1: ", "/scene/\\x1b]0;owned\\x07: unknown key");
  for (const std::string& output :
       {info.output, test::runCli("diff " + dir_.file("k.jsonl") + " " + trace_).output}) {
    EXPECT_EQ(output.find('\x1b'), std::string::npos) << output;
    EXPECT_EQ(output.find('\x7f'), std::string::npos) << output;
    EXPECT_EQ(output.find("\xc2\x9b"), std::string::npos) << output;
  }
}

}  // namespace
}  // namespace clothref
