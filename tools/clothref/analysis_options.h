// The options `stability` and `sweep` share: which scenes, methods and precisions to study.
// Method and precision names are checked by CLI11 against the one table of each enum.
#pragma once

#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "clothref/base/precision.h"
#include "clothref/core/method.h"
#include "clothref/scene/scene.h"
#include "commands.h"

namespace clothref::cli {

struct AnalysisSelection {
  std::vector<std::string> default_scenes;  // the command's, when --scene is not given
  std::vector<std::string> scenes;          // names or files
  std::vector<std::string> methods;         // empty = every row of the method table
  std::string precision = "both";           // float | double | both
};

// Adds --scene, --method and --precision to `app` (the help names selection.default_scenes).
inline void addAnalysisSelection(CLI::App* app, AnalysisSelection& selection) {
  std::string defaults;
  for (const std::string& name : selection.default_scenes)
    defaults += (defaults.empty() ? "" : ", ") + name;
  app->add_option("--scene", selection.scenes,
                  "Scene name or file, repeatable (default: " + defaults + ")");
  app->add_option("--method", selection.methods,
                  "Method, repeatable (default: every method, backward-euler included)")
      ->check(oneOf(kMethodNames));
  app->add_option("--precision", selection.precision, "float | double | both")
      ->check(CLI::IsMember({"float", "double", "both"}))
      ->capture_default_str();
}

// The scenes chosen, or the defaults when none was given (loadScene: a name or a file).
inline std::vector<Scene> selectedScenes(const AnalysisSelection& selection) {
  std::vector<Scene> scenes;
  for (const std::string& name :
       selection.scenes.empty() ? selection.default_scenes : selection.scenes)
    scenes.push_back(loadScene(name));
  return scenes;
}

// The methods chosen (names already checked), in the order given; every method when none.
inline std::vector<Method> selectedMethods(const AnalysisSelection& selection) {
  if (selection.methods.empty()) return {kAllMethods.begin(), kAllMethods.end()};
  std::vector<Method> methods;
  for (const std::string& name : selection.methods) methods.push_back(*parseMethod(name));
  return methods;
}

// Float, double, or both in that order.
inline std::vector<Precision> selectedPrecisions(const AnalysisSelection& selection) {
  if (selection.precision == "both") return {Precision::Float, Precision::Double};
  return {*parseEnum(kPrecisionNames, selection.precision)};
}

}  // namespace clothref::cli
