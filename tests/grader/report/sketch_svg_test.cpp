// The pictures of a failed check's state (tools/grader/grade/report/sketch_svg.cpp): static SVG,
// drawn from the numbers, in the report page and in results.json.
#include "grader/grade/report/sketch_svg.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "report_samples.h"

namespace clothref::grader {
namespace {

using test_samples::countOf;
using test_samples::sampleSketch;

// A failed collision check's state, in two panels (the whole scene, and the contact up close): in
// each one circle per sphere, a dot per particle, three arrows per body, nothing but static SVG;
// a check without a sketch gets no picture.
TEST(SketchSvg, AFailedCollisionCheckGetsASmallPictureOfTheStateTried) {
  Sketch sketch = sampleSketch(true);
  const std::string svg = stateSketchSvg(sketch, "s");
  ASSERT_EQ(svg.rfind("<svg ", 0), 0u) << svg;
  EXPECT_EQ(countOf(svg, "<circle "), 4u);
  EXPECT_EQ(countOf(svg, "r=\"3.5\""), 2u);  // the particle's dot
  EXPECT_EQ(countOf(svg, "<line "), 12u);
  EXPECT_EQ(countOf(svg, "marker-end=\"url(#s-yours)\""), 4u);
  EXPECT_NE(svg.find(">particle 312</text>"), std::string::npos);
  EXPECT_NE(svg.find("around the contact"), std::string::npos);
  EXPECT_EQ(svg.find("<script"), std::string::npos);
  EXPECT_EQ(svg.find("nan"), std::string::npos);
  // a non-finite velocity loses its arrow, never the picture; a non-finite position, the picture
  sketch.bodies[1].v_actual = {std::nanf(""), 0, 0};
  const std::string without_arrow = stateSketchSvg(sketch, "s");
  EXPECT_EQ(countOf(without_arrow, "<line "), 10u);
  EXPECT_EQ(without_arrow.find("nan"), std::string::npos);
  sketch.bodies[1].x = {std::nanf(""), 0, 0};
  EXPECT_EQ(stateSketchSvg(sketch, "s"), "");
  EXPECT_EQ(stateSketchSvg(Sketch{}, "s"), "");
}

// Labels never cover each other: a particle on a sphere's surface, a second sphere touching the
// first, and a second particle beside the first (the cases' usual shapes), in both panels.
TEST(SketchSvg, SketchLabelsNeverCoverEachOther) {
  Sketch sketch;
  sketch.bodies.push_back({"sphere 0", {0, 0.5f, 0}, 0.5f, {0, -1, 0}, {0, 0, 0}, {0, -1, 0}});
  sketch.bodies.push_back({"sphere 1", {0.95f, 0.5f, 0}, 0.5f, {0, 0, 0}, {0, 0, 0}, {0, 0, 0}});
  sketch.bodies.push_back({"particle 312", {0, 0, 0}, 0, {0, 0.2f, 0}, {0, 0, 0}, {0, 0.2f, 0}});
  sketch.bodies.push_back({"particle 313", {0.02f, 0.01f, 0}, 0, {0, 0, 0}, {0, 0, 0}, {0, 0, 0}});
  const std::string svg = stateSketchSvg(sketch, "s");
  ASSERT_FALSE(svg.empty());
  // every label: x, y of its baseline and its text, per panel (the second panel starts at x 326)
  struct Label {
    double x, y;
    std::string text;
  };
  std::vector<Label> found;
  const std::string open = "<text x=\"";
  for (std::size_t at = svg.find(open); at != std::string::npos; at = svg.find(open, at + 1)) {
    const double x = std::stod(svg.substr(at + open.size()));
    const std::size_t y_at = svg.find("y=\"", at) + 3;
    const double y = std::stod(svg.substr(y_at));
    const std::size_t text_at = svg.find('>', at) + 1;
    const std::string text = svg.substr(text_at, svg.find('<', text_at) - text_at);
    if (text.rfind("sphere ", 0) == 0 || text.rfind("particle ", 0) == 0)
      found.push_back({x, y, text});
  }
  EXPECT_GE(found.size(), 4u) << svg;  // all four in the overview at least
  for (std::size_t i = 0; i < found.size(); ++i)
    for (std::size_t j = i + 1; j < found.size(); ++j) {
      const Label& a = found[i];
      const Label& b = found[j];
      const bool apart = a.x + 6.2 * double(a.text.size()) <= b.x ||
                         b.x + 6.2 * double(b.text.size()) <= a.x || a.y <= b.y - 12 ||
                         b.y <= a.y - 12;
      EXPECT_TRUE(apart) << a.text << " at " << a.x << "," << a.y << " covers " << b.text << " at "
                         << b.x << "," << b.y;
    }
}

// A failed springs check: the grid's dots and one line per spring that differs, each kind in its
// own style and counted in the legend; springs outside the cloth are left to the text.
TEST(SketchSvg, AFailedSpringsCheckGetsTheGridWithTheSpringsThatDiffer) {
  Sketch sketch;
  sketch.grid = 4;
  sketch.missing = {{0, 5}, {1, 6}};
  sketch.unexpected = {{0, 2}, {3, 99}};  // 99 is outside a 4 x 4 cloth
  sketch.differing = {{4, 5}};
  sketch.differing_means = "wrong <label>";
  const std::string svg = stateSketchSvg(sketch, "s");
  ASSERT_EQ(svg.rfind("<svg ", 0), 0u) << svg;
  EXPECT_EQ(countOf(svg, "<circle "), 16u);
  // one path per kind, one "M" per spring drawn
  const auto springsDrawn = [&](const std::string& kind) {
    const std::string start = "<path class=\"gr-" + kind + "\" d=\"";
    const std::size_t at = svg.find(start);
    if (at == std::string::npos) return std::size_t{0};
    const std::size_t from = at + start.size();
    return countOf(svg.substr(from, svg.find('"', from) - from), "M");
  };
  EXPECT_EQ(springsDrawn("missing"), 2u);
  EXPECT_EQ(springsDrawn("unexpected"), 1u);
  EXPECT_EQ(springsDrawn("differing"), 1u);
  EXPECT_NE(svg.find("missing (2)"), std::string::npos) << svg;
  EXPECT_NE(svg.find("only yours (2)"), std::string::npos) << svg;
  EXPECT_NE(svg.find("wrong &lt;label&gt; (1)"), std::string::npos) << svg;
  EXPECT_EQ(svg.find("<label>"), std::string::npos);
  // a passed check (no grid, no bodies) and a cloth too large to draw get none
  sketch.grid = 0;
  EXPECT_EQ(stateSketchSvg(sketch, "s"), "");
  sketch.grid = 1000;
  EXPECT_EQ(stateSketchSvg(sketch, "s"), "");
}

// Every id a picture defines starts with the id it is given: two pictures of one page (two failed
// checks, on Gradescope every test of a submission) never share an arrow head or a clip path.
TEST(SketchSvg, EveryIdStartsWithThePicturesOwn) {
  Sketch sketch;
  sketch.bodies.push_back({"sphere 0", {0, 0.5f, 0}, 0.5f, {0, -1, 0}, {0, 0, 0}, {0, -1, 0}});
  sketch.bodies.push_back({"particle 3", {0, 0.02f, 0}, 0, {0, 1, 0}, {0, 0, 0}, {0, 1, 0}});
  const std::string a = stateSketchSvg(sketch, "gr-test-3");
  ASSERT_FALSE(a.empty());
  std::size_t ids = 0;
  for (std::size_t at = a.find(" id=\""); at != std::string::npos; at = a.find(" id=\"", at + 1)) {
    ++ids;
    EXPECT_EQ(a.compare(at + 5, 10, "gr-test-3-"), 0) << a.substr(at, 40);
  }
  EXPECT_GE(ids, 5u);  // three arrow heads, two clip paths
  EXPECT_EQ(countOf(a, "url(#gr-test-3-"), countOf(a, "url(#"));
  // the same state, the same picture: nothing depends on what was drawn before
  EXPECT_EQ(stateSketchSvg(sketch, "gr-test-3"), a);
}

}  // namespace
}  // namespace clothref::grader
