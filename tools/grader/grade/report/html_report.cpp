// The student's report page (html_report.h).
#include "grader/grade/report/html_report.h"

#include <algorithm>
#include <sstream>
#include <string>
#include <vector>

#include "clothref/io/error.h"
#include "grader/grade/report/outputs.h"
#include "grader/grade/report/stub_text.h"
#include "grader/grade/text.h"
#include "pages/html.h"
#include "pages/page_assets.h"
#include "pages/view_data.h"

namespace clothref::grader {

namespace {

const char* kReportStyle = R"(
.gr-table { border-collapse: collapse; margin: 6px 0; font-size: 0.92em; }
.gr-table th, .gr-table td { border: 1px solid #ddd; padding: 2px 8px; text-align: left;
                             overflow-wrap: anywhere; }
.gr-table th { background: #f0f2f5; }
.gr-pass { color: #2a7a2a; } .gr-fail { color: #b22222; } .gr-info { color: #555; }
.gr-check { border: 1px solid #e3e3e3; border-radius: 4px; margin: 4px 0; padding: 2px 8px; }
.gr-check > summary { cursor: pointer; font-weight: 600; }
.gr-cause { display: inline-block; background: #fde8e8; color: #8b1a1a; border-radius: 3px;
            padding: 0 5px; margin-left: 6px; font-size: 0.85em; font-weight: 400; }
.gr-cause.gr-guess { background: #f1f1f1; color: #555; border: 1px dashed #aaa; }
.gr-check pre, .gr-note pre, .gr-log pre { background: #f6f8fa; padding: 6px; overflow-x: auto; }
.gr-likely { border-left: 4px solid #c0392b; padding-left: 8px; margin: 6px 0; }
.gr-guesses { border-left: 4px dashed #999; padding-left: 8px; margin: 6px 0; color: #444; }
.gr-log > summary { cursor: pointer; color: #555; }
.gr-points p { margin: 4px 0; }
.gr-failed table { border-collapse: collapse; margin: 6px 0; font-size: 0.92em; }
.gr-failed th, .gr-failed td { border: 1px solid #ddd; padding: 2px 8px; text-align: left;
                               vertical-align: top; }
.gr-failed th { background: #f0f2f5; }
.gr-pictures { display: flex; flex-wrap: wrap; gap: 10px; margin: 6px 0; }
.gr-picture { margin: 0; }
.gr-picture figcaption { font-size: 0.85em; color: #555; }
.gr-passed { margin: 6px 0; }
.gr-passed > summary { cursor: pointer; }
)";

// A cause as a badge: its id, a guess dashed and marked "?".
std::string badge(const std::string& id, bool likely) {
  return std::string("<span class=\"") + (likely ? "gr-cause" : "gr-cause gr-guess") + "\"" +
         (likely ? "" : " title=\"a guess\"") + ">" + pages::escapeHtml(id) + (likely ? "" : "?") +
         "</span>";
}

std::string filesHtml(const GradeReport& report) {
  const auto e = [](const std::string& text) { return pages::escapeHtml(text); };
  std::string body =
      "<table class=\"gr-table gr-files\"><tr><th>file</th><th>found at</th><th>used</th></tr>\n";
  for (const UsedFile& f : report.files) {
    std::string used = "yours";
    if (!f.compiled) {
      used = f.status == Verdict::MissingFile
                 ? std::string("ours (yours is missing)")
                 : "ours (yours: " + e(f.problem.substr(0, f.problem.find('\n'))) + ")";
      if (f.status != Verdict::MissingFile && !f.problem.empty())
        used += "<details class=\"gr-log\"><summary>the first error" +
                std::string(f.log.empty() ? "" : " and the whole log") + "</summary><pre>" +
                e(f.problem) + "</pre>" +
                (f.log.empty() ? std::string() : "<pre>" + e(f.log) + "</pre>") + "</details>";
    }
    body += "<tr><td>" + e(f.name) + "</td><td>" + (f.path.empty() ? "(missing)" : e(f.path)) +
            "</td><td>" + used + "</td></tr>\n";
  }
  return body + "</table>\n";
}

std::string notesHtml(const std::vector<Note>& notes) {
  std::string out;
  for (const Note& note : notes) {
    out += "<div class=\"gr-info gr-note\">" + markdownToHtml(note.text);
    if (!note.block.empty()) out += "<pre>" + pages::escapeHtml(note.block) + "</pre>";
    out += "</div>\n";
  }
  return out;
}

const char* kInformationStatus[] = {"differs", "identical"};

}  // namespace

nlohmann::ordered_json wholeRunView(GradeReport& report) {
  nlohmann::ordered_json whole_run_view = nullptr;
  for (const TestResult& t : report.tests) {
    if (!t.traces) continue;
    try {
      // the traces as the probe kept them, named for the page (never a path of ours)
      std::istringstream reference(t.traces->reference), student(t.traces->student);
      pages::ViewOptions view;
      view.labels = {"reference", "your code"};
      whole_run_view = pages::viewerData({{"reference", &reference}, {"your run", &student}}, view);
    } catch (const InputError& problem) {
      // a student trace the reader refuses (cut short by a crash) leaves the report without it
      report.notes.push_back("The whole run could not be pictured: " +
                             codeSpan(safeName(problem.what())));
    }
  }
  return whole_run_view;
}

std::string studentReportHtml(const GradeReport& given,
                              const nlohmann::ordered_json& whole_run_view) {
  const GradeReport report = cleaned(given);
  const std::vector<TestText> texts = testTexts(report);
  const std::vector<StubText> stubs = stubTexts(report);
  const auto e = [](const std::string& text) { return pages::escapeHtml(text); };
  std::string body = "<p><strong>Score " + points(report.score) + " / " + points(report.max_score) +
                     "</strong>. Edition " + std::to_string(report.edition) + " (" +
                     e(report.edition_source) +
                     "). Verdict: " + std::string(verdictId(report.verdict)) + ".</p>\n";
  body += filesHtml(report);
  body += notesHtml(report.notes);
  // score per stub and what is wrong at a glance, then each stub as a student reads it
  body +=
      "<h2>Stubs</h2>\n<table class=\"gr-table gr-stubs\"><tr><th>stub</th><th>points</th>"
      "<th>checks passed</th><th>causes</th></tr>\n";
  for (const StubText& stub : stubs) {
    if (!report.stub_max.count(stub.stub)) continue;
    std::string chips;
    for (const auto& [id, likely] : stub.ids) chips += badge(id, likely);
    body += "<tr><td><a href=\"#" + e(stub.stub) + "\">" + e(stub.stub) + "</a></td><td>" +
            points(report.stub_score.at(stub.stub)) + " / " +
            points(report.stub_max.at(stub.stub)) + "</td><td class=\"" +
            (stub.failed.empty() ? "gr-pass" : "gr-fail") + "\">" +
            std::to_string(stub.passed.size()) + " of " + std::to_string(stub.checks) +
            "</td><td>" + chips + "</td></tr>\n";
  }
  body += "</table>\n<div class=\"gr-info\">" + markdownToHtml(kNumberLegend) + "</div>\n";
  const auto check = [&](std::size_t k, bool open) {
    const TestResult& t = report.tests[k];
    const char* state = t.informational ? "gr-info" : t.passed() ? "gr-pass" : "gr-fail";
    const char* mark = t.informational ? "\xE2\x84\xB9"
                       : t.passed()    ? "\xE2\x9C\x94"
                                       : "\xE2\x9C\x98";
    std::string out =
        std::string("<details class=\"gr-check\"") + (open ? " open" : "") + "><summary class=\"" +
        state + "\">" + mark + " " + e(t.check) +
        (t.informational ? std::string(t.check.find("information only") == std::string::npos
                                           ? " (information only)"
                                           : "") +
                               " \xE2\x80\x94 " + kInformationStatus[t.passed() ? 1 : 0]
                         : " \xE2\x80\x94 " + points(t.score) + " / " + points(t.max_score));
    for (const Cause& cause : t.causes) out += badge(cause.id, cause.likely);
    out += "</summary>\n";
    return out;
  };
  for (const StubText& stub : stubs) {
    body += "<h2 id=\"" + e(stub.stub) + "\">" + e(stub.stub) + "</h2>\n<div class=\"gr-points\">" +
            markdownToHtml(stub.points) + "</div>\n";
    if (!stub.failed.empty()) {
      body += testHtml(TestText{{}, stub.likely, stub.guesses});
      body += "<div class=\"gr-failed\">" + markdownToHtml(stub.tableMarkdown()) + "</div>\n";
      // the pictures of the states the failed checks tried, open
      std::string pictures;
      for (const CheckRow& row : stub.failed) {
        const std::string svg =
            stateSketchSvg(report.tests[row.test].sketch, "gr-sketch-" + std::to_string(row.test));
        if (!svg.empty())
          pictures += "<figure class=\"gr-picture\">" + svg + "<figcaption>" +
                      e(report.tests[row.test].check) + "</figcaption></figure>\n";
      }
      if (!pictures.empty()) body += "<div class=\"gr-pictures\">" + pictures + "</div>\n";
      // each failed check in full, folded: its output and what the probe measured for it
      for (const CheckRow& row : stub.failed) {
        const std::size_t k = row.test;
        std::string measured;
        for (const Cause& cause : report.tests[k].causes)
          if (!cause.detail.empty())
            measured += markdownToHtml(codeSpan(cause.id) + ": " + cause.detail);
        body += check(k, false) + markdownToHtml(texts[k].output) + measured + "</details>\n";
      }
    }
    if (!stub.passed.empty()) {
      body += std::string("<details class=\"gr-passed\"><summary class=\"gr-pass\">") +
              "\xE2\x9C\x94 " + std::to_string(stub.passed.size()) + " of " +
              std::to_string(stub.checks) + " checks passed</summary>\n";
      for (std::size_t k : stub.passed)
        body += check(k, false) + testHtml(texts[k]) + "</details>\n";
      body += "</details>\n";
    }
    for (std::size_t k : stub.information)
      body += check(k, false) + testHtml(texts[k]) + "</details>\n";
  }
  // information-only checks of no course stub (the whole run)
  std::string section;
  for (std::size_t k = 0; k < report.tests.size(); ++k) {
    const TestResult& t = report.tests[k];
    const auto& names = stubNames();
    if (std::find(names.begin(), names.end(), t.stub) != names.end()) continue;
    if (t.stub != section) {
      section = t.stub;
      body += "<h2 id=\"" + e(t.stub) + "\">" + e(t.stub) + "</h2>\n";
    }
    body += check(k, false) + stateSketchSvg(t.sketch, "gr-sketch-" + std::to_string(k)) +
            testHtml(texts[k]) + "</details>\n";
  }
  std::string viewer;
  if (!whole_run_view.is_null()) {
    body +=
        "<h2>Your whole run beside the reference</h2>\n<p>The course scene run by your "
        "three files and by the reference (information only: it never changes the score). "
        "Each of your cloth's particles is coloured by its distance to the reference's.</p>\n"
        "<div id=\"whole-run\"></div>\n"
        "<script type=\"application/json\" id=\"whole-run-data\">" +
        pages::jsonForScript(whole_run_view) +
        "</script>\n<script>mountViewer(document.getElementById('whole-run'), "
        "JSON.parse(document.getElementById('whole-run-data').textContent), "
        "{layout: 'side', stills: 4});</script>\n";
    viewer = pages::viewerScriptAndStyle();
  }
  return pages::fillTemplate(pages::pageAsset("report.html"),
                             {{"TITLE", e(report.submission)},
                              {"STYLE", std::string(pages::pageAsset("viewer.css")) + kReportStyle},
                              {"VIEWER", viewer},
                              {"BODY", body}});
}

}  // namespace clothref::grader
