#include "grader/grade/confinement.h"

#include <algorithm>
#include <string>

#include "clothref/io/error.h"
#include "grader/grade/run/uid_lease.h"
#include "grader/grade/submission/neighbours.h"
#include "grader/grade/text.h"

namespace clothref::grader {
namespace fs = std::filesystem;

Isolation isolationFor(const CourseToolchain& toolchain, const std::vector<fs::path>& private_paths,
                       const fs::path& submission) {
  Isolation isolation = detectIsolation();
  if (isolation.uid >= 0) {
    const UidLease lease = leaseUids();
    isolation.uid = lease.uid;
    isolation.tool_uid = lease.tool_uid;
    isolation.uid_lease = lease.hold;
  }
  isolation.ours = ourFolders(toolchain);
  for (const fs::path& path : private_paths)
    isolation.ours.push_back(fs::absolute(path).lexically_normal());
  // A single grade covers its neighbours as a batch does (another submission beside this one).
  const bool can_cover = isolation.kind == IsolationKind::Bubblewrap || isolation.private_mounts;
  for (const fs::path& path : neighbours(submission, can_cover)) isolation.ours.push_back(path);
  // Outermost only: a folder inside another is covered with it (and could not be mounted on once
  // the outer one is covered).
  std::vector<fs::path> outermost;
  for (const fs::path& path : isolation.ours) {
    bool inside = false;
    for (const fs::path& other : isolation.ours)
      inside = inside || (other != path && isUnder(path, other));
    if (!inside && std::find(outermost.begin(), outermost.end(), path) == outermost.end())
      outermost.push_back(path);
  }
  isolation.ours = outermost;
  return isolation;
}

void checkConfinement(const Isolation& isolation, const GradeScratch& scratch,
                      const CourseKit* kit) {
  if (isolation.uid < 0) return;
  std::error_code error;
  const fs::path temp = fs::temp_directory_path(error);
  for (const fs::path& folder : isolation.ours)
    for (const fs::path& ours : {scratch.root(), kit ? kit->root : fs::path()})
      if (!ours.empty() && isUnder(fs::weakly_canonical(ours, error), folder))
        throw InputError("TMPDIR (" + safeName(temp.string()) + ") is inside " +
                         safeName(folder.string()) +
                         ", which student code must not see: set TMPDIR to another folder");
  for (const int uid : {isolation.uid, isolation.tool_uid})
    if (!readableAs(uid, {scratch.root()}, nullptr) &&
        firstReachableAs(uid, {scratch.root()}).empty())
      throw InputError("TMPDIR (" + safeName(temp.string()) + ") cannot be reached by uid " +
                       std::to_string(uid) +
                       " (a folder on its path is closed to other users): set TMPDIR to a "
                       "folder every user may pass through, such as /tmp");
  if (isolation.kind == IsolationKind::Bubblewrap || isolation.private_mounts) return;
  for (const int uid : {isolation.uid, isolation.tool_uid}) {
    const std::string open = firstReachableAs(uid, isolation.ours);
    if (!open.empty())
      throw InputError(safeName(open) + " can be read by uid " + std::to_string(uid) +
                       ", which runs student code, and this machine allows no private mount "
                       "namespace to cover it: make it unreadable to other users (chmod o-rwx), "
                       "as the Gradescope set-up does");
  }
}

}  // namespace clothref::grader
