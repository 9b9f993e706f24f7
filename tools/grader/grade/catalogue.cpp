#include "grader/grade/catalogue.h"

#include <array>
#include <nlohmann/json.hpp>

#include "clothref/io/error.h"
#include "clothref/io/json_input.h"
#include "clothref/io/limits.h"

namespace clothref::grader {
namespace {

constexpr const char* kFormat = "clothref-grader-diagnoses";
constexpr std::array<const char*, 5> kRecognisedBy = {"signature", "property", "guess",
                                                      "signature + pattern", "crash + pattern"};

[[noreturn]] void catalogueError(const std::string& source, const std::string& pointer,
                                 const std::string& problem) {
  throw InputError(source + ": " + pointer + ": " + problem);
}

// The string at `entry[key]`; `may_be_empty` false: a missing, mistyped or empty value is refused.
std::string stringField(const nlohmann::json& entry, const char* key, const std::string& source,
                        const std::string& pointer, bool may_be_empty = false) {
  const std::string at = pointer + "/" + key;
  if (!entry.contains(key)) catalogueError(source, at, "missing");
  const nlohmann::json& value = entry.at(key);
  if (!value.is_string())
    catalogueError(source, at, "expected a string, got " + excerpt(value.dump()));
  std::string text = value.get<std::string>();
  if (text.empty() && !may_be_empty) catalogueError(source, at, "empty");
  return text;
}

// Lower-case words of letters and digits joined by single '-': each becomes one C++ constant name.
bool wellFormedId(const std::string& id) {
  if (id.empty() || id.front() == '-' || id.back() == '-') return false;
  for (std::size_t k = 0; k < id.size(); ++k) {
    const char c = id[k];
    const bool word = (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9');
    if (!word && !(c == '-' && id[k - 1] != '-')) return false;
  }
  return true;
}

Diagnosis diagnosisAt(const nlohmann::json& entry, const std::string& source,
                      const std::string& pointer) {
  if (!entry.is_object())
    catalogueError(source, pointer, "expected an object, got " + excerpt(entry.dump()));
  for (const auto& [key, value] : entry.items())
    if (key != "id" && key != "stub" && key != "recognised_by" && key != "kind" &&
        key != "deduction" && key != "proof" && key != "model" && key != "text" && key != "why" &&
        key != "example" && key != "non_finite")
      catalogueError(source, pointer + "/" + excerpt(key), "unknown field");
  Diagnosis d;
  d.id = stringField(entry, "id", source, pointer);
  if (!wellFormedId(d.id))
    catalogueError(source, pointer + "/id",
                   "\"" + excerpt(d.id) + "\" is not lower-case words joined by '-'");
  stringField(entry, "stub", source, pointer);  // the docs table's; checked, not kept
  d.recognised_by = stringField(entry, "recognised_by", source, pointer);
  bool known = false;
  for (const char* way : kRecognisedBy) known = known || d.recognised_by == way;
  if (!known)
    catalogueError(source, pointer + "/recognised_by",
                   "unknown: \"" + excerpt(d.recognised_by) + "\"");
  // The build reads these (diagnoses.cmake: the rubric's defaults, the models); here they are
  // only checked to be there with their types.
  stringField(entry, "kind", source, pointer);
  stringField(entry, "proof", source, pointer);
  for (const char* key : {"deduction", "model"}) {
    if (!entry.contains(key)) catalogueError(source, pointer + "/" + key, "missing");
    const nlohmann::json& value = entry.at(key);
    const bool number = std::string(key) == "deduction";
    if (!value.is_null() && !(number ? value.is_number() : value.is_string()))
      catalogueError(source, pointer + "/" + key,
                     std::string("expected ") + (number ? "a number" : "a string") +
                         " or null, got " + excerpt(value.dump()));
  }
  d.text = stringField(entry, "text", source, pointer);
  d.why = stringField(entry, "why", source, pointer);
  // no example where there is no student's line to show (the grader's own failure, `unknown`)
  d.example = stringField(entry, "example", source, pointer, true);
  if (entry.contains("non_finite") && !entry.at("non_finite").is_boolean())
    catalogueError(source, pointer + "/non_finite", "expected true or false");
  d.non_finite = entry.value("non_finite", false);
  return d;
}

}  // namespace

Catalogue loadCatalogue(const std::filesystem::path& path) {
  const std::string source = path.string();
  const nlohmann::json document = readJsonFile(source, "diagnosis catalogue");
  if (!document.is_object()) catalogueError(source, "", "expected an object");
  if (!document.contains("format") || document["format"] != kFormat)
    catalogueError(source, "/format", std::string("expected \"") + kFormat + "\"");
  if (!document.contains("diagnoses") || !document["diagnoses"].is_array())
    catalogueError(source, "/diagnoses", "expected an array of diagnoses");
  Catalogue catalogue;
  std::map<std::string, std::string> first_at;  // id -> the pointer of its entry
  const nlohmann::json& entries = document["diagnoses"];
  for (std::size_t k = 0; k < entries.size(); ++k) {
    const std::string pointer = "/diagnoses/" + std::to_string(k);
    Diagnosis d = diagnosisAt(entries[k], source, pointer);
    const auto [it, first] = first_at.emplace(d.id, pointer);
    if (!first)
      catalogueError(source, pointer + "/id",
                     "duplicate id \"" + d.id + "\" (first at " + it->second + ")");
    catalogue.entries.emplace(d.id, std::move(d));
  }
  return catalogue;
}

void fillCauseTexts(const Catalogue& catalogue, std::vector<TestResult>& tests) {
  for (TestResult& test : tests)
    for (Cause& cause : test.causes) {
      auto it = catalogue.entries.find(cause.id);
      if (it == catalogue.entries.end()) continue;  // named by its id alone
      cause.text = it->second.text;
      cause.why = it->second.why;
      cause.example = it->second.example;
      if (it->second.recognised_by == "guess") cause.likely = false;
    }
}

}  // namespace clothref::grader
