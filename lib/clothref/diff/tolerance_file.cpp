// Tolerances: which one applies to a value, and the tolerance file (docs/trace-format.md) read
// into DiffOptions with one-line errors naming the file and the JSON pointer.
#include "clothref/diff/diff.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <fstream>
#include <limits>
#include <sstream>

#include <fmt/format.h>

#include "clothref/diff/diff_support.h"
#include "clothref/io/error.h"
#include "clothref/io/json_input.h"
#include "clothref/io/limits.h"
#include "clothref/trace/format.h"
#include "clothref/trace/reader.h"

namespace clothref {

using namespace diff_support;

namespace {

using json = nlohmann::json;

// ---------------------------------------------------------------------------------------------
// Tolerance files

[[noreturn]] void toleranceError(const std::string& source, const std::string& pointer,
                                 const std::string& problem) {
  throw InputError(fmt::format("{}: {}: {}", source, pointer.empty() ? "/" : pointer, problem));
}

double nonNegative(const json& object, const std::string& key, const std::string& source,
                   const std::string& pointer) {
  const json& value = object[key];
  if (!value.is_number() || !(value.get<double>() >= 0) || !std::isfinite(value.get<double>()))
    toleranceError(source, pointer + "/" + key,
                   "expected a finite number >= 0, got " + excerpt(value.dump()));
  return value.get<double>();
}

Tolerance toleranceFromJson(const json& value, const std::string& source,
                            const std::string& pointer) {
  if (!value.is_object()) toleranceError(source, pointer, "expected an object");
  for (const auto& item : value.items())
    if (item.key() != "mode" && item.key() != "abs" && item.key() != "rel" &&
        item.key() != "floor" && item.key() != "ulps")
      toleranceError(source, pointer + "/" + item.key(), "unknown key");
  Tolerance tolerance;
  if (value.contains("abs")) tolerance.abs = nonNegative(value, "abs", source, pointer);
  if (value.contains("rel")) tolerance.rel = nonNegative(value, "rel", source, pointer);
  if (value.contains("floor")) tolerance.floor = nonNegative(value, "floor", source, pointer);
  if (value.contains("ulps")) {
    const json& ulps = value["ulps"];
    if (!ulps.is_number_integer() || ulps.get<std::int64_t>() < 0)
      toleranceError(source, pointer + "/ulps",
                     "expected an integer >= 0, got " + excerpt(ulps.dump()));
    tolerance.ulps = ulps.get<std::int64_t>();
  }
  if (value.contains("mode")) {
    const json& mode = value["mode"];
    const std::optional<ToleranceMode> parsed =
        mode.is_string() ? parseEnum(kToleranceModeNames, mode.get<std::string>()) : std::nullopt;
    if (!parsed)
      toleranceError(
          source, pointer + "/mode",
          "expected one of " + enumNames(kToleranceModeNames) + ", got " + excerpt(mode.dump()));
    tolerance.mode = *parsed;
  } else if (value.contains("abs") && value.contains("rel")) {
    tolerance.mode = ToleranceMode::Combined;
  } else if (value.contains("abs")) {
    tolerance.mode = ToleranceMode::Absolute;
  } else if (value.contains("rel")) {
    tolerance.mode = ToleranceMode::Relative;
  }
  return tolerance;
}

}  // namespace

Tolerance toleranceFor(const DiffOptions& options, const std::string& body, Field field) {
  if (field == Field::Time) return options.time.value_or(options.global);
  const auto it = options.bodies.find(body);
  if (it == options.bodies.end()) return options.global;
  const std::optional<Tolerance>& own =
      field == Field::Position ? it->second.position : it->second.velocity;
  return own.value_or(options.global);
}

ordered_json toleranceToJson(const Tolerance& t) {
  return {{"mode", toleranceModeName(t.mode)},
          {"abs", t.abs},
          {"rel", t.rel},
          {"floor", t.floor},
          {"ulps", t.ulps}};
}

DiffOptions toleranceOptionsFromJson(const json& document, const std::string& source) {
  if (!document.is_object()) toleranceError(source, "", "expected a JSON object");
  DiffOptions options;
  for (const auto& item : document.items()) {
    const std::string& key = item.key();
    const json& value = item.value();
    if (key == "format") {
      if (value != "clothref-tolerances")
        toleranceError(source, "/format",
                       "expected \"clothref-tolerances\", got " + excerpt(value.dump()));
    } else if (key == "version") {
      if (value != kToleranceFileVersion)
        toleranceError(source, "/version",
                       fmt::format("unsupported version {} (this build reads {})",
                                   excerpt(value.dump()), kToleranceFileVersion));
    } else if (key == "comment") {
      if (!value.is_string()) toleranceError(source, "/comment", "expected a string");
    } else if (key == "default") {
      options.global = toleranceFromJson(value, source, "/default");
    } else if (key == "time") {
      options.time = toleranceFromJson(value, source, "/time");
    } else if (key == "bodies") {
      if (!value.is_object()) toleranceError(source, "/bodies", "expected an object");
      for (const auto& body : value.items()) {
        const std::string pointer = "/bodies/" + body.key();
        // the trace writer's body names; a typo must not silently fall back to the default
        if (body.key() != "cloth" && body.key() != "spheres")
          toleranceError(source, pointer, "unknown body (cloth, spheres)");
        if (!body.value().is_object()) toleranceError(source, pointer, "expected an object");
        BodyTolerances& tolerances = options.bodies[body.key()];
        for (const auto& field : body.value().items()) {
          if (field.key() == "position")
            tolerances.position = toleranceFromJson(field.value(), source, pointer + "/position");
          else if (field.key() == "velocity")
            tolerances.velocity = toleranceFromJson(field.value(), source, pointer + "/velocity");
          else
            toleranceError(source, pointer + "/" + field.key(),
                           "unknown field (position, velocity)");
        }
      }
    } else {
      toleranceError(source, "/" + key, "unknown key");
    }
  }
  return options;
}

DiffOptions readToleranceFile(const std::string& path) {
  return toleranceOptionsFromJson(readJsonFile(path, "tolerance file"), path);
}

}  // namespace clothref
