// The object cache's key: another compiler version or another isolation is another object.
#include "grader/grade/run/build.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <set>

#include "test_util.h"

namespace clothref::grader {
namespace {

// An object compiled unconfined may hold host bytes (`.incbin "/etc/shadow"`): a confined run
// must never reuse it; nor may a run with another compiler version reuse another's objects.
TEST(ObjectCachePath, DependsOnTheIsolationAndTheCompilerVersion) {
  test::TempDir temp;
  test::writeText(temp.path() / "a.cpp", "int a;\n");
  for (const char* version : {"1", "2"}) {
    const std::filesystem::path compiler = temp.path() / (std::string("cc-") + version);
    test::writeText(compiler, std::string("#!/bin/sh\necho fake compiler ") + version + "\n");
    std::filesystem::permissions(compiler, std::filesystem::perms::owner_all);
  }
  CourseToolchain toolchain = defaultToolchain();
  toolchain.cache_dir = temp.path() / "cache";
  toolchain.compiler = (temp.path() / "cc-1").string();
  // The same command line (the cache hashes its flags): only the version query tells them apart.
  const std::vector<std::string> command = {"cc", "-O2", "-c", (temp.path() / "a.cpp").string(),
                                            "-o", "a.o"};
  const auto key = [&] {
    return objectCachePath(toolchain, command, temp.path() / "a.cpp", temp.path());
  };
  const std::filesystem::path none = key();
  EXPECT_EQ(key(), none);  // a key, not a random name
  toolchain.isolation.kind = IsolationKind::Rlimits;
  const std::filesystem::path rlimits = key();
  toolchain.isolation.tool_uid = kToolUid;
  const std::filesystem::path confined = key();
  toolchain.isolation.kind = IsolationKind::Bubblewrap;
  const std::filesystem::path boxed = key();
  toolchain.compiler = (temp.path() / "cc-2").string();
  const std::filesystem::path other_compiler = key();
  const std::set<std::filesystem::path> keys = {none, rlimits, confined, boxed, other_compiler};
  EXPECT_EQ(keys.size(), 5u);
}

// Work that does not depend on the student's bytes is never repeated: the build made our
// reference objects (build/grader-prebuilt), so a submission whose files are byte for byte ours,
// or missing, links them without running a compiler, even with no object cache.
TEST(BuildProbes, ReferenceObjectsComeFromThePrebuiltFolder) {
  CourseToolchain toolchain = defaultToolchain();
  ASSERT_FALSE(toolchain.prebuilt_dir.empty());
  ASSERT_TRUE(std::filesystem::is_directory(toolchain.prebuilt_dir)) << toolchain.prebuilt_dir;
  toolchain.cache_dir.clear();
  SubmissionFiles files;
  for (const char* name : {"sphere.cpp", "integrator.cpp"}) {  // cloth.cpp missing
    files.found[name] = toolchain.reference_dir / "2022" / name;
    files.bytes[name] = test::readText(files.found[name]);
  }
  const test::TempDir work;
  const ProbeBuild build = buildProbes(files, 2022, toolchain, work.path());
  ASSERT_TRUE(build.ok) << build.problem;
  ASSERT_EQ(build.files.size(), 3u);
  EXPECT_EQ(build.files[0].problem, "missing");
  for (std::size_t k = 1; k < 3; ++k) {
    EXPECT_TRUE(build.files[k].compiled) << build.files[k].name << ": " << build.files[k].problem;
    EXPECT_EQ(build.files[k].compile_seconds, 0.0) << build.files[k].name << " was compiled";
  }
}

}  // namespace
}  // namespace clothref::grader
