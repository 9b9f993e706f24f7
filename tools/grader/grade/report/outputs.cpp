#include "grader/grade/report/outputs.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <sstream>

#include "grader/grade/cause_ids.h"
#include "grader/grade/text.h"

namespace clothref::grader {
namespace {

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

// “check” of a test, as later tests refer to it.
std::string curlyQuoted(const std::string& text) { return "\xE2\x80\x9C" + text + "\xE2\x80\x9D"; }

std::string quoteBlock(const std::vector<SourceQuote>& quotes) {
  std::string lines;
  for (const SourceQuote& quote : quotes)
    lines += quote.file + ":" + std::to_string(quote.line) + ": " + quote.text + "\n";
  return codeBlock(lines);
}

}  // namespace

std::string notesMarkdown(const std::vector<Note>& notes) {
  std::string out;
  for (const Note& note : notes)
    if (note.block.empty()) out += "- " + note.text + "\n";
  for (const Note& note : notes)
    if (!note.block.empty()) out += "\n" + note.text + "\n\n" + codeBlock(note.block);
  return out;
}

std::string causeMarkdown(const Cause& cause, const std::string& stub, const CauseShown& shown) {
  std::string block =
      std::string(cause.likely ? "**Likely cause**" : "**Possible cause (a guess)**") + " (" +
      codeSpan(cause.id) + ")";
  if (!shown.explained_under.empty())
    block += ": explained under " + curlyQuoted(shown.explained_under) + " above.\n";
  else
    block += (cause.text.empty() ? "" : ": " + cause.text) + "\n";
  // what the probe measured for this check: one paragraph right under the head
  if (!cause.detail.empty())
    block += "\n" + cause.detail + (cause.detail.back() == '\n' ? "" : "\n");
  // how the cause was proven on this submission, or where its model and the numbers part
  if (!cause.proof.empty()) block += "\n" + cause.proof + "\n";
  if (shown.explained_under.empty() && cause.likely && !shown.why_under.empty() &&
      (!cause.why.empty() || !cause.example.empty())) {
    block += "\n**Why**, and the mistake with its fix: as under " + codeSpan(shown.why_under) +
             " above.\n";
  } else if (shown.explained_under.empty() && cause.likely) {
    if (!cause.why.empty()) block += "\n**Why**: " + cause.why + "\n";
    if (!cause.example.empty())
      block += "\nThe mistake and its fix, in short:\n\n" + codeBlock(cause.example);
  }
  if (shown.quote && !cause.quotes.empty())
    block += "\nIn " + codeSpan(cause.quotes.front().file) + ", inside " + codeSpan(stub) +
             ":\n\n" + quoteBlock(cause.quotes);
  return block;
}

std::string statusWord(const TestResult& t) {
  if (t.informational) return t.passed() ? "identical" : "differs";
  return t.passed() ? "passed" : "failed";
}

std::pair<int, int> checksPassed(const GradeReport& report, const std::string& stub) {
  int passed = 0, total = 0;
  for (const TestResult& t : report.tests)
    if (t.stub == stub && !t.informational) {
      ++total;
      passed += t.passed();
    }
  return {passed, total};
}

std::set<std::string> stubsShownLater(const GradeReport& report) {
  std::set<std::string> later;
  for (const TestResult& t : report.tests)
    if (t.visibility != "visible") later.insert(t.stub);
  return later;
}

double roundedPoints(double value) {
  const double rounded = std::round(value * 1000) / 1000;
  return rounded == 0 ? 0.0 : rounded;  // never "-0"
}

std::string points(double value) {
  std::ostringstream out;
  out << roundedPoints(value);
  return out.str();
}

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
    text(file.log);
  }
  for (Note& note : report.notes) {
    name(note.text);
    text(note.block);
  }
  for (FileChoice& choice : report.choices) {
    name(choice.name);
    name(choice.used);
    for (std::string& other : choice.others) name(other);
  }
  for (TestResult& test : report.tests) {
    // How the probe's run ended (it crashed, timed out, answered twice differently: read, so
    // likely) beside another likely cause of the same check: that cause is what made it end so.
    const auto ending = [](const Cause& c) {
      return c.id == cause::kCrashed || c.id == cause::kTimedOut ||
             c.id == cause::kUndefinedBehaviour;
    };
    const bool explained = std::any_of(test.causes.begin(), test.causes.end(),
                                       [&](const Cause& c) { return c.likely && !ending(c); });
    if (explained) std::erase_if(test.causes, ending);
    // A symptom (NaN, a blow-up, a wrong order) beside a cause proven on this check: the proven
    // cause's model gives that check's numbers (its replay or repair), so it is no cause of its
    // own.
    const bool proven = std::any_of(test.causes.begin(), test.causes.end(),
                                    [](const Cause& c) { return c.proven(); });
    if (proven)
      std::erase_if(test.causes, [](const Cause& c) {
        return c.id == cause::kNonFinite || c.id == cause::kUnstable || c.id == cause::kWrongOrder;
      });
    name(test.stub);
    name(test.check);
    name(test.visibility);
    text(test.output);
    text(test.rubric_note);
    for (Cause& cause : test.causes) {
      name(cause.id);
      text(cause.detail);
      text(cause.proof);
      text(cause.text);
      text(cause.why);
      text(cause.example);
      for (SourceQuote& quote : cause.quotes) {
        name(quote.file);
        name(quote.text);
      }
    }
  }
  if (repairs.any())
    report.notes.push_back("text from the submission made printable and valid UTF-8 (" +
                           repairs.describe() + ")");
  return report;
}

std::string TestText::markdown() const {
  std::string out = output;
  for (const auto* blocks : {&likely, &guesses})
    for (const std::string& block : *blocks) {
      if (!out.empty() && out.back() != '\n') out += '\n';
      out += "\n" + block;
    }
  return out;
}

std::vector<TestText> testTexts(const GradeReport& report) {
  std::vector<TestText> texts;
  // visibility and a long output -> the test that showed it (a test refers only to one shown with
  // it)
  std::map<std::string, std::string> outputs;
  const std::set<std::string> later = stubsShownLater(report);
  // stub, visibility and cause -> the check that explained it and the lines it quoted: a visible
  // test never refers to one the student cannot see yet
  std::map<std::string, std::pair<std::string, std::vector<SourceQuote>>> explained;
  for (const TestResult& t : report.tests) {
    TestText text;
    text.output = t.output;
    // the Markdown report shows information-only tests last: nothing refers to them
    const bool failed = !t.passed() && !t.informational;
    if (failed && t.output.find('\n') != std::string::npos) {
      auto [it, first] = outputs.emplace(t.visibility + "\n" + t.output, t.name());
      if (!first) text.output = "Same as for " + curlyQuoted(it->second) + " above.\n";
    }
    // the per-mistake line tells how every check of its stub went: not on a stub whose checks
    // are shown at different times
    const bool one_time =
        !later.count(t.stub) ||
        std::all_of(report.tests.begin(), report.tests.end(), [&](const TestResult& other) {
          return other.stub != t.stub || other.visibility == t.visibility;
        });
    if (!t.rubric_note.empty() && one_time)
      text.output = t.rubric_note + (text.output.empty() ? "\n" : "\n\n" + text.output);
    for (const Cause& cause : t.causes) {
      CauseShown shown;
      if (failed) {
        const auto [it, first] = explained.emplace(t.stub + "\n" + t.visibility + "\n" + cause.id,
                                                   std::pair{t.name(), cause.quotes});
        if (!first) {
          shown.explained_under = it->second.first;
          shown.quote = cause.quotes != it->second.second;  // other lines than those shown
        }
      }
      (cause.likely ? text.likely : text.guesses).push_back(causeMarkdown(cause, t.stub, shown));
    }
    texts.push_back(text);
  }
  return texts;
}

std::string filesMarkdown(const GradeReport& report) {
  std::string out;
  for (const UsedFile& f : report.files) {
    out += "- " + f.name + ": " + (f.path.empty() ? std::string("not found") : codeSpan(f.path));
    if (f.compiled)
      out += ", compiled\n";
    else
      out += std::string(f.status == Verdict::MissingFile ? "" : ", did not build") +
             "; our reference version linked instead\n";
  }
  for (const UsedFile& f : report.files) {
    if (f.compiled || f.status == Verdict::MissingFile || f.problem.empty()) continue;
    out += "\n" + codeSpan(f.name) + ", the first error:\n\n" + codeBlock(f.problem);
    if (!f.log.empty())
      out +=
          "\nThe whole log of " + codeSpan(f.name) + " (its own messages):\n\n" + codeBlock(f.log);
  }
  return out;
}

std::string scoreSentence(const GradeReport& report, const std::string& score,
                          const std::string& verdict) {
  if (!stubsShownLater(report).empty())
    return "Some checks are shown later: the score and the verdict come with them.";
  return score + points(report.score) + " / " + points(report.max_score) + verdict +
         verdictId(report.verdict) + ".";
}

std::string summaryLine(const GradeReport& given) {
  const GradeReport report = cleaned(given);
  return "graded " + report.submission + " (" + std::to_string(report.edition) +
         "): " + points(report.score) + " / " + points(report.max_score) + ", verdict " +
         verdictId(report.verdict);
}

std::vector<std::string> choiceLines(const GradeReport& given) {
  const GradeReport report = cleaned(given);
  std::vector<std::string> lines;
  for (const FileChoice& choice : report.choices) {
    std::string others;
    for (const std::string& other : choice.others) others += (others.empty() ? "" : ", ") + other;
    lines.push_back(choice.name + ": used " + choice.used + "; also found " + others);
  }
  return lines;
}

nlohmann::ordered_json resultsJson(const GradeReport& given) {
  const GradeReport report = cleaned(given);
  const std::vector<TestText> texts = testTexts(report);
  nlohmann::ordered_json out;
  out["score"] = roundedPoints(report.score);
  out["execution_time"] =
      std::round((report.seconds.count("total") ? report.seconds.at("total") : 0) * 1000) / 1000;
  std::string summary = "Edition " + std::to_string(report.edition) + " (" + report.edition_source +
                        "). " + scoreSentence(report, "Code score ", ". Verdict: ") + "\n\n" +
                        filesMarkdown(report);
  if (!report.isolation.empty()) summary += "\nStudent code ran with: " + report.isolation + ".\n";
  if (!report.notes.empty()) summary += "\n" + notesMarkdown(report.notes);
  summary += "\n" + std::string(kNumberLegend) + "\n";
  out["output"] = summary;
  out["output_format"] = "md";
  out["visibility"] = "visible";
  out["stdout_visibility"] = "hidden";
  nlohmann::ordered_json tests = nlohmann::ordered_json::array();
  for (std::size_t k = 0; k < report.tests.size(); ++k) {
    const TestResult& t = report.tests[k];
    nlohmann::ordered_json test;
    test["name"] = t.name();
    test["score"] = roundedPoints(t.score);
    test["max_score"] = roundedPoints(t.max_score);
    test["status"] = t.passed() ? "passed" : "failed";
    test["output"] = texts[k].markdown();
    test["output_format"] = "md";
    test["visibility"] = t.visibility;
    nlohmann::ordered_json tags = nlohmann::ordered_json::array({t.stub});
    for (const auto& id : t.causeIds()) tags.push_back(id);
    test["tags"] = tags;
    if (!t.causes.empty() || t.informational) {
      nlohmann::ordered_json extra;
      if (t.informational) extra["information_only"] = statusWord(t);
      nlohmann::ordered_json causes = nlohmann::ordered_json::array();
      for (const Cause& cause : t.causes)
        causes.push_back({{"id", cause.id}, {"likely", cause.likely}, {"proven", cause.proven()}});
      if (!t.causes.empty()) extra["causes"] = causes;
      test["extra_data"] = extra;
    }
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
  nlohmann::ordered_json stub_scores, stub_max;
  for (const auto& [stub, value] : report.stub_score) stub_scores[stub] = roundedPoints(value);
  for (const auto& [stub, value] : report.stub_max) stub_max[stub] = roundedPoints(value);
  extra["stub_scores"] = stub_scores;
  extra["stub_max"] = stub_max;
  extra["seconds"] = report.seconds;
  out["extra_data"] = extra;
  return out;
}

std::string junitXml(const GradeReport& given) {
  const GradeReport report = cleaned(given);
  const std::vector<TestText> texts = testTexts(report);
  int failures = 0;
  for (const TestResult& t : report.tests) failures += t.passed() || t.informational ? 0 : 1;
  std::ostringstream out;
  out << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
  out << "<testsuites tests=\"" << report.tests.size() << "\" failures=\"" << failures
      << "\" name=\"clothref grade\">\n";
  out << "  <testsuite name=\"" << xmlEscape(report.submission) << "\" tests=\""
      << report.tests.size() << "\" failures=\"" << failures << "\">\n";
  out << "    <properties><property name=\"score\" value=\"" << points(report.score)
      << "\"/><property name=\"max_score\" value=\"" << points(report.max_score)
      << "\"/><property name=\"edition\" value=\"" << report.edition
      << "\"/><property name=\"verdict\" value=\"" << verdictId(report.verdict)
      << "\"/><property name=\"isolation\" value=\"" << xmlEscape(report.isolation) << "\"/>";
  // The notes (files chosen or refused, encodings, what text was decoded) on one line; a note's
  // block follows its text.
  std::string notes;
  for (const Note& note : report.notes)
    notes +=
        (notes.empty() ? "" : " | ") + note.text + (note.block.empty() ? "" : ": " + note.block);
  if (!notes.empty()) out << "<property name=\"notes\" value=\"" << xmlEscape(notes) << "\"/>";
  out << "</properties>\n";
  for (std::size_t k = 0; k < report.tests.size(); ++k) {
    const TestResult& t = report.tests[k];
    out << "    <testcase classname=\"" << xmlEscape(t.stub) << "\" name=\"" << xmlEscape(t.check)
        << "\">";
    if (t.informational) {
      // information only: never a failure, whatever it found
      out << "<system-out>"
          << xmlEscape("information only, " + statusWord(t) + "\n\n" + texts[k].markdown())
          << "</system-out></testcase>\n";
      continue;
    }
    if (!t.passed())
      out << "\n      <failure message=\""
          << xmlEscape(points(t.score) + " / " + points(t.max_score)) << "\">"
          << xmlEscape(texts[k].markdown()) << "</failure>\n    ";
    out << "<system-out>" << xmlEscape(points(t.score) + " / " + points(t.max_score))
        << "</system-out></testcase>\n";
  }
  out << "  </testsuite>\n</testsuites>\n";
  return out.str();
}

}  // namespace clothref::grader
