// BATCHDIR/index.html, the class at a glance (class_page.h).
#include "grader/grade/report/class_page.h"

#include <algorithm>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "pages/html.h"
#include "pages/page_assets.h"

namespace clothref::grader {

std::string batchIndexHtml(const std::vector<ClassRow>& rows) {
  nlohmann::ordered_json data;
  data["stubs"] = stubNames();
  std::vector<std::string> checks;           // every check name, in order of first appearance
  std::map<std::string, std::size_t> index;  // check name -> position in `checks`
  nlohmann::ordered_json submissions = nlohmann::ordered_json::array();
  for (const ClassRow& row : rows) {
    nlohmann::ordered_json s;
    s["submission"] = row.name;
    s["edition"] = row.edition;
    s["stub_scores"] = row.stub_score;
    s["stub_max"] = row.stub_max;
    s["total"] = row.score;
    s["max"] = row.max_score;
    s["verdict"] = verdictId(row.verdict);
    s["problem"] = row.problem;
    s["seconds"] = row.seconds;
    s["report"] = row.report;
    // per check: passed, failed (by its position in `checks`)
    nlohmann::ordered_json passed = nlohmann::ordered_json::object();
    for (const auto& [name, ok] : row.checks) {
      if (!index.count(name)) {
        index[name] = checks.size();
        checks.push_back(name);
      }
      passed[std::to_string(index[name])] = ok;
    }
    nlohmann::ordered_json cause_list = nlohmann::ordered_json::array();
    for (const auto& [id, likely] : row.causes)
      cause_list.push_back({{"id", id}, {"likely", likely}});
    s["checks"] = passed;
    s["causes"] = cause_list;
    submissions.push_back(s);
  }
  data["checks"] = checks;
  data["submissions"] = submissions;
  std::vector<std::string> isolation;  // each description once, in the rows' order
  for (const ClassRow& row : rows)
    if (!row.isolation.empty() &&
        std::find(isolation.begin(), isolation.end(), row.isolation) == isolation.end())
      isolation.push_back(row.isolation);
  data["isolation"] = isolation;
  return pages::fillTemplate(pages::pageAsset("class.html"),
                             {{"STYLE", std::string(pages::pageAsset("viewer.css"))},
                              {"SCRIPT", std::string(pages::pageAsset("class.js"))},
                              {"DATA", pages::jsonForScript(data)}});
}

}  // namespace clothref::grader
