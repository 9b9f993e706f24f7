// Where a compile's object comes from before the compiler runs: the keys of the object cache (the
// flags, the source's and the stand-in headers' bytes, the compiler's identity, the confinement),
// the objects prebuilt with clothref, and the edition's precompiled stand-in headers; and the
// steps every probe build shares (the whole build and the one-file sanitizer rebuild): the compile
// and link commands and compiles through that cache.
#pragma once
#include <filesystem>
#include <string>
#include <vector>

#include "grader/grade/run/build.h"
#include "grader/grade/run/tools.h"

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

// The compile of one course file for `edition` (a cloth of `particles_per_edge` squared particles;
// 25 is the course's), with the precompiled header `pch` when given.
std::vector<std::string> compileCommand(const CourseToolchain& t, int edition,
                                        const std::filesystem::path& source,
                                        const std::filesystem::path& object, int particles_per_edge,
                                        const std::filesystem::path& pch = {});

// A compile or link the grader could not run (ToolRun::ours): the grade stops as ours.
const ToolRun& checked(const ToolRun& run);

// Runs the compile commands, taking objects from the cache where it has them and filling it.
std::vector<ToolRun> compileAll(const CourseToolchain& t,
                                const std::vector<std::vector<std::string>>& commands,
                                const std::filesystem::path& work_dir);

// Our own reference files and helpers are compiled with the grader's uid, unconfined (only it may
// read them), and keyed as the objects prebuilt with clothref are.
CourseToolchain oursOf(const CourseToolchain& toolchain);

// The object holding the sanitizer's defaults, compiled into `work_dir` (prebuilt with clothref,
// cached, or compiled here); empty when it fails.
std::filesystem::path sanitizerOptionsObject(const CourseToolchain& toolchain,
                                             const std::filesystem::path& work_dir);

// The link of a probe: the objects in order, the driver library last; with the sanitizer's flag
// and defaults for a sanitized build.
std::vector<std::string> linkCommand(const CourseToolchain& toolchain, int edition,
                                     const std::vector<std::filesystem::path>& objects,
                                     const std::filesystem::path& sanitizer_options,
                                     const std::filesystem::path& out);

// Paths a compile or link in the scratch folder gets are absolute.
CourseToolchain absolutePaths(const CourseToolchain& given);

}  // namespace clothref::grader
