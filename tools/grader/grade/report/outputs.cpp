#include "grader/grade/report/outputs.h"

#include <cmath>
#include <sstream>

#include "grader/grade/text.h"

namespace clothref::grader {
namespace {

double rounded(double value) { return std::round(value * 1000) / 1000; }

std::string xmlEscape(const std::string& text) {
  std::string out;
  for (char c : text) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      default:
        // Control characters other than tab and newline are not allowed in XML 1.0.
        if (static_cast<unsigned char>(c) < 0x20 && c != '\n' && c != '\t')
          out += ' ';
        else
          out += c;
    }
  }
  return out;
}

// The report with every text made safe (text.h): valid UTF-8 (Big5 lines decoded, other bytes
// U+FFFD), control characters escaped, names on one line; plus a note saying what was done. Every
// writer starts from this, so no byte a submission controls reaches an output unchecked.
GradeReport cleaned(const GradeReport& given) {
  GradeReport report = given;
  TextRepairs repairs;
  const auto name = [&](std::string& text) { text = safeName(text, &repairs); };
  const auto text = [&](std::string& value) { value = safeText(value, &repairs); };
  name(report.submission);
  text(report.edition_source);
  name(report.isolation);
  for (UsedFile& file : report.files) {
    name(file.name);
    name(file.path);
    text(file.problem);
  }
  for (std::string& note : report.notes) name(note);
  for (TestResult& test : report.tests) {
    name(test.stub);
    name(test.check);
    text(test.output);
    for (std::string& id : test.diagnoses) name(id);
  }
  if (repairs.any())
    report.notes.push_back("text from the submission made printable and valid UTF-8 (" +
                           repairs.describe() + ")");
  return report;
}

std::string number(double value) {
  std::ostringstream out;
  out << rounded(value);
  return out.str();
}

std::string filesSection(const GradeReport& report) {
  std::string out = "| file | used | status |\n|---|---|---|\n";
  for (const UsedFile& f : report.files) {
    std::string status = f.compiled               ? "compiled"
                         : f.problem == "missing" ? "missing"
                                                  : "did not build";
    if (!f.compiled) status += "; our reference version linked instead";
    out += "| " + f.name + " | " + (f.path.empty() ? "-" : "`" + f.path + "`") + " | " + status +
           " |\n";
  }
  return out;
}

}  // namespace

std::string summaryLine(const GradeReport& given) {
  const GradeReport report = cleaned(given);
  return "graded " + report.submission + " (" + std::to_string(report.edition) +
         "): " + number(report.score) + " / " + number(report.max_score);
}

nlohmann::ordered_json resultsJson(const GradeReport& given) {
  const GradeReport report = cleaned(given);
  nlohmann::ordered_json out;
  out["score"] = rounded(report.score);
  out["execution_time"] = rounded(report.seconds.count("total") ? report.seconds.at("total") : 0);
  std::string summary = "Edition " + std::to_string(report.edition) + " (" + report.edition_source +
                        "). Code score " + number(report.score) + " / " + number(report.max_score) +
                        ". Verdict: " + verdictId(report.verdict) + ".\n\n" + filesSection(report);
  if (!report.isolation.empty()) summary += "\nStudent code ran with: " + report.isolation + ".\n";
  for (const auto& note : report.notes) summary += "\n- " + note;
  out["output"] = summary;
  out["output_format"] = "md";
  out["visibility"] = "visible";
  out["stdout_visibility"] = "hidden";
  nlohmann::ordered_json tests = nlohmann::ordered_json::array();
  for (const TestResult& t : report.tests) {
    nlohmann::ordered_json test;
    test["name"] = t.name();
    test["score"] = rounded(t.score);
    test["max_score"] = rounded(t.max_score);
    test["status"] = t.passed() ? "passed" : "failed";
    test["output"] = t.output;
    test["output_format"] = "md";
    test["visibility"] = "visible";
    nlohmann::ordered_json tags = nlohmann::ordered_json::array({t.stub});
    for (const auto& id : t.diagnoses) tags.push_back(id);
    test["tags"] = tags;
    tests.push_back(test);
  }
  out["tests"] = tests;
  nlohmann::ordered_json extra;
  extra["edition"] = report.edition;
  extra["verdict"] = verdictId(report.verdict);
  extra["isolation"] = report.isolation;
  nlohmann::ordered_json files = nlohmann::ordered_json::array();
  for (const UsedFile& f : report.files)
    files.push_back(
        {{"name", f.name}, {"path", f.path}, {"compiled", f.compiled}, {"problem", f.problem}});
  extra["files"] = files;
  extra["stub_scores"] = report.stub_score;
  extra["stub_max"] = report.stub_max;
  extra["seconds"] = report.seconds;
  out["extra_data"] = extra;
  return out;
}

std::string junitXml(const GradeReport& given) {
  const GradeReport report = cleaned(given);
  int failures = 0;
  for (const TestResult& t : report.tests) failures += t.passed() ? 0 : 1;
  std::ostringstream out;
  out << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
  out << "<testsuites tests=\"" << report.tests.size() << "\" failures=\"" << failures
      << "\" name=\"clothref grade\">\n";
  out << "  <testsuite name=\"" << xmlEscape(report.submission) << "\" tests=\""
      << report.tests.size() << "\" failures=\"" << failures << "\">\n";
  out << "    <properties><property name=\"score\" value=\"" << number(report.score)
      << "\"/><property name=\"max_score\" value=\"" << number(report.max_score)
      << "\"/><property name=\"edition\" value=\"" << report.edition
      << "\"/><property name=\"verdict\" value=\"" << verdictId(report.verdict)
      << "\"/><property name=\"isolation\" value=\"" << xmlEscape(report.isolation) << "\"/>";
  // The notes (files chosen or refused, encodings, what text was decoded) on one line.
  std::string notes;
  for (const std::string& note : report.notes) notes += (notes.empty() ? "" : " | ") + note;
  if (!notes.empty()) out << "<property name=\"notes\" value=\"" << xmlEscape(notes) << "\"/>";
  out << "</properties>\n";
  for (const TestResult& t : report.tests) {
    out << "    <testcase classname=\"" << xmlEscape(t.stub) << "\" name=\"" << xmlEscape(t.check)
        << "\">";
    if (!t.passed())
      out << "\n      <failure message=\""
          << xmlEscape(number(t.score) + " / " + number(t.max_score)) << "\">"
          << xmlEscape(t.output) << "</failure>\n    ";
    out << "<system-out>" << xmlEscape(number(t.score) + " / " + number(t.max_score))
        << "</system-out></testcase>\n";
  }
  out << "  </testsuite>\n</testsuites>\n";
  return out.str();
}

std::string markdownReport(const GradeReport& given) {
  const GradeReport report = cleaned(given);
  std::ostringstream out;
  out << "# Grading report: " << report.submission << "\n\n";
  out << "Edition " << report.edition << " (" << report.edition_source << "). **Code score "
      << number(report.score) << " / " << number(report.max_score) << "**. Verdict: **"
      << verdictId(report.verdict) << "**.\n\n";
  if (!report.isolation.empty()) out << "Student code ran with: " << report.isolation << ".\n\n";
  out << "| stub | score |\n|---|---|\n";
  for (const auto& stub : stubNames())
    if (report.stub_max.count(stub))
      out << "| `" << stub << "` | " << number(report.stub_score.at(stub)) << " / "
          << number(report.stub_max.at(stub)) << " |\n";
  out << "\n## Files\n\n" << filesSection(report);
  for (const UsedFile& f : report.files)
    if (!f.compiled && f.problem != "missing")
      out << "\n`" << f.name << "`:\n\n```\n" << f.problem << "```\n";
  if (!report.notes.empty()) {
    out << "\n";
    for (const auto& note : report.notes) out << "- " << note << "\n";
  }
  out << "\n## Failed checks\n";
  bool any = false;
  for (const TestResult& t : report.tests) {
    if (t.passed() || t.informational) continue;
    any = true;
    out << "\n### " << t.name() << " (" << number(t.score) << " / " << number(t.max_score)
        << ")\n\n"
        << t.output << "\n";
  }
  if (!any) out << "\nNone.\n";
  out << "\n## Passed checks\n\n";
  for (const TestResult& t : report.tests)
    if (t.passed() && !t.informational)
      out << "- " << t.name() << " (" << number(t.score) << " / " << number(t.max_score) << ")\n";
  for (const TestResult& t : report.tests)
    if (t.informational) out << "\n## " << t.name() << "\n\n" << t.output << "\n";
  return out.str();
}

}  // namespace clothref::grader
