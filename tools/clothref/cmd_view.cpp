// clothref view A.jsonl [B.jsonl] -o view.html: one self-contained HTML page that plays a trace
// (cloth as a shaded mesh, spheres, orbit camera, time slider) or compares two: each cloth particle
// coloured by its distance to the other trace, the first differing step marked on the slider, the
// largest difference over time (tools/pages/, docs/pictures.md). No network at view time.
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "clothref/io/error.h"
#include "clothref/io/output_file.h"
#include "commands.h"
#include "pages/view_data.h"

namespace clothref::cli {

namespace {

struct ViewCommandOptions {
  std::vector<std::string> traces;
  std::string output;
  std::string title;
  pages::ViewOptions view;
  bool quiet = false;
};

int runView(const ViewCommandOptions& o) {
  if (o.output.empty()) throw InputError("-o: an output file is required (e.g. -o view.html)");
  pages::ViewSummary summary;
  const nlohmann::ordered_json data = pages::viewerData(o.traces, o.view, &summary);
  std::string title = o.title;
  if (title.empty())
    for (const auto& trace : data["traces"])
      title += (title.empty() ? "" : " vs ") + trace["label"].get<std::string>();
  const std::string page = pages::viewerPage(data, title);
  OutputFile file(o.output);
  file.stream() << page;
  file.commit();
  if (!o.quiet) {
    std::cerr << fmt::format("clothref view: {} frames of {} recorded steps, {:.2f} MB",
                             summary.frames, summary.recorded, double(page.size()) / 1e6);
    if (o.traces.size() == 2)
      std::cerr << (summary.first_difference
                        ? fmt::format("; first difference at step {}, largest {:.3g} m",
                                      *summary.first_difference, summary.largest_difference)
                        : std::string("; the traces' states are identical"));
    std::cerr << '\n';
  }
  return kExitOk;
}

}  // namespace

Command addViewCommand(CLI::App& root) {
  CLI::App* app = root.add_subcommand(
      "view",
      "Write one self-contained HTML page that plays a trace in 3-D, or compares two (distance "
      "colouring, first difference, largest difference over time); docs/pictures.md");
  auto options = std::make_shared<ViewCommandOptions>();
  app->add_option("traces", options->traces,
                  "One trace, or two to compare (- is standard input; .gz is read as gzip)")
      ->required()
      ->expected(1, 2);
  app->add_option("-o,--output", options->output, "The HTML file to write");
  app->add_option("--labels", options->view.labels, "Names of the traces on the page");
  app->add_option("--title", options->title, "Page title (default: the labels)");
  app->add_option("--max-frames", options->view.max_frames,
                  "Frames the page holds, evenly spread (0: as many as fit about 3.6 MB)")
      ->capture_default_str();
  app->add_flag("-q,--quiet", options->quiet, "No summary line on stderr");
  return {app, [options] { return runView(*options); }};
}

}  // namespace clothref::cli
