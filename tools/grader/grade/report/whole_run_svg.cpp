// The whole run as a static SVG (whole_run_svg.h).
#include "grader/grade/report/whole_run_svg.h"

#include <algorithm>
#include <cmath>
#include <exception>
#include <map>
#include <sstream>
#include <tuple>
#include <vector>

#include <fmt/format.h>

#include "clothref/trace/reader.h"

namespace clothref::grader {
namespace {

constexpr double kSide = 300, kGap = 40, kMargin = 10, kTitle = 16, kLegend = 34;

struct Run {
  TraceHeader header;
  std::map<std::int64_t, TraceStep> steps;  // by step number
};

Run readRun(const std::string& text, const std::string& name) {
  std::istringstream in(text);
  TraceReader reader(in, name);
  Run run{reader.header(), {}};
  while (reader.next()) reader.parseStep(run.steps[reader.prefix().step]);
  return run;
}

bool allFinite(const TraceStep& step) {
  for (const BodyState& body : step.bodies)
    for (double v : body.position)
      if (!std::isfinite(v)) return false;
  return true;
}

// The largest distance between the two runs' particles at one step; infinity when a value of
// either is not finite.
double largestDistance(const TraceStep& a, const TraceStep& b) {
  double largest = 0;
  for (std::size_t body = 0; body < a.bodies.size() && body < b.bodies.size(); ++body) {
    const auto& pa = a.bodies[body].position;
    const auto& pb = b.bodies[body].position;
    for (std::size_t k = 0; k + 2 < pa.size() && k + 2 < pb.size(); k += 3) {
      const double d = std::hypot(pa[k] - pb[k], pa[k + 1] - pb[k + 1], pa[k + 2] - pb[k + 2]);
      largest = std::isfinite(d) ? std::max(largest, d) : INFINITY;
    }
  }
  return largest;
}

// The radii of the header's spheres (scene.spheres.items[k].radius), 0 where not given.
std::vector<double> sphereRadii(const TraceHeader& header) {
  std::vector<double> radii;
  const auto scene = header.json.value("scene", nlohmann::ordered_json::object());
  if (!scene.is_object() || !scene.contains("spheres") || !scene["spheres"].is_object()) return {};
  const auto items = scene["spheres"].value("items", nlohmann::ordered_json::array());
  for (const auto& item : items)
    radii.push_back(item.is_object() && item.contains("radius") && item["radius"].is_number()
                        ? item["radius"].get<double>()
                        : 0.0);
  return radii;
}

// The front view (x right, y up) of both runs at one step: the reference's cloth as grey dots and
// spheres filled, the student's as red dots and red outlines.
std::string frontPanel(const TraceHeader& header, const TraceStep& reference,
                       const TraceStep& student, const std::string& id) {
  const std::vector<double> radii = sphereRadii(header);
  double lo_x = 1e30, hi_x = -1e30, lo_y = 1e30, hi_y = -1e30;
  const auto extend = [&](double x, double y, double r) {
    if (!std::isfinite(x) || !std::isfinite(y)) return;
    lo_x = std::min(lo_x, x - r), hi_x = std::max(hi_x, x + r);
    lo_y = std::min(lo_y, y - r), hi_y = std::max(hi_y, y + r);
  };
  for (const TraceStep* step : {&reference, &student})
    for (std::size_t body = 0; body < step->bodies.size() && body < header.bodies.size(); ++body) {
      const bool spheres = header.bodies[body].name == "spheres";
      const auto& p = step->bodies[body].position;
      for (std::size_t k = 0; k + 2 < p.size(); k += 3)
        extend(p[k], p[k + 1], spheres && k / 3 < radii.size() ? radii[k / 3] : 0);
    }
  if (lo_x > hi_x) return {};
  const double span = std::max(0.1, 1.1 * std::max(hi_x - lo_x, hi_y - lo_y));
  const double mid_x = (lo_x + hi_x) / 2, mid_y = (lo_y + hi_y) / 2, scale = kSide / span;
  const auto px = [&](double x) { return kMargin + kSide / 2 + (x - mid_x) * scale; };
  const auto py = [&](double y) { return kTitle + kSide / 2 - (y - mid_y) * scale; };
  std::string out = fmt::format(
      R"(<clipPath id="{0}-front"><rect x="{1}" y="{2}" width="{3}" height="{3}"/></clipPath>)"
      R"(<rect x="{1}" y="{2}" width="{3}" height="{3}" fill="none" stroke="#ddd"/>)"
      R"svg(<g clip-path="url(#{0}-front)">)svg",
      id, kMargin, kTitle, kSide);
  for (const auto& [step, dots, sphere_style] :
       {std::tuple{&reference, "#999", R"(fill="#dce8f5" stroke="#5b7fa6")"},
        std::tuple{&student, "#c0392b",
                   R"(fill="none" stroke="#c0392b" stroke-dasharray="4,2")"}}) {
    std::string path;  // one path of zero-length strokes: a dot per particle, a small picture
    for (std::size_t body = 0; body < step->bodies.size() && body < header.bodies.size(); ++body) {
      const auto& p = step->bodies[body].position;
      const bool spheres = header.bodies[body].name == "spheres";
      for (std::size_t k = 0; k + 2 < p.size(); k += 3) {
        if (!std::isfinite(p[k]) || !std::isfinite(p[k + 1])) continue;
        if (spheres && k / 3 < radii.size() && radii[k / 3] > 0)
          out += fmt::format(R"(<circle cx="{:.1f}" cy="{:.1f}" r="{:.1f}" {}/>)", px(p[k]),
                             py(p[k + 1]), radii[k / 3] * scale, sphere_style);
        else
          path += fmt::format("M{:.1f} {:.1f}h0", px(p[k]), py(p[k + 1]));
      }
    }
    if (!path.empty())
      out += fmt::format(
          R"(<path d="{}" stroke="{}" stroke-width="3" stroke-linecap="round" fill="none"/>)", path,
          dots);
  }
  return out + "</g>";
}

// The largest distance at every common step, log scale; 0 on the bottom edge, not finite on the
// top edge (a cross).
std::string distancePanel(const std::vector<double>& t, const std::vector<double>& distance) {
  double smallest = INFINITY, largest = 0;
  for (double d : distance)
    if (d > 0 && std::isfinite(d)) smallest = std::min(smallest, d), largest = std::max(largest, d);
  if (largest == 0) smallest = largest = 1e-6;  // all equal or all broken: any decade will do
  const int lo = int(std::floor(std::log10(smallest)));
  const int hi = std::max(lo + 1, int(std::ceil(std::log10(largest))));
  const double left = kMargin + kSide + kGap, top = kTitle, width = kSide - 10, height = kSide - 24;
  const double t0 = t.front(), t1 = std::max(t.back(), t0 + 1e-12);
  const auto px = [&](double time) { return left + (time - t0) / (t1 - t0) * width; };
  const auto py = [&](double d) {
    if (!(d > 0)) return top + height;
    if (!std::isfinite(d)) return top;
    return top + height - (std::log10(d) - lo) / (hi - lo) * height;
  };
  std::string out =
      fmt::format(R"(<rect x="{}" y="{}" width="{}" height="{}" fill="none" stroke="#ddd"/>)", left,
                  top, width, height);
  const int every = (hi - lo) > 6 ? 2 : 1;
  for (int decade = lo; decade <= hi; decade += every)
    out += fmt::format(
        R"(<line x1="{0:.1f}" y1="{1:.1f}" x2="{2:.1f}" y2="{1:.1f}" stroke="#eee"/>)"
        R"(<text x="{3:.1f}" y="{4:.1f}" font-size="9" fill="#555" text-anchor="end">1e{5}</text>)",
        left, py(std::pow(10.0, decade)), left + width, left - 2, py(std::pow(10.0, decade)) + 3,
        decade);
  out += fmt::format(
      R"(<text x="{0:.1f}" y="{1:.1f}" font-size="9" fill="#555">{2:g}</text>)"
      R"(<text x="{3:.1f}" y="{1:.1f}" font-size="9" fill="#555" text-anchor="end">{4:g} s</text>)",
      left, top + height + 11, t0, left + width, t1);
  std::string line;
  for (std::size_t k = 0; k < t.size(); ++k) {
    const double x = px(t[k]), y = py(distance[k]);
    line += fmt::format("{}{:.1f},{:.1f}", line.empty() ? "" : " ", x, y);
    out += !std::isfinite(distance[k])
               ? fmt::format(R"(<path d="M{0:.1f} {1:.1f}l6 6m0 -6l-6 6" stroke="#c0392b"/>)",
                             x - 3, y - 3)
               : fmt::format(
                     R"(<circle cx="{:.1f}" cy="{:.1f}" r="2.5" {}/>)", x, y,
                     distance[k] > 0 ? R"(fill="#c0392b")" : R"(fill="#fff" stroke="#2a7a2a")");
  }
  return fmt::format(R"(<polyline points="{}" fill="none" stroke="#c0392b"/>)", line) + out;
}

}  // namespace

std::string wholeRunSvg(const TestResult::Traces& traces, const std::string& id) {
  Run reference, student;
  try {
    reference = readRun(traces.reference, "the reference");
    student = readRun(traces.student, "your run");
  } catch (const std::exception&) {
    return {};  // a trace cut short: the text says where the run ended
  }
  std::vector<double> t, distance;
  const TraceStep* shown_reference = nullptr;
  const TraceStep* shown_student = nullptr;
  for (const auto& [step, state] : reference.steps) {
    const auto other = student.steps.find(step);
    if (other == student.steps.end()) continue;
    t.push_back(state.prefix.t);
    distance.push_back(largestDistance(state, other->second));
    if (allFinite(other->second)) shown_reference = &state, shown_student = &other->second;
  }
  if (t.empty() || !shown_reference) return {};
  const double width = 2 * kMargin + 2 * kSide + kGap, height = kTitle + kSide + kLegend;
  std::string out = fmt::format(
      R"(<svg class="gr-sketch gr-whole-run" xmlns="http://www.w3.org/2000/svg" width="{0}" )"
      R"(height="{1}" viewBox="0 0 {0} {1}" style="max-width: 100%; height: auto" role="img" )"
      R"(aria-label="your whole run beside the reference's">)",
      width, height);
  out += fmt::format(
      R"(<text x="{}" y="12" font-size="11" fill="#555">front view at step {} (t = {:g} s))"
      R"(</text><text x="{}" y="12" font-size="11" fill="#555">largest distance to the )"
      R"(reference (m), log scale</text>)",
      kMargin, shown_reference->prefix.step, shown_reference->prefix.t,
      kMargin + kSide + kGap - 30);
  out += frontPanel(reference.header, *shown_reference, *shown_student, id);
  out += distancePanel(t, distance);
  out += fmt::format(
      R"(<text x="{0}" y="{1}" font-size="11"><tspan fill="#5b7fa6">&#9679; the reference</tspan> )"
      R"(<tspan fill="#c0392b">&#9679; your run</tspan></text>)"
      R"(<text x="{0}" y="{2}" font-size="11" fill="#555">a hollow point: no distance at all )"
      R"((identical); a cross: a value that is not finite</text></svg>)",
      kMargin, kTitle + kSide + 14, kTitle + kSide + 28);
  return out;
}

}  // namespace clothref::grader
