// The state a failed check tried, as a small static SVG (sketch_svg.h).
#include "grader/grade/report/sketch_svg.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <utility>
#include <vector>

#include <fmt/format.h>

#include "pages/html.h"

namespace clothref::grader {
namespace {

// The opening of a sketch's <svg> and its arrow-head markers, one per colour.
std::string sketchSvgStart(double width, double height, const char* label,
                           const std::vector<std::pair<std::string, std::string>>& markers,
                           const std::string& id) {
  // max-width: a narrow column (Gradescope's) scales the picture down instead of cutting it
  std::string out = fmt::format(
      R"(<svg class="gr-sketch" xmlns="http://www.w3.org/2000/svg" width="{0}" height="{1}" )"
      R"(viewBox="0 0 {0} {1}" style="max-width: 100%; height: auto" role="img" )"
      R"(aria-label="{2}"><defs>)",
      width, height, label);
  for (const auto& [name, colour] : markers)
    out += fmt::format(
        R"(<marker id="{2}-{0}" viewBox="0 0 8 8" refX="7" refY="4" markerWidth="6" )"
        R"(markerHeight="6" orient="auto"><path d="M0,0 L8,4 L0,8 z" fill="{1}"/></marker>)",
        name, colour, id);
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
std::string bodiesPanel(const std::vector<SketchBody>& bodies, double lo_x, double lo_y,
                        double span, double left, double top, double side, const std::string& id,
                        const std::string& clip, std::vector<Box>& labels) {
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
               : fmt::format(R"(<circle cx="{:.1f}" cy="{:.1f}" r="3.5" fill="#333"/>)", px(b.x[0]),
                             py(b.x[1]));
  for (const SketchBody& b : bodies) {
    const std::array<const std::array<float, 3>*, 3> velocities = {&b.v, &b.v_expected,
                                                                   &b.v_actual};
    for (std::size_t k = 0; k < kinds.size(); ++k) {
      const auto& v = *velocities[k];
      if (!std::isfinite(v[0]) || !std::isfinite(v[1])) continue;  // NaN loses its arrow only
      out += fmt::format(R"(<line x1="{:.1f}" y1="{:.1f}" x2="{:.1f}" y2="{:.1f}" stroke="{}" )"
                         R"svg(stroke-width="2" marker-end="url(#{}-{})"/>)svg",
                         px(b.x[0]), py(b.x[1]), px(b.x[0] + v[0] * arrow),
                         py(b.x[1] + v[1] * arrow), kinds[k].second, id, kinds[k].first);
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
    const std::array<std::pair<double, double>, 5> corners = {
        {{cx + 0.7 * r + 2, cy - 0.7 * r - 2},             // upper right
         {cx - 0.7 * r - 2 - width, cy - 0.7 * r - 2},     // upper left
         {cx + 0.7 * r + 2, cy + 0.7 * r + kLabelHeight},  // lower right
         {cx - 0.7 * r - 2 - width, cy + 0.7 * r + kLabelHeight},
         {cx - width / 2, cy + 4}}};  // on the centre
    Box chosen{};
    bool placed = false;
    for (const auto& [x, y] : corners) {
      const Box box{x, y - kLabelHeight + 2, x + width, y + 2};
      const bool inside =
          box.x0 >= left && box.x1 <= left + side && box.y0 >= top && box.y1 <= top + side;
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

std::string bodiesSvg(const std::vector<SketchBody>& bodies, const std::string& id) {
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
  std::string out =
      sketchSvgStart(width, height, "the state tried", {kinds.begin(), kinds.end()}, id);
  std::vector<Box> labels;
  out += fmt::format(R"(<text x="{}" y="12" font-size="11" fill="#555">the bodies, front view )"
                     R"((x right, y up)</text>)",
                     kMargin);
  out += bodiesPanel(bodies, mid_x - span / 2, mid_y - span / 2, span, kMargin, kTitle, kSide, id,
                     id + "-all", labels);
  if (zoom) {
    const double left = kMargin + kSide + kGap;
    out += fmt::format(R"(<text x="{}" y="12" font-size="11" fill="#555">around the contact, )"
                       R"({:.0f} cm across</text>)",
                       left, zoom_span * 100);
    labels.clear();
    out += bodiesPanel(bodies, cx - zoom_span / 2, cy - zoom_span / 2, zoom_span, left, kTitle,
                       kSide, id, id + "-near", labels);
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

std::string springsSvg(const Sketch& sketch, const std::string& id) {
  const int n = sketch.grid;
  constexpr double kSide = 260, kMargin = 12, kLegend = 48;
  const double cell = (kSide - 2 * kMargin) / std::max(1, n - 1);
  const auto px = [&](int index) { return kMargin + (index % n) * cell; };
  const auto py = [&](int index) { return kMargin + (index / n) * cell; };
  std::string out = sketchSvgStart(kSide, kSide + kLegend, "the springs that differ", {}, id);
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

std::string stateSketchSvg(const Sketch& sketch, const std::string& id) {
  if (!sketch.bodies.empty()) return bodiesSvg(sketch.bodies, id);
  // A grid past this size would be dots only; the text lists the springs.
  if (sketch.grid >= 2 && sketch.grid <= 100) return springsSvg(sketch, id);
  return {};
}

}  // namespace clothref::grader
