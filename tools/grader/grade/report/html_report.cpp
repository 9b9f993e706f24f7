#include "grader/grade/report/html_report.h"

#include <stdlib.h>

#include <algorithm>
#include <atomic>
#include <array>
#include <cmath>
#include <fstream>
#include <map>
#include <sstream>
#include <vector>

#include <fmt/format.h>

#include "clothref/io/error.h"
#include "pages/html.h"
#include "pages/page_assets.h"
#include "pages/view_data.h"
#include "grader/grade/report/outputs.h"
#include "grader/grade/text.h"

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

std::string number(double value) { return points(value); }

std::size_t backtickRun(std::string_view text, std::size_t at) {
  std::size_t n = 0;
  while (at + n < text.size() && text[at + n] == '`') ++n;
  return n;
}

// Inline Markdown of one line, escaped: code spans (a run of N backticks up to the next run of
// exactly N, as text.h's codeSpan writes them) and **bold**; everything else is text.
std::string inlineMarkdown(std::string_view line) {
  std::string out;
  bool bold = false;
  for (std::size_t i = 0; i < line.size();) {
    if (line[i] == '`') {
      const std::size_t n = backtickRun(line, i);
      std::size_t close = i + n;
      while (close < line.size()) {
        close = line.find('`', close);
        if (close == std::string_view::npos) break;
        const std::size_t m = backtickRun(line, close);
        if (m == n) break;
        close += m;
      }
      if (close == std::string_view::npos || close >= line.size()) {  // no closing run: text
        out += line.substr(i, n);
        i += n;
        continue;
      }
      std::string_view code = line.substr(i + n, close - i - n);
      if (code.size() >= 2 && code.front() == ' ' && code.back() == ' ' &&
          code.find_first_not_of(' ') != std::string_view::npos)
        code = code.substr(1, code.size() - 2);
      out += "<code>" + pages::escapeHtml(code) + "</code>";
      i = close + n;
    } else if (line.compare(i, 2, "**") == 0) {
      out += bold ? "</strong>" : "<strong>";
      bold = !bold;
      i += 2;
    } else {
      const std::size_t next = std::min(line.find('`', i), line.find("**", i));
      const std::size_t end = next == std::string_view::npos ? line.size() : next;
      out += pages::escapeHtml(line.substr(i, end - i));
      i = end;
    }
  }
  if (bold) out += "</strong>";
  return out;
}

// Checks of `stub` that count for points, and how many of them passed.
std::pair<int, int> checksPassed(const GradeReport& report, const std::string& stub) {
  int passed = 0, total = 0;
  for (const TestResult& t : report.tests)
    if (t.stub == stub && !t.informational) {
      ++total;
      passed += t.passed();
    }
  return {passed, total};
}

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
)";

// The opening of a sketch's <svg> and its arrow-head markers, one per colour.
std::string sketchSvgStart(double width, double height, const char* label,
                           const std::vector<std::pair<std::string, std::string>>& markers) {
  std::string out = fmt::format(
      R"(<svg class="gr-sketch" xmlns="http://www.w3.org/2000/svg" width="{0}" height="{1}" )"
      R"(viewBox="0 0 {0} {1}" role="img" aria-label="{2}"><defs>)",
      width, height, label);
  for (const auto& [name, colour] : markers)
    out += fmt::format(
        R"(<marker id="gr-{0}" viewBox="0 0 8 8" refX="7" refY="4" markerWidth="6" )"
        R"(markerHeight="6" orient="auto"><path d="M0,0 L8,4 L0,8 z" fill="{1}"/></marker>)",
        name, colour);
  return out + "</defs>";
}

// A rectangle of the picture in pixels, for labels that must not cover each other.
struct Box {
  double x0, y0, x1, y1;
  bool overlaps(const Box& o) const { return x0 < o.x1 && o.x0 < x1 && y0 < o.y1 && o.y0 < y1; }
};

// One panel of a collision sketch: the part [lo, hi] of the x-y plane drawn in the pixel box at
// (left, top) of size `side` x `side`, one scale for both axes; arrows scaled so that the fastest
// velocity spans 40 % of the panel's width in metres. Bodies, then arrows, then labels, each label
// where it covers no other label (tried beside its body on four sides).
std::string bodiesPanel(const std::vector<SketchBody>& bodies, double lo_x, double lo_y, double span,
                        double left, double top, double side, const std::string& clip,
                        std::vector<Box>& labels) {
  const double scale = side / span;
  const auto px = [&](double x) { return left + (x - lo_x) * scale; };
  const auto py = [&](double y) { return top + side - (y - lo_y) * scale; };
  double fastest = 0;
  for (const SketchBody& b : bodies)
    for (const auto& v : {b.v, b.v_expected, b.v_actual})
      if (std::isfinite(v[0]) && std::isfinite(v[1]))
        fastest = std::max(fastest, std::hypot(double(v[0]), double(v[1])));
  const double arrow = fastest > 0 ? 0.4 * span / fastest : 0;
  const std::array<std::pair<std::string, std::string>, 3> kinds = {
      {{"before", "#888"}, {"course", "#2a7a2a"}, {"yours", "#c0392b"}}};
  std::string out = fmt::format(
      R"(<clipPath id="{0}"><rect x="{1:.1f}" y="{2:.1f}" width="{3:.1f}" height="{3:.1f}"/>)"
      R"(</clipPath><rect x="{1:.1f}" y="{2:.1f}" width="{3:.1f}" height="{3:.1f}" fill="none" )"
      R"svg(stroke="#ddd"/><g clip-path="url(#{0})">)svg",
      clip, left, top, side);
  for (const SketchBody& b : bodies)
    out += b.radius > 0
               ? fmt::format(R"(<circle cx="{:.1f}" cy="{:.1f}" r="{:.1f}" fill="#dce8f5" )"
                             R"(stroke="#5b7fa6" fill-opacity="0.8"/>)",
                             px(b.x[0]), py(b.x[1]), b.radius * scale)
               : fmt::format(R"(<circle cx="{:.1f}" cy="{:.1f}" r="3.5" fill="#333"/>)",
                             px(b.x[0]), py(b.x[1]));
  for (const SketchBody& b : bodies) {
    const std::array<const std::array<float, 3>*, 3> velocities = {&b.v, &b.v_expected,
                                                                   &b.v_actual};
    for (std::size_t k = 0; k < kinds.size(); ++k) {
      const auto& v = *velocities[k];
      if (!std::isfinite(v[0]) || !std::isfinite(v[1])) continue;  // NaN loses its arrow only
      out += fmt::format(R"(<line x1="{:.1f}" y1="{:.1f}" x2="{:.1f}" y2="{:.1f}" stroke="{}" )"
                         R"svg(stroke-width="2" marker-end="url(#gr-{})"/>)svg",
                         px(b.x[0]), py(b.x[1]), px(b.x[0] + v[0] * arrow),
                         py(b.x[1] + v[1] * arrow), kinds[k].second, kinds[k].first);
    }
  }
  out += "</g>";
  // Labels of the bodies whose centre is in the panel: beside the dot, or inside the circle's top
  // for a sphere, on the first side where it covers no label placed before.
  constexpr double kCharWidth = 6.2, kLabelHeight = 12;
  for (const SketchBody& b : bodies) {
    const double cx = px(b.x[0]), cy = py(b.x[1]);
    if (cx < left || cx > left + side || cy < top || cy > top + side) continue;
    const double width = kCharWidth * double(b.label.size());
    const double r = b.radius > 0 ? b.radius * scale : 4;
    const std::array<std::pair<double, double>, 5> corners = {{
        {cx + 0.7 * r + 2, cy - 0.7 * r - 2},            // upper right
        {cx - 0.7 * r - 2 - width, cy - 0.7 * r - 2},    // upper left
        {cx + 0.7 * r + 2, cy + 0.7 * r + kLabelHeight},  // lower right
        {cx - 0.7 * r - 2 - width, cy + 0.7 * r + kLabelHeight},
        {cx - width / 2, cy + 4}}};  // on the centre
    Box chosen{};
    bool placed = false;
    for (const auto& [x, y] : corners) {
      const Box box{x, y - kLabelHeight + 2, x + width, y + 2};
      const bool inside = box.x0 >= left && box.x1 <= left + side && box.y0 >= top &&
                          box.y1 <= top + side;
      const bool free = std::none_of(labels.begin(), labels.end(),
                                     [&](const Box& other) { return other.overlaps(box); });
      if (inside && free) {
        chosen = box;
        placed = true;
        break;
      }
    }
    if (!placed) continue;  // no free place: the text below the picture names every body
    labels.push_back(chosen);
    out += fmt::format(
        R"(<text x="{:.1f}" y="{:.1f}" font-size="11" fill="#222" paint-order="stroke" )"
        R"(stroke="#fff" stroke-width="3">{}</text>)",
        chosen.x0, chosen.y1 - 2, pages::escapeHtml(b.label));
  }
  return out;
}

// The point where two bodies meet (the middle of their gap, or of their overlap) and how wide the
// gap is, for the closest pair; false for fewer than two bodies.
bool contactPoint(const std::vector<SketchBody>& bodies, double& x, double& y, double& gap) {
  bool found = false;
  for (std::size_t i = 0; i < bodies.size(); ++i)
    for (std::size_t j = i + 1; j < bodies.size(); ++j) {
      const auto& a = bodies[i];
      const auto& b = bodies[j];
      const double dx = double(b.x[0]) - a.x[0], dy = double(b.x[1]) - a.x[1];
      const double d = std::hypot(dx, dy);
      const double g = d - a.radius - b.radius;
      if (found && g >= gap) continue;
      found = true;
      gap = g;
      const double t = d > 0 ? (a.radius + g / 2) / d : 0;
      x = a.x[0] + dx * t;
      y = a.x[1] + dy * t;
    }
  return found;
}

std::string bodiesSvg(const std::vector<SketchBody>& bodies) {
  constexpr double kSide = 300, kGap = 16, kMargin = 10, kTitle = 16, kLegend = 34;
  double lo_x = 1e30, hi_x = -1e30, lo_y = 1e30, hi_y = -1e30;
  for (const SketchBody& b : bodies) {
    if (!std::isfinite(b.x[0]) || !std::isfinite(b.x[1]) || !std::isfinite(b.radius))
      return {};  // a body we cannot place: the text says where it was
    lo_x = std::min(lo_x, double(b.x[0] - b.radius));
    hi_x = std::max(hi_x, double(b.x[0] + b.radius));
    lo_y = std::min(lo_y, double(b.x[1] - b.radius));
    hi_y = std::max(hi_y, double(b.x[1] + b.radius));
  }
  // The whole scene with room for the arrows around it; beside it, when two bodies meet, the
  // contact up close (a square a few times the gap, at least 10 cm), where a particle on a
  // sphere's surface and its arrows are not lost in the sphere's size.
  const double extent = std::max({hi_x - lo_x, hi_y - lo_y, 0.2});
  const double span = 1.8 * extent;
  const double mid_x = (lo_x + hi_x) / 2, mid_y = (lo_y + hi_y) / 2;
  double cx = 0, cy = 0, gap = 0;
  const bool zoom = contactPoint(bodies, cx, cy, gap);
  const double zoom_span = std::max(0.1, 6 * std::abs(gap));
  const double width = 2 * kMargin + kSide + (zoom ? kGap + kSide : 0);
  const double height = kTitle + kSide + kLegend + kMargin;
  const std::array<std::pair<std::string, std::string>, 3> kinds = {
      {{"before", "#888"}, {"course", "#2a7a2a"}, {"yours", "#c0392b"}}};
  static std::atomic<unsigned long> sketches{0};
  const std::string id = "gr-sketch-" + std::to_string(sketches++);
  std::string out = sketchSvgStart(width, height, "the state tried", {kinds.begin(), kinds.end()});
  std::vector<Box> labels;
  out += fmt::format(R"(<text x="{}" y="12" font-size="11" fill="#555">the bodies, front view )"
                     R"((x right, y up)</text>)",
                     kMargin);
  out += bodiesPanel(bodies, mid_x - span / 2, mid_y - span / 2, span, kMargin, kTitle, kSide,
                     id + "-all", labels);
  if (zoom) {
    const double left = kMargin + kSide + kGap;
    out += fmt::format(R"(<text x="{}" y="12" font-size="11" fill="#555">around the contact, )"
                       R"({:.0f} cm across</text>)",
                       left, zoom_span * 100);
    labels.clear();
    out += bodiesPanel(bodies, cx - zoom_span / 2, cy - zoom_span / 2, zoom_span, left, kTitle,
                       kSide, id + "-near", labels);
  }
  out += fmt::format(
      R"(<text x="{0}" y="{1}" font-size="11"><tspan fill="#888">&#8594; velocity before</tspan> )"
      R"(<tspan fill="#2a7a2a">&#8594; after the course's collide</tspan> )"
      R"(<tspan fill="#c0392b">&#8594; after yours</tspan></text>)"
      R"(<text x="{0}" y="{2}" font-size="11" fill="#555">arrows on one scale per panel; the )"
      R"(numbers below give x, y and z</text></svg>)",
      kMargin, kTitle + kSide + 16, kTitle + kSide + 30);
  return out;
}

std::string springsSvg(const Sketch& sketch) {
  const int n = sketch.grid;
  constexpr double kSide = 260, kMargin = 12, kLegend = 48;
  const double cell = (kSide - 2 * kMargin) / std::max(1, n - 1);
  const auto px = [&](int index) { return kMargin + (index % n) * cell; };
  const auto py = [&](int index) { return kMargin + (index / n) * cell; };
  std::string out = sketchSvgStart(kSide, kSide + kLegend, "the springs that differ", {});
  // Every particle as a dot, row 0 at the top as the course numbers them (i * n + j).
  for (int index = 0; index < n * n; ++index)
    out += fmt::format(R"(<circle cx="{:.1f}" cy="{:.1f}" r="1.5" fill="#999"/>)", px(index),
                       py(index));
  // One path per kind (a spring is "Mx yLx y"): a page stays small when every spring is wrong.
  const auto springs = [&](const std::vector<std::array<int, 2>>& pairs, const char* kind,
                           const char* style) {
    std::string path;
    for (const auto& [a, b] : pairs)
      if (a >= 0 && b >= 0 && a < n * n && b < n * n)  // outside the cloth: only in the text
        path += fmt::format("M{:.1f} {:.1f}L{:.1f} {:.1f}", px(a), py(a), px(b), py(b));
    if (!path.empty())
      out += fmt::format(R"(<path class="gr-{}" d="{}" fill="none" {}/>)", kind, path, style);
  };
  springs(sketch.missing, "missing",
          R"(stroke="#2a7a2a" stroke-width="1.5" stroke-dasharray="3,2")");
  springs(sketch.unexpected, "unexpected", R"(stroke="#c0392b" stroke-width="1.5")");
  springs(sketch.differing, "differing", R"(stroke="#d68910" stroke-width="2")");
  out += fmt::format(
      R"(<text x="{0}" y="{1}" font-size="10"><tspan fill="#2a7a2a">- - missing ({4})</tspan> )"
      R"(<tspan fill="#c0392b">&#8212; only yours ({5})</tspan></text>)"
      R"(<text x="{0}" y="{2}" font-size="10" fill="#d68910">&#8212; {6} ({7})</text>)"
      R"(<text x="{0}" y="{3}" font-size="10" fill="#555">{8} x {8} cloth, row 0 at the top</text>)"
      R"(</svg>)",
      kMargin, kSide + kLegend - 34, kSide + kLegend - 20, kSide + kLegend - 6,
      sketch.missing.size(), sketch.unexpected.size(), pages::escapeHtml(sketch.differing_means),
      sketch.differing.size(), n);
  return out;
}

}  // namespace

std::string stateSketchSvg(const Sketch& sketch) {
  if (!sketch.bodies.empty()) return bodiesSvg(sketch.bodies);
  // A grid past this size would be dots only; the text lists the springs.
  if (sketch.grid >= 2 && sketch.grid <= 100) return springsSvg(sketch);
  return {};
}

std::string markdownToHtml(std::string_view markdown) {
  std::string out;
  std::istringstream lines{std::string(markdown)};
  std::string line;
  std::size_t fence = 0;  // the open fence's length, 0 outside a code block
  bool list = false, paragraph = false, table = false;
  const auto close = [&] {
    if (list) out += "</ul>\n";
    if (paragraph) out += "</p>\n";
    if (table) out += "</table>\n";
    list = paragraph = table = false;
  };
  // "| a | b |" rows: the first is the header, a "|---|" row under it is dropped.
  const auto cells = [](const std::string& row) {
    std::vector<std::string> found;
    std::size_t start = row.find('|') + 1;
    for (std::size_t bar; (bar = row.find('|', start)) != std::string::npos; start = bar + 1) {
      const std::string cell = row.substr(start, bar - start);
      const std::size_t first = cell.find_first_not_of(' ');
      found.push_back(first == std::string::npos
                          ? std::string()
                          : cell.substr(first, cell.find_last_not_of(' ') - first + 1));
    }
    return found;
  };
  while (std::getline(lines, line)) {
    const std::size_t run = backtickRun(line, 0);
    // a fence opens with three backticks or more and closes with a line of as many or more
    if (!fence && run >= 3) {
      close();
      out += "<pre><code>";
      fence = run;
      continue;
    }
    if (fence && run >= fence && line.find_first_not_of("` ", run) == std::string::npos) {
      out += "</code></pre>\n";
      fence = 0;
      continue;
    }
    if (fence) {
      out += pages::escapeHtml(line) + "\n";
      continue;
    }
    if (line.find_first_not_of(" \t") == std::string::npos) {
      close();
      continue;
    }
    const std::size_t indent = line.find_first_not_of(' ');
    if (line[indent] == '|' && line.find('|', indent + 1) != std::string::npos) {
      if (line.find_first_not_of("|-: ") == std::string::npos) continue;  // the separator row
      const bool header = !table;
      if (!table) close();
      if (!table) out += "<table>\n";
      table = true;
      out += "<tr>";
      for (const std::string& cell : cells(line))
        out += (header ? "<th>" : "<td>") + inlineMarkdown(cell) +
               (header ? "</th>" : "</td>");
      out += "</tr>\n";
      continue;
    }
    if (table) out += "</table>\n";
    table = false;
    if (line.compare(indent, 2, "- ") == 0) {
      line.erase(0, indent);
      if (paragraph) out += "</p>\n";
      paragraph = false;
      if (!list) out += "<ul>\n";
      list = true;
      out += "<li>" + inlineMarkdown(std::string_view(line).substr(2)) + "</li>\n";
      continue;
    }
    if (list) out += "</ul>\n";
    list = false;
    if (line.rfind("#", 0) == 0) {
      if (paragraph) out += "</p>\n";
      paragraph = false;
      out += "<p><strong>" + inlineMarkdown(line.substr(line.find_first_not_of('#'))) +
             "</strong></p>\n";
      continue;
    }
    out += (paragraph ? "\n" : "<p>") + inlineMarkdown(line);
    paragraph = true;
  }
  if (fence) out += "</code></pre>\n";
  close();
  return out;
}

GradeReport gradeWithWholeRun(const fs::path& dir, const GradeOptions& options,
                              nlohmann::ordered_json& whole_run_view) {
  whole_run_view = nullptr;
  GradeReport report = gradeSubmission(dir, options);
  for (const TestResult& t : report.tests) {
    if (!t.traces) continue;
    try {
      // the traces as the probe kept them, named for the page (never a path of ours)
      std::istringstream reference(t.traces->reference), student(t.traces->student);
      pages::ViewOptions view;
      view.labels = {"reference", "your code"};
      whole_run_view =
          pages::viewerData({{"reference", &reference}, {"your run", &student}}, view);
    } catch (const InputError& problem) {
      // a student trace the reader refuses (cut short by a crash) leaves the report without it
      report.notes.push_back("The whole run could not be pictured: " +
                             codeSpan(safeName(problem.what())));
    }
  }
  return report;
}

namespace {

const char* causeClass(const Cause& cause) {
  return cause.likely ? "gr-cause" : "gr-cause gr-guess";
}

// A test's output and causes as HTML: the likely causes and the guesses in blocks of their own.
std::string testHtml(const TestText& text) {
  std::string out = markdownToHtml(text.output);
  for (const auto& [blocks, css] :
       {std::pair{&text.likely, "gr-likely"}, std::pair{&text.guesses, "gr-guesses"}})
    if (!blocks->empty()) {
      out += std::string("<div class=\"") + css + "\">";
      for (const std::string& block : *blocks) out += markdownToHtml(block);
      out += "</div>\n";
    }
  return out;
}

std::string filesHtml(const GradeReport& report) {
  const auto e = [](const std::string& text) { return pages::escapeHtml(text); };
  std::string body =
      "<table class=\"gr-table gr-files\"><tr><th>file</th><th>found at</th><th>used</th></tr>\n";
  for (const UsedFile& f : report.files) {
    std::string used = "yours";
    if (!f.compiled) {
      used = f.status == Verdict::MissingFile ? std::string("ours (yours is missing)")
                                              : "ours (yours: " +
                                                    e(f.problem.substr(0, f.problem.find('\n'))) +
                                                    ")";
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

nlohmann::ordered_json withHtmlSummary(nlohmann::ordered_json results, const GradeReport& given) {
  const GradeReport report = cleaned(given);
  std::string out = "<p><strong>Score " + number(report.score) + " / " + number(report.max_score) +
                    "</strong> (edition " + std::to_string(report.edition) + ", verdict " +
                    std::string(verdictId(report.verdict)) +
                    ")</p>\n<table>\n<tr><th>stub</th>"
                    "<th>points</th><th>checks passed</th></tr>\n";
  for (const std::string& stub : stubNames()) {
    if (!report.stub_max.count(stub)) continue;
    const auto [passed, total] = checksPassed(report, stub);
    out += "<tr><td>" + pages::escapeHtml(stub) + "</td><td>" +
           number(report.stub_score.count(stub) ? report.stub_score.at(stub) : 0) + " / " +
           number(report.stub_max.at(stub)) + "</td><td>" + std::to_string(passed) + " of " +
           std::to_string(total) + "</td></tr>\n";
  }
  out += "</table>\n";
  std::string failed;
  int not_shown = 0;  // failed tests the rubric shows later or never: not named here either
  for (const TestResult& t : report.tests) {
    if (t.passed() || t.informational) continue;
    if (t.visibility != "visible") {
      ++not_shown;
      continue;
    }
    failed += "<li>" + pages::escapeHtml(t.name());
    for (const Cause& cause : t.causes)
      failed += " <em>(" + pages::escapeHtml(cause.id) + (cause.likely ? "" : "?") + ")</em>";
    failed += "</li>\n";
  }
  if (!failed.empty())
    out += "<p>Failed checks (details in each test below; a cause marked ? is a guess):</p>\n<ul>\n" +
           failed + "</ul>\n";
  if (not_shown)
    out += "<p>" + std::to_string(not_shown) + " more failed check" + (not_shown == 1 ? "" : "s") +
           " shown later.</p>\n";
  if (results.contains("output") && results["output"].is_string())
    out += markdownToHtml(results["output"].get<std::string>());
  results["output"] = out;
  results["output_format"] = "html";
  return results;
}

std::string studentReportHtml(const GradeReport& given,
                              const nlohmann::ordered_json& whole_run_view) {
  const GradeReport report = cleaned(given);
  const std::vector<TestText> texts = testTexts(report);
  const auto e = [](const std::string& text) { return pages::escapeHtml(text); };
  std::string body = "<p><strong>Score " + number(report.score) + " / " + number(report.max_score) +
                     "</strong>. Edition " + std::to_string(report.edition) + " (" +
                     e(report.edition_source) + "). Verdict: " +
                     std::string(verdictId(report.verdict)) + ".</p>\n";
  body += filesHtml(report);
  body += notesHtml(report.notes);
  // score per stub, then every check of each stub
  body +=
      "<h2>Stubs</h2>\n<table class=\"gr-table gr-stubs\"><tr><th>stub</th><th>points</th>"
      "<th>checks passed</th></tr>\n";
  for (const std::string& stub : stubNames()) {
    if (!report.stub_max.count(stub)) continue;
    const auto [passed, total] = checksPassed(report, stub);
    body += "<tr><td><a href=\"#" + e(stub) + "\">" + e(stub) + "</a></td><td>" +
            number(report.stub_score.count(stub) ? report.stub_score.at(stub) : 0) + " / " +
            number(report.stub_max.at(stub)) + "</td><td class=\"" +
            (passed == total ? "gr-pass" : "gr-fail") + "\">" + std::to_string(passed) + " of " +
            std::to_string(total) + "</td></tr>\n";
  }
  body += "</table>\n";
  std::string section;
  for (std::size_t k = 0; k < report.tests.size(); ++k) {
    const TestResult& t = report.tests[k];
    if (t.stub != section) {
      section = t.stub;
      body += "<h2 id=\"" + e(t.stub) + "\">" + e(t.stub) + "</h2>\n";
    }
    const char* state = t.informational ? "gr-info" : t.passed() ? "gr-pass" : "gr-fail";
    const char* mark = t.informational ? "\xE2\x84\xB9"
                       : t.passed()    ? "\xE2\x9C\x94"
                                       : "\xE2\x9C\x98";
    const bool open = !t.passed() && !t.informational;  // the whole run: its status in the summary
    body += std::string("<details class=\"gr-check\"") + (open ? " open" : "") +
            "><summary class=\"" + state + "\">" + mark + " " + e(t.check) +
            (t.informational
                 ? std::string(t.check.find("information only") == std::string::npos
                                   ? " (information only)"
                                   : "") +
                       " \xE2\x80\x94 " + kInformationStatus[t.passed() ? 1 : 0]
                 : " \xE2\x80\x94 " + number(t.score) + " / " + number(t.max_score));
    for (const Cause& cause : t.causes)
      body += std::string("<span class=\"") + causeClass(cause) + "\"" +
              (cause.likely ? "" : " title=\"a guess\"") + ">" + e(cause.id) +
              (cause.likely ? "" : "?") + "</span>";
    body += "</summary>\n" + stateSketchSvg(t.sketch) + testHtml(texts[k]) + "</details>\n";
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

std::string batchIndexHtml(const fs::path& batch_dir, const std::vector<BatchRow>& rows) {
  nlohmann::ordered_json data;
  data["stubs"] = stubNames();
  std::vector<std::string> checks;           // every check name, in order of first appearance
  std::map<std::string, std::size_t> index;  // check name -> position in `checks`
  nlohmann::ordered_json submissions = nlohmann::ordered_json::array();
  for (const BatchRow& row : rows) {
    nlohmann::ordered_json s = rowJson(row);  // the marker's fields, then the page's own
    s.erase("dir");                           // where it was graded: not for the page
    s.erase("isolation");
    std::error_code error;
    s["report"] =
        row.name +
        (fs::exists(batch_dir / row.name / "report.html", error) ? "/report.html" : "/report.md");
    // per check: passed, failed; the named causes (extra_data's, with whether each is likely;
    // else a test's tags after its stub)
    nlohmann::ordered_json passed = nlohmann::ordered_json::object();
    std::vector<std::pair<std::string, bool>> causes;  // id, likely on some test
    const auto name_cause = [&](const std::string& id, bool likely) {
      for (auto& [known, was_likely] : causes)
        if (known == id) {
          was_likely = was_likely || likely;
          return;
        }
      causes.push_back({id, likely});
    };
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
    nlohmann::ordered_json cause_list = nlohmann::ordered_json::array();
    for (const auto& [id, likely] : causes) cause_list.push_back({{"id", id}, {"likely", likely}});
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
