// Where a compile's object comes from before the compiler runs: the keys of the object cache (the
// flags, the source's and the stand-in headers' bytes, the compiler's identity, the confinement),
// the objects prebuilt with clothref, and the edition's precompiled stand-in headers.
#pragma once
#include <filesystem>
#include <string>
#include <vector>

#include "grader/grade/run/build.h"

namespace clothref::grader {

// The flags every compile of course code starts with (the compiler first).
std::vector<std::string> baseFlags(const CourseToolchain& t);

// Unique among the threads of this process: temporary files carry it beside the pid.
std::string uniqueSuffix();

// The cache file for a compile command (`trusted`: our own reference files, keyed without the
// confinement so the prebuilt objects serve every isolation).
std::filesystem::path cachePath(const CourseToolchain& t, const std::vector<std::string>& command,
                                const std::filesystem::path& source,
                                const std::filesystem::path& work_dir, bool trusted);

// The edition's precompiled stand-in headers (the `-include` file), or none.
std::filesystem::path precompiledHeader(const CourseToolchain& t, int edition,
                                        const std::filesystem::path& work_dir);

// A stored object (prebuilt or cached) copied into a build folder, readable by the link's uid.
bool copyObject(const std::filesystem::path& from, const std::filesystem::path& object);

// The object of `command` taken from the set prebuilt with clothref, when it has it.
bool fromPrebuilt(const CourseToolchain& t, const std::vector<std::string>& command,
                  const std::filesystem::path& source, const std::filesystem::path& object);

}  // namespace clothref::grader
