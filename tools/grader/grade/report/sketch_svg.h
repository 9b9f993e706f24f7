// The state a failed check tried, drawn as a small static SVG for the student's report page and
// for the check's output in results.json (docs/pictures.md): no script, no style element, no
// text from the student, nothing loaded.
#pragma once
#include <string>

#include "grader/grade/results.h"

namespace clothref::grader {

// "" for an empty sketch. A collision check: the bodies seen from the front (x right, y up),
// spheres as circles, cloth particles as dots, and from each body its velocity before the call
// (grey), after the course's collide (green) and after the student's (red), all arrows on one
// scale. A springs check: the n x n cloth as dots, row 0 at the top, and the springs the course
// has and the student lacks (green, dashed), that only the student has (red), and that differ
// (orange). `id` starts every id the picture defines (arrow heads, clip paths): one per picture
// of a page, so two pictures never share one.
std::string stateSketchSvg(const Sketch& sketch, const std::string& id);

}  // namespace clothref::grader
