// BATCHDIR/index.html, the class at a glance (class_page.h).
#include "grader/grade/report/class_page.h"

#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "pages/html.h"
#include "pages/page_assets.h"

namespace clothref::grader {

namespace fs = std::filesystem;

namespace {

// results.json of a batch folder, or null when it is missing or not JSON (a half-written folder
// of an interrupted batch has a row.json only if its results were written first).
nlohmann::json readResults(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return nullptr;
  std::stringstream text;
  text << in.rdbuf();
  return nlohmann::json::parse(text.str(), nullptr, false);
}

}  // namespace

std::vector<ClassRow> classRows(const fs::path& batch_dir, const std::vector<BatchRow>& rows) {
  std::vector<ClassRow> out;
  for (const BatchRow& row : rows) {
    ClassRow c;
    c.name = row.name;
    c.edition = row.edition;
    c.stub_score = row.stub_score;
    c.stub_max = row.stub_max;
    c.score = row.score;
    c.max_score = row.max_score;
    c.verdict = row.verdict;
    c.problem = row.problem;
    c.seconds = row.seconds;
    std::error_code error;
    c.report =
        row.name +
        (fs::exists(batch_dir / row.name / "report.html", error) ? "/report.html" : "/report.md");
    const auto name_cause = [&](const std::string& id, bool likely) {
      for (auto& [known, was_likely] : c.causes)
        if (known == id) {
          was_likely = was_likely || likely;
          return;
        }
      c.causes.push_back({id, likely});
    };
    const nlohmann::json results = readResults(batch_dir / row.name / "results.json");
    if (results.is_object() && results.contains("tests") && results["tests"].is_array())
      for (const auto& test : results["tests"]) {
        if (!test.is_object() || !test.contains("name") || !test["name"].is_string()) continue;
        c.checks.push_back({test["name"].get<std::string>(), test.value("status", "") == "passed"});
        const nlohmann::json* listed = nullptr;
        if (test.contains("extra_data") && test["extra_data"].is_object() &&
            test["extra_data"].contains("causes") && test["extra_data"]["causes"].is_array())
          listed = &test["extra_data"]["causes"];
        if (listed) {
          for (const auto& cause : *listed)
            if (cause.is_object() && cause.contains("id") && cause["id"].is_string())
              name_cause(cause["id"].get<std::string>(), cause.value("likely", true));
        } else if (test.contains("tags") && test["tags"].is_array()) {
          for (std::size_t k = 1; k < test["tags"].size(); ++k)
            if (test["tags"][k].is_string()) name_cause(test["tags"][k].get<std::string>(), true);
        }
      }
    out.push_back(std::move(c));
  }
  return out;
}

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
  return pages::fillTemplate(pages::pageAsset("class.html"),
                             {{"STYLE", std::string(pages::pageAsset("viewer.css"))},
                              {"SCRIPT", std::string(pages::pageAsset("class.js"))},
                              {"DATA", pages::jsonForScript(data)}});
}

}  // namespace clothref::grader
