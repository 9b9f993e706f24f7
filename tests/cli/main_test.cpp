// What every command shares (tools/clothref/main.cpp): the input-limit flags before or after the
// command name, output into a FIFO, and a signal during a write.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>
#include <chrono>
#include <filesystem>
#include <future>
#include <string>
#include <thread>

#include "test_util.h"

namespace clothref {
namespace {

namespace fs = std::filesystem;

TEST(OutputFileCli, TraceIntoAFifoKeepsTheFifo) {
  const test::TempDir dir;
  const std::string path = dir.file("pipe");
  ASSERT_EQ(::mkfifo(path.c_str(), 0600), 0);
  auto reader = std::async(std::launch::async, [&] { return test::readText(path); });
  const auto result = test::runCli("trace --scene free-fall --steps 3 -o " + path);
  EXPECT_EQ(result.exit_code, 0) << result.output;
  const std::string text = reader.get();
  EXPECT_EQ(text.rfind("{\"format\":\"clothref-trace\"", 0), 0u) << text.substr(0, 80);
  EXPECT_TRUE(test::isFifo(path));
}

// SIGINT, SIGTERM and SIGHUP during `trace -o`: the temporary file is removed, one line says so,
// and the process ends by the signal (a shell reports 128 + N).
TEST(OutputFileCli, SignalRemovesTheTemporaryFile) {
  for (int signal : {SIGINT, SIGTERM, SIGHUP}) {
    const test::TempDir dir;
    const std::string output = dir.file("out.jsonl");
    const std::string errors = dir.file("err.txt");
    const pid_t child = ::fork();
    ASSERT_GE(child, 0);
    if (child == 0) {
      const int fd = ::open(errors.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
      ::dup2(fd, 2);
      ::execl(CLOTHREF_BIN, CLOTHREF_BIN, "trace", "--scene", "small-cloth", "--steps", "100000000",
              "--stride", "1", "-o", output.c_str(), static_cast<char*>(nullptr));
      ::_exit(127);
    }
    const std::string temporary = output + ".tmp" + std::to_string(child);
    for (int i = 0; i < 3000 && !(std::filesystem::exists(temporary) &&
                                  std::filesystem::file_size(temporary) > 0);
         ++i)
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    ASSERT_TRUE(std::filesystem::exists(temporary)) << signal;
    ::kill(child, signal);
    int status = 0;
    ASSERT_EQ(::waitpid(child, &status, 0), child);
    EXPECT_TRUE(WIFSIGNALED(status)) << signal;
    if (WIFSIGNALED(status)) {
      EXPECT_EQ(WTERMSIG(status), signal);
    }
    EXPECT_FALSE(std::filesystem::exists(temporary)) << signal;
    EXPECT_FALSE(std::filesystem::exists(output)) << signal;
    // the line names the command, the signal and what was removed
    const char* name = signal == SIGINT ? "SIGINT" : signal == SIGTERM ? "SIGTERM" : "SIGHUP";
    EXPECT_EQ(test::readText(errors), std::string("clothref trace: interrupted (") + name +
                                          "); removed the partial output " + temporary + "\n");
  }
}

// --scene /dev/zero used to grow to gigabytes: the file limit stops it, and the --max-* flags
// work before or after the command name.
TEST(FilesCli, EndlessInputStopsAtTheLimitSetByFlag) {
  for (const char* args : {"--max-file-bytes 100000 trace --scene /dev/zero",
                           "trace --scene /dev/zero --max-file-bytes 100000"}) {
    const test::CommandResult run = test::runCli(args);
    EXPECT_EQ(run.exit_code, 2) << run.output;
    EXPECT_EQ(run.output,
              "clothref: /dev/zero: larger than 100000 bytes (raise the limit with "
              "--max-file-bytes)\n");
  }
}

// A sanitizer build reserves terabytes of address space for its shadow memory: no address-space
// limit can be set under it.
#if defined(__SANITIZE_ADDRESS__)
#define CLOTHREF_ADDRESS_SPACE_LIMITS 0
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define CLOTHREF_ADDRESS_SPACE_LIMITS 0
#endif
#endif
#ifndef CLOTHREF_ADDRESS_SPACE_LIMITS
#define CLOTHREF_ADDRESS_SPACE_LIMITS 1
#endif

// Out of memory anywhere is one line and exit 2: a 100 MB trace header (its limit raised) parsed
// under a 512 MiB address-space limit, set in the forked child only. It used to end in
// "terminate called after throwing an instance of 'std::bad_alloc'" and SIGABRT: the JSON
// library's destructors allocate, so the bad_alloc could not reach the command's catch.
TEST(MainCli, OutOfMemoryIsOneLineAndExitTwo) {
  if (!CLOTHREF_ADDRESS_SPACE_LIMITS)
    GTEST_SKIP() << "a sanitizer build cannot run under RLIMIT_AS";
  const test::TempDir dir;
  const std::string trace = dir.file("t.jsonl");
  ASSERT_EQ(test::runCli("trace --scene spring --steps 2 -o " + trace).exit_code, 0);
  const std::string text = test::readText(trace);
  const std::size_t at = text.find("\"scene\":{") + 9;
  std::string big = text.substr(0, at) + "\"junk\":[";
  for (int i = 0; i < 50'000'000; ++i) big += "0,";
  big += "0]," + text.substr(at);
  test::writeText(dir.file("big.jsonl"), big);
  big.clear();
  big.shrink_to_fit();
  const test::ProcessResult run =
      test::runCliDirect({"diff", "--max-header-bytes", "1000000000", dir.file("big.jsonl"), trace},
                         dir.path(), "", 512ull << 20);
  EXPECT_EQ(run.exit_code, 2) << run.stderr_text;
  EXPECT_EQ(run.stderr_text, "clothref diff: out of memory\n");
  EXPECT_EQ(run.stdout_text, "");
}

// Bare `clothref` says where to look; a missing input file says why it did not open.
TEST(MainCli, BareClothrefPointsToHelpAndMissingFilesSayWhy) {
  const test::CommandResult bare = test::runCli("");
  EXPECT_EQ(bare.exit_code, 2);
  EXPECT_EQ(bare.output, "clothref: a command is needed (clothref --help lists them)\n");
  const test::TempDir dir;
  const test::CommandResult diff =
      test::runCli("diff " + dir.file("missing.jsonl") + " " + dir.file("other.jsonl"));
  EXPECT_EQ(diff.exit_code, 2);
  EXPECT_EQ(diff.output, "clothref: " + dir.file("missing.jsonl") +
                             ": cannot open the trace file (No such file or directory)\n");
}

}  // namespace
}  // namespace clothref
