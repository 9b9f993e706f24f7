// The probe driver: the child process's main, linked with the student's three object files and
// our framework definitions. It reads one ProbeMessage (the probe group and its inputs) from
// stdin, calls the student's stubs of that group, and writes one ProbeMessage with the outputs to
// fd 3. It never computes a score or a reference result: those live in the grader process.
//
// The groups it serves are the rows of kGroups below, one per name of bridge/probe_keys.h, each
// group's course side a header of groups/ that the build finds (groups.inc, generated); a request
// for another group, or for a method that is not one of the course's integrators, is refused:
// nothing on fd 3, the reason on stderr, exit 70.
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <iostream>
#include <iterator>
#include <string>
#include <utility>

#include "grader/driver/driver_support.h"
// every header of driver/groups/, listed by the build (tools/grader/CMakeLists.txt)
#include "grader/driver/groups.inc"

namespace {

// The groups served, by the protocol's group name: the one dispatch of the driver, a row per name
// of the protocol's list (bridge/probe_keys.h), each calling probe<Name> of its header in groups/
// (a name whose function no header defines does not build).
struct Group {
  const char* name;
  void (*run)(const ProbeMessage& in, ProbeMessage& out);
};
#define CLOTHREF_PROBE_SERVED(identifier, text, name) {group::identifier, probe##name},
constexpr Group kGroups[] = {CLOTHREF_PROBE_GROUPS(CLOTHREF_PROBE_SERVED)};
#undef CLOTHREF_PROBE_SERVED

// Runs the row named `name`; false when no row is. Unrolled over the rows, so that each call is
// a direct call the compiler may inline, as a hand-written chain's would be (a crash report
// quotes the same driver frames as before the table).
template <std::size_t... row>
bool serve(const std::string& name, const ProbeMessage& in, ProbeMessage& out,
           std::index_sequence<row...>) {
  return ((name == kGroups[row].name && (kGroups[row].run(in, out), true)) || ...);
}

bool writeAll(int fd, const std::string& data) {
  size_t done = 0;
  while (done < data.size()) {
    const ssize_t n = ::write(fd, data.data() + done, data.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    done += static_cast<size_t>(n);
  }
  return true;
}

}  // namespace

int main() {
  std::string request((std::istreambuf_iterator<char>(std::cin)), std::istreambuf_iterator<char>());
  const auto in = probe::decodeMessage(request);
  if (!in) {
    std::fprintf(stderr, "probe driver: malformed request\n");
    return 70;
  }
  ProbeMessage out;
  out.nonce = in->nonce;
  const std::string name = in->text(key::kGroup);
  try {
    if (!serve(name, *in, out, std::make_index_sequence<std::size(kGroups)>()))
      throw BadRequest{"unknown group '" + name + "'"};
  } catch (const BadRequest& bad) {
    std::fprintf(stderr, "probe driver: %s\n", bad.why.c_str());
    return 70;
  }
  out.texts[key::kGroup] = name;
  return writeAll(probe::kResultFd, probe::encodeMessage(out)) ? 0 : 71;
}
