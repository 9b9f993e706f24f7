// What a student's initializeSpring made, read back as a model (issue 38, "likely means proven"):
// the course's springs with whole grid families left out or pushed more than once, each type's
// rest length scaled and its label changed. Fitted from the student's springs at the course's
// size, then replayed (explain/replay.h) at both sizes by the springs probe.
//
// Plain data and free functions, no probe: the sets come from the probe (the student's) and the
// library's initializeSpring (the course's).
#pragma once
#include <array>
#include <map>
#include <string>
#include <utility>
#include <vector>

namespace clothref::grader {

// The course's spring types by their number (SpringType: 0, 1, 2).
inline constexpr const char* kSpringTypeNames[] = {"STRUCTURAL", "SHEAR", "BEND"};

// The springs of one cloth, by the pair of particles they join.
struct SpringSet {
  // (lower index, higher index) -> every (rest length (m), type) pushed for that pair.
  std::map<std::pair<int, int>, std::vector<std::pair<float, int>>> pairs;
  int count = 0;
};

// The grid family of a pair of an n x n cloth, in the order of the library's grid springs:
// 0 structural along a row, 1 along a column, 2 shear down-right, 3 shear down-left, 4 bend
// along a row, 5 along a column; -1 for a pair that is no grid neighbour.
int springFamily(std::pair<int, int> pair, int n);

struct SpringModel {
  std::array<bool, 6> missing{};                // per family: none of its springs
  std::array<int, 6> copies{1, 1, 1, 1, 1, 1};  // per family: each spring pushed this often
  std::array<double, 3> rest_ratio{1, 1, 1};    // per type: the student's rest / the course's
  std::array<int, 3> label{0, 1, 2};            // per type: the student's label of it
  std::vector<std::string> changes;             // the above in words, one per change
};

// The model that best gives `student` from the course's `reference` on an n x n cloth (medians
// and majorities per family and type).
SpringModel fitSpringModel(const SpringSet& student, const SpringSet& reference, int n);

// The springs `m` makes from the course's `reference` springs of an n x n cloth.
SpringSet modelSprings(const SpringModel& m, const SpringSet& reference, int n);

// "the course's springs without the shear down-left springs and with ...".
std::string springModelText(const SpringModel& m);

}  // namespace clothref::grader
