// OutputFile: atomic replacement of regular files and new paths; direct writes to anything else.
#include "clothref/io/output_file.h"

#include <fstream>
#include <future>
#include <iterator>
#include <string>

#include <gtest/gtest.h>
#include <sys/stat.h>

#include "test_util.h"

namespace clothref {
namespace {

std::string readAll(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

bool isFifo(const std::string& path) {
  struct stat info {};
  return ::lstat(path.c_str(), &info) == 0 && S_ISFIFO(info.st_mode);
}

TEST(OutputFile, NewPathAppearsOnlyOnCommit) {
  const test::TempDir dir;
  const std::string path = dir.file("out.txt");
  {
    OutputFile output(path);
    output.stream() << "hello";
    EXPECT_FALSE(std::filesystem::exists(path));
    output.commit();
  }
  EXPECT_EQ(readAll(path), "hello");
}

TEST(OutputFile, UncommittedOutputLeavesTheOldFileAndNoTemporary) {
  const test::TempDir dir;
  const std::string path = dir.file("out.txt");
  test::writeLines(path, {"old"});
  {
    OutputFile output(path);
    output.stream() << "new";
  }
  EXPECT_EQ(readAll(path), "old\n");
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir.path()), {}), 1);
}

TEST(OutputFile, SymbolicLinkKeepsTheLinkAndReplacesItsTarget) {
  const test::TempDir dir;
  test::writeLines(dir.file("target.txt"), {"old"});
  std::filesystem::create_symlink(dir.file("target.txt"), dir.file("link.txt"));
  {
    OutputFile output(dir.file("link.txt"));
    output.stream() << "new";
    output.commit();
  }
  EXPECT_TRUE(std::filesystem::is_symlink(dir.file("link.txt")));
  EXPECT_EQ(readAll(dir.file("target.txt")), "new");
}

// A FIFO stands for every node that is not a regular file (devices, sockets): it must be written
// in place and survive. (Tests never write to a real device path.)
TEST(OutputFile, FifoIsWrittenInPlaceNotReplaced) {
  const test::TempDir dir;
  const std::string path = dir.file("pipe");
  ASSERT_EQ(::mkfifo(path.c_str(), 0600), 0);
  auto reader = std::async(std::launch::async, [&] { return readAll(path); });
  {
    OutputFile output(path);
    output.stream() << "through the pipe";
    output.commit();
  }
  EXPECT_EQ(reader.get(), "through the pipe");
  EXPECT_TRUE(isFifo(path));
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir.path()), {}), 1);
}

TEST(OutputFileCli, TraceIntoAFifoKeepsTheFifo) {
  const test::TempDir dir;
  const std::string path = dir.file("pipe");
  ASSERT_EQ(::mkfifo(path.c_str(), 0600), 0);
  auto reader = std::async(std::launch::async, [&] { return readAll(path); });
  const auto result = test::runCli("trace --scene free-fall --steps 3 -o " + path);
  EXPECT_EQ(result.exit_code, 0) << result.output;
  const std::string text = reader.get();
  EXPECT_EQ(text.rfind("{\"format\":\"clothref-trace\"", 0), 0u) << text.substr(0, 80);
  EXPECT_TRUE(isFifo(path));
}

}  // namespace
}  // namespace clothref
