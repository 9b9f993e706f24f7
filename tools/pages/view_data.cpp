#include "pages/view_data.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <memory>
#include <numeric>

#include <fmt/format.h>

#include "clothref/io/error.h"
#include "clothref/trace/reader.h"
#include "pages/html.h"
#include "pages/page_assets.h"

namespace clothref::pages {

namespace {

__extension__ typedef __int128 Wide;  // products of step counts that an int64 cannot hold

bool isRecorded(const TraceHeader& header, std::int64_t step) {
  return step >= 0 && step <= header.steps && (step % header.stride == 0 || step == header.steps);
}

// How many steps `a` and `b` (when given) both record, counted from the headers without listing
// them: a header may claim any number of steps (the reader refuses a file that ends before its
// claim, as diff does), and nothing is allocated for a claim.
std::int64_t commonStepCount(const TraceHeader& a, const TraceHeader* b) {
  if (!b) return a.steps / a.stride + 1 + (a.steps % a.stride != 0 ? 1 : 0);
  const std::int64_t end = std::min(a.steps, b->steps);
  const Wide lcm = Wide(a.stride) / std::gcd(a.stride, b->stride) * b->stride;  // no overflow
  std::int64_t n = std::int64_t(Wide(end) / lcm) + 1;  // the multiples of both, 0 first
  // a last step off the strides that both record (one step when both traces end there)
  const auto counts = [&](std::int64_t last) {
    return last <= end && Wide(last) % lcm != 0 && isRecorded(a, last) && isRecorded(*b, last);
  };
  if (counts(a.steps)) ++n;
  if (b->steps != a.steps && counts(b->steps)) ++n;
  return n;
}

// The index among `n` evenly spread over [0, n) that frame k of `wanted` gets (first and last
// included).
std::int64_t spreadIndex(std::int64_t k, std::int64_t wanted, std::int64_t n) {
  return std::int64_t((2 * Wide(k) * (n - 1) + (wanted - 1)) / (2 * Wide(wanted - 1)));
}

std::string labelOf(const std::string& path) {
  return path == "-" ? "standard input" : std::filesystem::path(path).filename().string();
}

// The same value, as `clothref diff` counts it with its default (bit-exact) tolerance: equal
// numbers (-0 == +0) or both NaN.
bool sameValue(double a, double b) { return a == b || (std::isnan(a) && std::isnan(b)); }

// Distance between two points; infinite when one is not finite and they are not the same value.
double pointDistance(const double* a, const double* b) {
  double sum = 0;
  for (int k = 0; k < 3; ++k) {
    if (sameValue(a[k], b[k])) continue;
    const double d = a[k] - b[k];
    if (!std::isfinite(d)) return INFINITY;
    sum += d * d;
  }
  return std::sqrt(sum);
}

const nlohmann::ordered_json* find(const nlohmann::ordered_json& json, const char* pointer) {
  const nlohmann::ordered_json::json_pointer where(pointer);
  return json.contains(where) ? &json.at(where) : nullptr;
}

// The cloth's faces or edges for the picture: {"grid": n} for a course grid (particle i * n + j),
// {"springs": [start, end, ...]} for a cloth given particle by particle, null when the header says
// neither in a usable form.
nlohmann::ordered_json clothMesh(const TraceHeader& header, std::int64_t particles) {
  const nlohmann::ordered_json& scene =
      header.json.value("scene", nlohmann::ordered_json::object());
  if (!scene.is_object()) return nullptr;
  if (const auto* n = find(scene, "/cloth/grid/particles_per_edge");
      n && n->is_number_integer() && n->get<std::int64_t>() * n->get<std::int64_t>() == particles)
    return {{"grid", n->get<std::int64_t>()}};
  const auto* springs = find(scene, "/cloth/springs");
  if (!springs || !springs->is_array()) return nullptr;
  nlohmann::ordered_json flat = nlohmann::ordered_json::array();
  for (const auto& spring : *springs) {
    const auto start = spring.value("start", std::int64_t(-1));
    const auto end = spring.value("end", std::int64_t(-1));
    if (start < 0 || end < 0 || start >= particles || end >= particles) return nullptr;
    flat.push_back(start);
    flat.push_back(end);
  }
  return {{"springs", flat}};
}

nlohmann::ordered_json sphereRadii(const TraceHeader& header) {
  nlohmann::ordered_json radii = nlohmann::ordered_json::array();
  const nlohmann::ordered_json& scene =
      header.json.value("scene", nlohmann::ordered_json::object());
  if (const auto* items = scene.is_object() ? find(scene, "/spheres/items") : nullptr;
      items && items->is_array())
    for (const auto& item : *items) {
      const auto* r = item.is_object() ? find(item, "/radius") : nullptr;
      radii.push_back(r && r->is_number() ? r->get<double>() : 0.0);
    }
  return radii;
}

nlohmann::ordered_json traceInfo(const TraceReader& reader, const std::string& label) {
  const TraceHeader& h = reader.header();
  const nlohmann::ordered_json& scene = h.json.value("scene", nlohmann::ordered_json::object());
  const auto text = [&](const char* key) {
    return scene.is_object() && scene.contains(key) && scene[key].is_string()
               ? scene[key].get<std::string>()
               : std::string();
  };
  return {{"label", label},
          {"path", reader.path()},
          {"scene", text("name")},
          {"description", text("description")},
          {"integrator", h.integrator},
          {"precision", h.json.value("precision", "")},
          {"dt", h.dt},
          {"steps", h.steps},
          {"stride", h.stride}};
}

}  // namespace

nlohmann::ordered_json viewerData(const std::vector<std::string>& paths, const ViewOptions& options,
                                  ViewSummary* summary) {
  std::vector<TraceSource> sources;
  for (const std::string& path : paths) sources.push_back({path, nullptr});
  return viewerData(sources, options, summary);
}

nlohmann::ordered_json viewerData(const std::vector<TraceSource>& sources,
                                  const ViewOptions& options, ViewSummary* summary) {
  if (sources.empty() || sources.size() > 2)
    throw InputError("view: give one trace, or two to compare (a reference and a student)");
  if (sources.size() == 2 && !sources[0].in && !sources[1].in && sources[0].name == "-" &&
      sources[1].name == "-")
    throw InputError("view: standard input can be read once: give '-' for one of the traces");
  if (!options.labels.empty() && options.labels.size() != sources.size())
    throw InputError(fmt::format("--labels: give one label per trace ({} traces, {} labels)",
                                 sources.size(), options.labels.size()));
  if (options.max_frames == 1 || options.max_frames < 0)
    throw InputError(
        fmt::format("--max-frames: must be 0 (automatic) or >= 2 (got {})", options.max_frames));
  std::vector<std::unique_ptr<TraceReader>> readers;
  for (const TraceSource& source : sources)
    readers.push_back(source.in ? std::make_unique<TraceReader>(*source.in, source.name)
                                : std::make_unique<TraceReader>(source.name));
  const bool two = readers.size() == 2;
  const TraceHeader& a = readers[0]->header();
  if (two) {
    const TraceHeader& b = readers[1]->header();
    const auto describe = [](const TraceHeader& h) {
      std::string text;
      for (const TraceBody& body : h.bodies)
        text += fmt::format("{}{} {}", text.empty() ? "" : ", ", body.name, body.particles);
      return text;
    };
    if (describe(a) != describe(b))
      throw InputError(fmt::format("{}: bodies ({}) differ from {}'s ({}): not the same scene",
                                   readers[1]->path(), describe(b), readers[0]->path(),
                                   describe(a)));
    // The same step of two step sizes is not the same time: refused, not aligned (clothref diff
    // counts dt among the differences that matter).
    if (a.dt != b.dt)
      throw InputError(fmt::format(
          "{}: dt {} s differs from {}'s {} s: step k is not the same time in both, so the two "
          "cannot be compared step by step (record both with one dt)",
          readers[1]->path(), b.dt, readers[0]->path(), a.dt));
  }
  const std::int64_t n = commonStepCount(a, two ? &readers[1]->header() : nullptr);

  // which bodies are drawn how
  std::int64_t values_per_trace = 0;  // floats of one frame of one trace
  std::int64_t cloth_body = -1, cloth_particles = 0;
  for (std::size_t i = 0; i < a.bodies.size(); ++i) {
    values_per_trace += 3 * a.bodies[i].particles;
    if (a.bodies[i].name == "cloth") {
      cloth_body = std::int64_t(i);
      cloth_particles = a.bodies[i].particles;
    }
  }
  const std::int64_t frame_bytes =
      (values_per_trace * std::int64_t(readers.size()) + (two ? cloth_particles : 0)) * 4;
  const std::int64_t automatic =
      std::max<std::int64_t>(2, kFrameBudgetBytes / std::max<std::int64_t>(1, frame_bytes * 4 / 3));
  const std::int64_t wanted = std::min(n, options.max_frames > 0 ? options.max_frames : automatic);
  // evenly spread, first and last included: frame k is common step spreadIndex(k)
  std::int64_t next_frame = 0, next_index = 0;
  const auto selected = [&](std::int64_t index) {
    if (wanted >= n) return true;
    while (next_frame < wanted && next_index < index)
      next_index = spreadIndex(++next_frame, wanted, n);
    return next_frame < wanted && next_index == index;
  };

  std::vector<float> positions[2];
  std::vector<float> distance;
  std::vector<double> frame_t;
  std::vector<float> largest;        // per common step, two traces only
  std::vector<std::int64_t> common;  // the common steps read, in order
  nlohmann::ordered_json frame_steps = nlohmann::ordered_json::array();
  std::optional<std::int64_t> first_difference;
  double first_difference_t = 0, largest_difference = 0;
  TraceStep steps[2];
  // Step by step as the files hold them (the reader checks each against its header and refuses a
  // file that ends early): what is kept grows with what was read, never with a header's claim.
  bool more[2] = {readers[0]->next(), two && readers[1]->next()};
  for (std::int64_t c = 0;; ++c) {
    if (c > 0) {
      more[0] = readers[0]->next();
      if (two) more[1] = readers[1]->next();
    }
    while (two && more[0] && more[1] && readers[0]->prefix().step != readers[1]->prefix().step) {
      const int behind = readers[0]->prefix().step < readers[1]->prefix().step ? 0 : 1;
      more[behind] = readers[std::size_t(behind)]->next();
    }
    if (!more[0] || (two && !more[1])) break;
    common.push_back(readers[0]->prefix().step);
    bool keep = selected(c);
    if (two) {
      const StepPrefix& pa = readers[0]->prefix();
      const StepPrefix& pb = readers[1]->prefix();
      const bool same_t = sameValue(pa.t, pb.t);
      // equal lines are equal states: nothing to compute unless the frame is shown
      if (!keep && readers[0]->line() == readers[1]->line()) {
        largest.push_back(0);
        continue;
      }
      readers[0]->parseStep(steps[0]);
      readers[1]->parseStep(steps[1]);
      bool differs = !same_t;
      double step_largest = 0;
      for (std::size_t body = 0; body < a.bodies.size(); ++body) {
        const BodyState& sa = steps[0].bodies[body];
        const BodyState& sb = steps[1].bodies[body];
        for (std::size_t v = 0; v < sa.position.size(); ++v)
          differs = differs || !sameValue(sa.position[v], sb.position[v]) ||
                    !sameValue(sa.velocity[v], sb.velocity[v]);
        for (std::size_t p = 0; p + 2 < sa.position.size(); p += 3)
          step_largest = std::max(step_largest, pointDistance(&sa.position[p], &sb.position[p]));
      }
      largest.push_back(float(step_largest));
      largest_difference = std::max(largest_difference, step_largest);
      if (differs && !first_difference) {
        first_difference = common.back();
        first_difference_t = pa.t;
        keep = true;  // the first differing state is always among the frames
      }
      if (keep && cloth_body >= 0) {
        const BodyState& sa = steps[0].bodies[std::size_t(cloth_body)];
        const BodyState& sb = steps[1].bodies[std::size_t(cloth_body)];
        for (std::size_t p = 0; p + 2 < sa.position.size(); p += 3)
          distance.push_back(float(pointDistance(&sa.position[p], &sb.position[p])));
      }
    } else if (keep) {
      readers[0]->parseStep(steps[0]);
    }
    if (!keep) continue;
    frame_steps.push_back(common.back());
    frame_t.push_back(readers[0]->prefix().t);
    for (std::size_t r = 0; r < readers.size(); ++r)
      for (const BodyState& body : steps[r].bodies)
        for (double v : body.position) positions[r].push_back(float(v));
  }

  nlohmann::ordered_json data;
  data["format"] = "clothref-view";
  data["version"] = 1;
  data["traces"] = nlohmann::ordered_json::array();
  for (std::size_t r = 0; r < readers.size(); ++r)
    data["traces"].push_back(traceInfo(
        *readers[r], options.labels.empty() ? labelOf(sources[r].name) : options.labels[r]));
  data["bodies"] = nlohmann::ordered_json::array();
  for (const TraceBody& body : a.bodies)
    data["bodies"].push_back({{"name", body.name}, {"particles", body.particles}});
  data["cloth_mesh"] = cloth_body >= 0 ? clothMesh(a, cloth_particles) : nullptr;
  const nlohmann::ordered_json& scene = a.json.value("scene", nlohmann::ordered_json::object());
  const auto* fixed = scene.is_object() ? find(scene, "/cloth/fixed") : nullptr;
  data["fixed"] = fixed && fixed->is_array() ? *fixed : nlohmann::ordered_json::array();
  data["sphere_radii"] = sphereRadii(a);
  if (common.empty())
    throw InputError(fmt::format("{}: no recorded step in common with {}", readers.back()->path(),
                                 readers[0]->path()));
  data["recorded"] = std::int64_t(common.size());
  data["frame_steps"] = frame_steps;
  data["frame_t"] = base64(frame_t.data(), frame_t.size() * sizeof(double));
  data["positions"] = nlohmann::ordered_json::array();
  for (std::size_t r = 0; r < readers.size(); ++r)
    data["positions"].push_back(base64(positions[r].data(), positions[r].size() * sizeof(float)));
  if (two) {
    data["distance"] = base64(distance.data(), distance.size() * sizeof(float));
    data["difference"] = {{"steps", common},
                          {"largest", base64(largest.data(), largest.size() * sizeof(float))}};
    data["first_difference"] =
        first_difference
            ? nlohmann::ordered_json{{"step", *first_difference},
                                     {"t", std::isfinite(first_difference_t)
                                               ? nlohmann::ordered_json(first_difference_t)
                                               : nlohmann::ordered_json(nullptr)}}
            : nlohmann::ordered_json(nullptr);
    data["largest_difference"] =
        std::isfinite(largest_difference) ? nlohmann::ordered_json(largest_difference) : nullptr;
  }
  if (summary) {
    summary->recorded = std::int64_t(common.size());
    summary->frames = std::int64_t(frame_steps.size());
    summary->first_difference = first_difference;
    summary->largest_difference = largest_difference;
  }
  return data;
}

std::string viewerScriptAndStyle() {
  return "<style>\n" + std::string(pageAsset("viewer.css")) + "</style>\n<script>\n" +
         std::string(pageAsset("viewer.js")) + "</script>\n";
}

std::string viewerPage(const nlohmann::ordered_json& data, const std::string& title) {
  return fillTemplate(pageAsset("viewer.html"), {{"TITLE", escapeHtml(title)},
                                                 {"VIEWER", viewerScriptAndStyle()},
                                                 {"DATA", jsonForScript(data)}});
}

}  // namespace clothref::pages
