// OutputFile: atomic replacement of regular files and new paths; direct writes to anything else.
#include "clothref/io/output_file.h"

#include <future>
#include <iterator>
#include <string>

#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include "test_util.h"

namespace clothref {
namespace {

TEST(OutputFile, NewPathAppearsOnlyOnCommit) {
  const test::TempDir dir;
  const std::string path = dir.file("out.txt");
  {
    OutputFile output(path);
    output.stream() << "hello";
    EXPECT_FALSE(std::filesystem::exists(path));
    output.commit();
  }
  EXPECT_EQ(test::readText(path), "hello");
}

TEST(OutputFile, UncommittedOutputLeavesTheOldFileAndNoTemporary) {
  const test::TempDir dir;
  const std::string path = dir.file("out.txt");
  test::writeLines(path, {"old"});
  {
    OutputFile output(path);
    output.stream() << "new";
  }
  EXPECT_EQ(test::readText(path), "old\n");
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
  EXPECT_EQ(test::readText(dir.file("target.txt")), "new");
}

// A FIFO stands for every node that is not a regular file (devices, sockets): it must be written
// in place and survive. (Tests never write to a real device path.)
TEST(OutputFile, FifoIsWrittenInPlaceNotReplaced) {
  const test::TempDir dir;
  const std::string path = dir.file("pipe");
  ASSERT_EQ(::mkfifo(path.c_str(), 0600), 0);
  auto reader = std::async(std::launch::async, [&] { return test::readText(path); });
  {
    OutputFile output(path);
    output.stream() << "through the pipe";
    output.commit();
  }
  EXPECT_EQ(reader.get(), "through the pipe");
  EXPECT_TRUE(test::isFifo(path));
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir.path()), {}), 1);
}

// A ".gz" path is written gzip-compressed, atomically like any other.
TEST(OutputFile, GzPathIsCompressed) {
  const test::TempDir dir;
  const std::string path = dir.file("out.txt.gz");
  {
    OutputFile out(path);
    for (int i = 0; i < 10000; ++i) out.stream() << "line " << i << '\n';
    out.commit();
  }
  const std::string bytes = test::readText(path);
  ASSERT_GE(bytes.size(), 2u);
  EXPECT_EQ(static_cast<unsigned char>(bytes[0]), 0x1f);
  EXPECT_EQ(static_cast<unsigned char>(bytes[1]), 0x8b);
  EXPECT_LT(bytes.size(), 30000u);  // 10000 lines of ~9 bytes, compressed
  const std::string command = "gzip -dc " + path + " | tail -n 1 > " + dir.file("last.txt");
  ASSERT_EQ(std::system(command.c_str()), 0);
  EXPECT_EQ(test::readText(dir.file("last.txt")), "line 9999\n");
}

}  // namespace
}  // namespace clothref
