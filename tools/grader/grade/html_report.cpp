#include "html_report.h"

#include <algorithm>
#include <fstream>
#include <map>
#include <sstream>

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

std::string batchIndexHtml(const fs::path& batch_dir, const std::vector<BatchRow>& rows) {
  nlohmann::ordered_json data;
  data["stubs"] = stubNames();
  std::vector<std::string> checks;           // every check name, in order of first appearance
  std::map<std::string, std::size_t> index;  // check name -> position in `checks`
  nlohmann::ordered_json submissions = nlohmann::ordered_json::array();
  for (const BatchRow& row : rows) {
    nlohmann::ordered_json s;
    s["name"] = row.name;
    s["edition"] = row.edition;
    s["stub_scores"] = row.stub_score;
    s["stub_max"] = row.stub_max;
    s["total"] = row.score;
    s["max"] = row.max_score;
    s["verdict"] = row.verdict;
    s["problem"] = row.problem;
    s["seconds"] = row.seconds;
    std::error_code error;
    s["report"] =
        row.name +
        (fs::exists(batch_dir / row.name / "report.html", error) ? "/report.html" : "/report.md");
    // per check: passed, failed; the named causes (a test's tags after its stub)
    nlohmann::ordered_json passed = nlohmann::ordered_json::object();
    std::vector<std::string> causes;
    const nlohmann::json results = readResults(batch_dir / row.name / "results.json");
    if (results.is_object() && results.contains("tests") && results["tests"].is_array())
      for (const auto& test : results["tests"]) {
        if (!test.is_object() || !test.contains("name") || !test["name"].is_string()) continue;
        const std::string name = test["name"].get<std::string>();
        if (!index.count(name)) {
          index[name] = checks.size();
          checks.push_back(name);
        }
        passed[std::to_string(index[name])] = test.value("status", "") == "passed";
        if (test.contains("tags") && test["tags"].is_array())
          for (std::size_t k = 1; k < test["tags"].size(); ++k)
            if (test["tags"][k].is_string()) {
              const std::string cause = test["tags"][k].get<std::string>();
              if (std::find(causes.begin(), causes.end(), cause) == causes.end())
                causes.push_back(cause);
            }
      }
    s["checks"] = passed;
    s["causes"] = causes;
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
