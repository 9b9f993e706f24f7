// A batch's row (one submission's line of grades.csv, and its row.json marker) as data: made from
// a report, written as JSON and CSV, read back from JSON.
#include <algorithm>
#include <fstream>
#include <sstream>

#include "clothref/io/error.h"
#include "clothref/io/json_input.h"
#include "grader/grade/batch.h"
#include "grader/grade/report/outputs.h"
#include "grader/grade/text.h"

namespace clothref::grader {

namespace fs = std::filesystem;

namespace {

std::string csvField(const std::string& given) {
  const std::string text = safeName(given);  // valid UTF-8, one line, no terminal escapes
  if (text.find_first_of(",\"") == std::string::npos) return text;
  std::string out = "\"";
  for (char c : text) out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
}

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

BatchRow rowOf(const BatchEntry& entry, const GradeReport& report) {
  BatchRow row;
  row.name = entry.name;
  row.dir = safeName(entry.dir.string());
  row.edition = report.edition;
  row.stub_score = report.stub_score;
  row.stub_max = report.stub_max;
  row.score = report.score;
  row.max_score = report.max_score;
  row.verdict = report.verdict;
  row.isolation = safeName(report.isolation);
  row.seconds = report.seconds.count("total") ? report.seconds.at("total") : 0;
  // the causes of its failed checks as every output names them (cleaned: outputs.h), each once,
  // likely when a check names it as likely
  for (const TestResult& t : cleaned(report).tests) {
    if (t.passed() || t.informational) continue;
    for (const Cause& cause : t.causes) {
      auto it = std::find_if(row.causes.begin(), row.causes.end(),
                             [&](const auto& named) { return named.first == cause.id; });
      if (it == row.causes.end())
        row.causes.push_back({cause.id, cause.likely});
      else
        it->second = it->second || cause.likely;
    }
  }
  return row;
}

nlohmann::ordered_json rowJson(const BatchRow& row) {
  nlohmann::ordered_json json;
  json["submission"] = row.name;
  json["dir"] = row.dir;
  json["edition"] = row.edition;
  json["stub_scores"] = row.stub_score;
  json["stub_max"] = row.stub_max;
  json["total"] = row.score;
  json["max"] = row.max_score;
  json["verdict"] = verdictId(row.verdict);
  json["isolation"] = row.isolation;
  json["problem"] = row.problem;
  json["seconds"] = row.seconds;
  nlohmann::ordered_json causes = nlohmann::ordered_json::array();
  for (const auto& [id, likely] : row.causes) causes.push_back({{"id", id}, {"likely", likely}});
  json["causes"] = causes;
  return json;
}

BatchRow rowFromJson(const nlohmann::json& json, const std::string& where) {
  try {
    BatchRow row;
    row.name = json.at("submission").get<std::string>();
    row.dir = json.at("dir").get<std::string>();
    row.edition = json.at("edition").get<int>();
    row.stub_score = json.at("stub_scores").get<std::map<std::string, double>>();
    row.stub_max = json.at("stub_max").get<std::map<std::string, double>>();
    row.score = json.at("total").get<double>();
    row.max_score = json.at("max").get<double>();
    if (!verdictFromId(json.at("verdict").get<std::string>(), row.verdict))
      throw InputError(where + ": not a batch row (unknown verdict)");
    row.isolation = json.at("isolation").get<std::string>();
    row.problem = json.at("problem").get<std::string>();
    row.seconds = json.at("seconds").get<double>();
    for (const auto& cause : json.at("causes"))
      row.causes.push_back({cause.at("id").get<std::string>(), cause.at("likely").get<bool>()});
    return row;
  } catch (const nlohmann::json::exception& error) {
    throw InputError(where + ": not a batch row (" + error.what() + ")");
  }
}

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
    c.isolation = row.isolation;
    std::error_code error;
    c.report = row.name + (fs::exists(batch_dir / row.name / "report.html", error) ? "/report.html"
                                                                                   : "/report.md");
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

std::string batchCsv(const std::vector<BatchRow>& rows, bool header) {
  std::string out;
  if (header) {
    out += "submission,edition";
    for (const std::string& stub : stubNames()) out += "," + csvField(stub);
    out += ",total,max,verdict,causes,guesses,seconds\n";
  }
  for (const BatchRow& row : rows) {
    out += csvField(row.name) + "," + (row.edition ? std::to_string(row.edition) : "");
    for (const std::string& stub : stubNames()) {
      auto it = row.stub_score.find(stub);
      out += "," + (it == row.stub_score.end() ? std::string() : points(it->second));
    }
    // the cause ids, likely ones and guesses apart, each list one field ("a b": no id has a space)
    std::string causes, guesses;
    for (const auto& [id, likely] : row.causes) {
      std::string& list = likely ? causes : guesses;
      list += (list.empty() ? "" : " ") + id;
    }
    std::ostringstream seconds;
    seconds.setf(std::ios::fixed);
    seconds.precision(1);
    seconds << row.seconds;
    out += "," + points(row.score) + "," + points(row.max_score) + "," +
           csvField(verdictId(row.verdict)) + "," + csvField(causes) + "," + csvField(guesses) +
           "," + seconds.str() + "\n";
  }
  return out;
}

}  // namespace clothref::grader
