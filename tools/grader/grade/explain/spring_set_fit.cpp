// The spring-set model (grader/grade/explain/spring_set_fit.h).
#include "grader/grade/explain/spring_set_fit.h"

#include <algorithm>
#include <cmath>
#include <set>

#include "grader/grade/explain/compare_text.h"

namespace clothref::grader {

int springFamily(std::pair<int, int> pair, int n) {
  const int di = pair.second / n - pair.first / n, dj = pair.second % n - pair.first % n;
  if (di == 0 && dj == 1) return 0;
  if (di == 1 && dj == 0) return 1;
  if (di == 1 && dj == 1) return 2;
  if (di == 1 && dj == -1) return 3;
  if (di == 0 && dj == 2) return 4;
  if (di == 2 && dj == 0) return 5;
  return -1;
}

SpringModel fitSpringModel(const SpringSet& student, const SpringSet& reference, int n) {
  SpringModel m;
  std::array<int, 6> present{}, total{};
  std::array<std::set<int>, 6> counts;
  std::array<std::vector<double>, 3> ratios;
  std::array<std::map<int, int>, 3> labels;
  for (const auto& [pair, entries] : reference.pairs) {
    const int f = springFamily(pair, n);
    if (f < 0) continue;
    ++total[std::size_t(f)];
    auto it = student.pairs.find(pair);
    if (it == student.pairs.end()) continue;
    ++present[std::size_t(f)];
    counts[std::size_t(f)].insert(int(it->second.size()));
    const int type = entries.front().second;
    ratios[std::size_t(type)].push_back(double(it->second.front().first) /
                                        double(entries.front().first));
    ++labels[std::size_t(type)][it->second.front().second];
  }
  static const char* families[] = {"structural along a row", "structural along a column",
                                   "shear down-right",       "shear down-left",
                                   "bend along a row",       "bend along a column"};
  for (std::size_t f = 0; f < 6; ++f) {
    m.missing[f] = total[f] > 0 && present[f] == 0;
    if (m.missing[f]) m.changes.push_back(std::string("without the ") + families[f] + " springs");
    if (counts[f].size() == 1 && *counts[f].begin() > 1) {
      m.copies[f] = *counts[f].begin();
      m.changes.push_back(std::string("with the ") + families[f] + " springs pushed " +
                          std::to_string(m.copies[f]) + " times");
    }
  }
  for (std::size_t t = 0; t < 3; ++t) {
    if (!ratios[t].empty()) {
      std::sort(ratios[t].begin(), ratios[t].end());
      const double r = ratios[t][ratios[t].size() / 2];
      if (std::abs(r - 1) > 1e-7) {
        m.rest_ratio[t] = r;
        m.changes.push_back(std::string("with the ") + kSpringTypeNames[t] + " rest length times " +
                            util::num(r));
      }
    }
    int best = int(t), votes = 0;
    for (const auto& [label, count] : labels[t])
      if (count > votes) best = label, votes = count;
    if (best != int(t)) {
      m.label[t] = best;
      m.changes.push_back(std::string("with the ") + kSpringTypeNames[t] + " springs labelled " +
                          (best >= 0 && best < 3 ? kSpringTypeNames[best] : "?"));
    }
  }
  return m;
}

SpringSet modelSprings(const SpringModel& m, const SpringSet& reference, int n) {
  SpringSet set;
  for (const auto& [pair, entries] : reference.pairs) {
    const int f = springFamily(pair, n);
    if (f >= 0 && m.missing[std::size_t(f)]) continue;
    const int copies = f >= 0 ? m.copies[std::size_t(f)] : 1;
    for (const auto& [rest, type] : entries)
      for (int c = 0; c < copies; ++c) {
        set.pairs[pair].push_back(
            {float(double(rest) * m.rest_ratio[std::size_t(type)]), m.label[std::size_t(type)]});
        ++set.count;
      }
  }
  return set;
}

std::string springModelText(const SpringModel& m) {
  std::string text = "the course's springs";
  for (std::size_t k = 0; k < m.changes.size(); ++k)
    text += (k == 0 ? " " : " and ") + m.changes[k];
  return text;
}

}  // namespace clothref::grader
