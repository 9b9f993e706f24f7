// The whole run as a static SVG, for the check's output in results.json, where the report page's
// viewer (a script) cannot run (docs/pictures.md): no script, no style element, nothing loaded,
// no text from the student.
#pragma once
#include <string>

#include "grader/grade/results.h"

namespace clothref::grader {

// Two panels: the student's bodies (red) over the reference's (grey) at the last recorded step
// where every value of the student's run is finite, seen from the front (x right, y up), and the
// largest distance of a student's particle to the reference's at every recorded step both runs
// have, on a log scale (0 and non-finite drawn on the axes' edges). "" when the traces cannot be
// read or share no recorded step. `id` starts every id the picture defines.
std::string wholeRunSvg(const TestResult::Traces& traces, const std::string& id);

}  // namespace clothref::grader
