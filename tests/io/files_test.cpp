// Whole-file reads with a size limit, and scratch directories that clean up after themselves.
#include "clothref/io/files.h"

#include <fstream>

#include <gtest/gtest.h>

#include "clothref/io/error.h"
#include "test_util.h"

namespace clothref {
namespace {

TEST(Files, ReadFileReturnsTheBytes) {
  const test::TempDir dir;
  std::ofstream(dir.file("a"), std::ios::binary) << std::string("x\0y\r\n", 5);
  EXPECT_EQ(readFile(dir.file("a"), "test file"), std::string("x\0y\r\n", 5));
}

TEST(Files, ReadFileRefusesPastItsLimitAndNamesMissingFiles) {
  const test::TempDir dir;
  std::ofstream(dir.file("big")) << std::string(1000, 'a');
  EXPECT_THROW(readFile(dir.file("big"), "test file", 999), InputError);
  EXPECT_EQ(readFile(dir.file("big"), "test file", 1000).size(), 1000u);
  try {
    readFile(dir.file("missing"), "scene file");
    ADD_FAILURE();
  } catch (const InputError& error) {
    EXPECT_EQ(std::string(error.what()),
              dir.file("missing") + ": cannot read the scene file (No such file or directory)");
  }
}

TEST(Files, ScratchDirIsFreshAndRemovedWithItsContents) {
  std::filesystem::path kept;
  {
    const ScratchDir a("clothref-test"), b("clothref-test");
    EXPECT_NE(a.path(), b.path());
    EXPECT_TRUE(std::filesystem::is_directory(a.path()));
    std::ofstream(a.path() / "file") << "x";
    kept = a.path();
  }
  EXPECT_FALSE(std::filesystem::exists(kept));
}

}  // namespace
}  // namespace clothref
