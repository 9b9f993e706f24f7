// What a student reads of one stub (stub_text.h).
#include "grader/grade/report/stub_text.h"

#include <algorithm>
#include <map>
#include <regex>
#include <sstream>

#include "grader/grade/report/outputs.h"

namespace clothref::grader {
namespace {

// A table cell: one line, and a '|' would end the cell (markdown_html.cpp reads "\|" as one).
std::string cell(const std::string& text) {
  std::string out;
  for (char c : text)
    out += c == '|' ? std::string("\\|") : c == '\n' ? std::string(" ") : std::string(1, c);
  return out;
}

// A line of plain text, fit for a cell: no code span (a submission may control what is in one),
// not a list item, a heading or a table row.
bool plainLine(const std::string& line) {
  return !line.empty() && line.find('`') == std::string::npos && line.front() != '#' &&
         line.front() != '-' && line.front() != '|' && line.front() != '*';
}

// What a check that compared no quantity found, in one sentence of its output's plain text: the
// first that says what it measured (an order observed, springs missing, a crash), else the first;
// without the state it tried in parentheses, and short enough for a row.
std::string foundSentence(const std::vector<std::string>& lines) {
  static const std::regex found(
      R"(\b(Observed|Largest|missing|wrong|did not|yours|not finite|crashed|timed out|killed|exceeded|differ)\b)");
  std::vector<std::string> sentences;
  bool fenced = false;
  for (const std::string& line : lines) {
    if (line.rfind("```", 0) == 0) fenced = !fenced;
    if (fenced || !plainLine(line)) continue;
    for (std::size_t from = 0; from < line.size();) {
      std::size_t stop = line.find(". ", from);
      stop = stop == std::string::npos ? line.size() : stop + 1;
      sentences.push_back(line.substr(from, stop - from));
      from = stop + 1;
    }
  }
  if (sentences.empty()) return {};
  std::string chosen = sentences.front();
  for (const std::string& sentence : sentences)
    if (std::regex_search(sentence, found)) {
      chosen = sentence;
      break;
    }
  const std::size_t state = chosen.find(" (state");
  if (state != std::string::npos) chosen = chosen.substr(0, state) + ".";
  if (chosen.size() > 200) {
    const std::size_t cut = chosen.rfind(' ', 197);
    chosen = chosen.substr(0, cut == std::string::npos ? 197 : cut) + " \xE2\x80\xA6";
  }
  return chosen;
}

}  // namespace

CheckRow checkRow(const TestResult& test, std::size_t index) {
  // compareValues's two lines (explain/compare_text.h): "- LABEL: expected E, yours Y", and under
  // it, two spaces deeper, "- x differs by ..." when a component differs
  static const std::regex compared(R"(^( *)- (.+?): expected (.+), yours (.+?)$)");
  CheckRow row;
  row.test = index;
  row.check = test.check;
  std::vector<std::string> lines;
  std::istringstream in(test.output);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  std::smatch first, chosen;
  std::size_t first_at = 0, chosen_at = 0;
  std::string by;
  bool fenced = false;
  for (std::size_t k = 0; k < lines.size(); ++k) {
    if (lines[k].rfind("```", 0) == 0) fenced = !fenced;
    std::smatch m;
    if (fenced || !std::regex_match(lines[k], m, compared)) continue;
    const std::string indent = m[1].str() + "  - ";
    const bool differs = k + 1 < lines.size() && lines[k + 1].rfind(indent, 0) == 0;
    if (first.empty()) {
      first = m;
      first_at = k;
    }
    if (differs) {
      chosen = m;
      chosen_at = k;
      by = lines[k + 1].substr(indent.size());
      break;
    }
  }
  const std::smatch& m = chosen.empty() ? first : chosen;
  if (!m.empty()) {
    // a nested comparison belongs to the item above it ("- sphere 0 (mass 125), before the
    // call: ..."): its name, up to the first parenthesis, comma or colon, names the body
    const std::size_t at = chosen.empty() ? first_at : chosen_at;
    const std::size_t depth = m[1].length();
    std::string owner;
    for (std::size_t k = at; depth > 0 && k-- > 0;) {
      const std::size_t indent = lines[k].find_first_not_of(' ');
      if (indent == std::string::npos || indent >= depth) continue;
      if (lines[k].compare(indent, 2, "- ") == 0)
        owner = lines[k].substr(indent + 2, lines[k].find_first_of("(,:", indent + 2) - indent - 2);
      break;
    }
    while (!owner.empty() && owner.back() == ' ') owner.pop_back();
    if (!owner.empty() && owner.find('`') == std::string::npos) row.check += ": " + owner;
    std::string yours = m[4].str();
    const std::string same = ": the same within the tolerance";
    if (yours.size() > same.size() &&
        yours.compare(yours.size() - same.size(), same.size(), same) == 0)
      yours.erase(yours.size() - same.size());
    row.check += ": " + m[2].str();
    row.expected = m[3].str();
    row.yours = yours;
    row.by = by;
    return row;
  }
  row.yours = foundSentence(lines);
  return row;
}

std::vector<StubText> stubTexts(const GradeReport& report) {
  std::vector<StubText> stubs;
  for (const std::string& stub : stubNames()) {
    StubText text;
    text.stub = stub;
    bool any = false;
    std::string rubric_note;
    // each cause once: the first failed check that names it gives its measurement and lines;
    // likely when any check names it as likely
    std::vector<Cause> causes;
    for (std::size_t k = 0; k < report.tests.size(); ++k) {
      const TestResult& t = report.tests[k];
      if (t.stub != stub) continue;
      any = true;
      if (t.informational) {
        text.information.push_back(k);
        continue;
      }
      ++text.checks;
      if (t.passed()) {
        text.passed.push_back(k);
        continue;
      }
      if (rubric_note.empty()) rubric_note = t.rubric_note;
      text.failed.push_back(checkRow(t, k));
      for (const Cause& cause : t.causes) {
        auto known = std::find_if(causes.begin(), causes.end(),
                                  [&](const Cause& c) { return c.id == cause.id; });
        if (known == causes.end()) {
          causes.push_back(cause);
          continue;
        }
        known->likely = known->likely || cause.likely;
        if (known->detail.empty()) known->detail = cause.detail;
        for (const SourceQuote& quote : cause.quotes)
          if (std::find(known->quotes.begin(), known->quotes.end(), quote) == known->quotes.end())
            known->quotes.push_back(quote);
      }
    }
    if (!any) continue;
    for (const Cause& cause : causes) {
      (cause.likely ? text.likely : text.guesses).push_back(causeMarkdown(cause, stub, {}));
      text.ids.push_back({cause.id, cause.likely});
    }
    const auto of = [&](const std::map<std::string, double>& values) {
      const auto it = values.find(stub);
      return it == values.end() ? 0.0 : it->second;
    };
    const std::string score =
        "**" + points(of(report.stub_score)) + " / " + points(of(report.stub_max)) + "**";
    const int passed = static_cast<int>(text.passed.size());
    const std::string checks =
        std::to_string(passed) + " of " + std::to_string(text.checks) + " checks passed";
    if (text.failed.empty())
      text.points = score + ": " +
                    (text.checks == 1 ? std::string("its check passed")
                                      : "all " + std::to_string(text.checks) + " checks passed") +
                    ".";
    else if (!rubric_note.empty())  // the per-mistake rule says itself (rubric.cpp)
      text.points = score + ", " + checks + ". " + rubric_note;
    else
      text.points =
          score + ", " + checks + ": scored per check (each failed check loses its own points).";
    stubs.push_back(std::move(text));
  }
  return stubs;
}

std::string StubText::causesMarkdown() const {
  std::string out;
  for (const auto* blocks : {&likely, &guesses})
    for (const std::string& block : *blocks) out += (out.empty() ? "" : "\n") + block;
  return out;
}

std::string StubText::tableMarkdown() const {
  if (failed.empty()) return {};
  std::string out = "| failed check | expected | yours | by how much |\n|---|---|---|---|\n";
  for (const CheckRow& row : failed)
    out += "| " + cell(row.check) + " | " + cell(row.expected) + " | " + cell(row.yours) + " | " +
           cell(row.by) + " |\n";
  return out;
}

std::string StubText::passedMarkdown(const GradeReport& report) const {
  if (passed.empty()) return {};
  std::string out = "Passed (" + std::to_string(passed.size()) + "): ";
  for (std::size_t k = 0; k < passed.size(); ++k)
    out += (k ? ", " : "") + report.tests[passed[k]].check;
  return out + ".\n";
}

}  // namespace clothref::grader
