// The folders student code touches, and who may read them (docs/grading-reference.md, "Sandbox"):
// one grade's scratch folder, laid out so that each part belongs to the uid that needs it and to no
// other student; the course kit, the only files of ours that compiles of student code read; and
// the link-proof tree operations the grader uses on folders a student process could write into
// (copy, remove, measure), which never follow a symbolic link.
#pragma once
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace clothref::grader {

// One grade's scratch folder under TMPDIR (removed with everything in it when this goes):
//   <root>/           root's, 0711: the uids of this grade pass through, nobody lists it
//   <root>/build/     the tool uid's, 0700: the copied sources, the objects, the linked probes
//   <root>/bin/       root's, 0711: the probes as they run, root:<probe gid> 0550 (the probe uid
//                     may run them, not change them; no other student may read them)
//   <root>/probes/    root's, 0711: one folder per probe group (root's, 0711) holding the
//                     request, stdout and stderr (0600), and sandbox/, the probe uid's own (0700)
// Without uids (the grader is not root) every folder is the grader's, 0700.
class GradeScratch {
 public:
  GradeScratch(int probe_uid, int tool_uid);
  ~GradeScratch();
  GradeScratch(const GradeScratch&) = delete;
  GradeScratch& operator=(const GradeScratch&) = delete;

  const std::filesystem::path& root() const { return root_; }
  std::filesystem::path build() const { return root_ / "build"; }
  std::filesystem::path bin() const { return root_ / "bin"; }
  std::filesystem::path probes() const { return root_ / "probes"; }

  // Copies the linked probe `built` (in build/) to bin/<name> (default: its own name), runnable
  // by the probe uid only.
  std::filesystem::path publish(const std::filesystem::path& built,
                                const std::string& name = "") const;

  // Another folder like build/ (the tool uid's, 0700), e.g. for the sanitizer's second build.
  std::filesystem::path extraBuild(const std::string& name) const;

 private:
  std::filesystem::path root_;
  int probe_uid_, tool_uid_;
};

// The only files of ours a compile or link of student code may read, gathered in one folder per
// grader process (root's, 0755; removed at exit): copies of the stand-in headers and of the probe
// driver libraries, and the precompiled stand-in headers (hard links where the file system
// allows, else copies). Everything else of ours (the reference files and objects, the library's
// sources, the build, the cache) may then stay where no student uid can read it.
struct CourseKit {
  std::filesystem::path root;
  std::filesystem::path course_dir;  // copy of tools/grader/course
  std::filesystem::path lib_dir;     // copies of libclothref_grader_course_<edition>.a
};
// The kit for these course and driver folders (made on first use, once per process).
const CourseKit& courseKit(const std::filesystem::path& course_dir,
                           const std::filesystem::path& driver_lib_dir);
// The kit's copy of the precompiled header whose `-include` file is `header` (made on first use).
std::filesystem::path kitHeader(const CourseKit& kit, const std::filesystem::path& header);

// Removes `path` and everything below it without following a symbolic link (a link is removed,
// never what it points to); folders a student made unreadable are opened as root anyway. True
// when it is gone.
bool removeTree(const std::filesystem::path& path);

// Copies the tree `from` to `to` (made if missing) without following a symbolic link: folders
// and regular files only, at most `max_bytes` in all; every entry it leaves out (a link, a
// device, what is past the limit) is named in `skipped`. Returns the bytes copied.
std::uint64_t copyTree(const std::filesystem::path& from, const std::filesystem::path& to,
                       std::uint64_t max_bytes, std::vector<std::string>* skipped);

// Bytes (rounded up to 4 KiB blocks, at least one per entry) of everything below `path` whose
// owner is `uid` (any owner when `uid` < 0), links not followed; entries count too, so a million
// empty files is not free. The count stops soon after it passes `stop_after`.
std::uint64_t bytesBelow(const std::filesystem::path& path, int uid = -1,
                         std::uint64_t stop_after = ~std::uint64_t{0} >> 1);

// The folders every process may write into (TMPDIR's, /tmp, /var/tmp, /dev/shm, /run/lock, and
// any other folder open to every user within three levels of /, found once per process): where a
// student process could leave files outside its own folder. The fallback makes each a private
// filesystem of its runs where it can, and counts and removes what a grade's uids leave in them.
const std::vector<std::filesystem::path>& sharedTemporaryFolders();

// Bytes of the top-level entries of `folders` owned by `uid`, and their removal (without
// following links).
std::uint64_t bytesOwnedBy(int uid, const std::vector<std::filesystem::path>& folders);
void removeOwnedBy(int uid, const std::vector<std::filesystem::path>& folders);

}  // namespace clothref::grader
