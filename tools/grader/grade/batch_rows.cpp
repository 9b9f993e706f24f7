// A batch's row (one submission's line of grades.csv, and its row.json marker) as data: made from
// a report, written as JSON and CSV, read back from JSON.
#include <algorithm>
#include <sstream>

#include "clothref/io/error.h"
#include "clothref/io/json_input.h"
#include "grader/grade/batch.h"
#include "grader/grade/report/outputs.h"
#include "grader/grade/text.h"

namespace clothref::grader {
namespace {

std::string number(double value) { return points(value); }

std::string csvField(const std::string& given) {
  const std::string text = safeName(given);  // valid UTF-8, one line, no terminal escapes
  if (text.find_first_of(",\"") == std::string::npos) return text;
  std::string out = "\"";
  for (char c : text) out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
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
    return row;
  } catch (const nlohmann::json::exception& error) {
    throw InputError(where + ": not a batch row (" + error.what() + ")");
  }
}

std::string batchCsv(const std::vector<BatchRow>& rows, bool header) {
  std::string out;
  if (header) {
    out += "submission,edition";
    for (const std::string& stub : stubNames()) out += "," + csvField(stub);
    out += ",total,max,verdict,isolation,seconds\n";
  }
  for (const BatchRow& row : rows) {
    out += csvField(row.name) + "," + (row.edition ? std::to_string(row.edition) : "");
    for (const std::string& stub : stubNames()) {
      auto it = row.stub_score.find(stub);
      out += "," + (it == row.stub_score.end() ? std::string() : number(it->second));
    }
    std::ostringstream seconds;
    seconds.setf(std::ios::fixed);
    seconds.precision(1);
    seconds << row.seconds;
    out += "," + number(row.score) + "," + number(row.max_score) + "," +
           csvField(verdictId(row.verdict)) + "," + csvField(row.isolation) + "," + seconds.str() +
           "\n";
  }
  return out;
}

}  // namespace clothref::grader
