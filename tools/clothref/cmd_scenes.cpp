// clothref scenes: the built-in scenes, one line each.
#include <algorithm>
#include <iostream>
#include <memory>

#include <fmt/format.h>

#include "clothref/scene/scene.h"
#include "commands.h"

namespace clothref::cli {

Command addScenesCommand(CLI::App& root) {
  CLI::App* app =
      root.add_subcommand("scenes", "List the built-in scenes (the first is the default)");
  auto json = std::make_shared<bool>(false);
  app->add_flag("--json", *json, "Print every built-in scene as JSON, one per line");
  return {app, [json] {
            std::size_t width = 0;  // the longest name sets the column
            for (const Scene& scene : builtinScenes()) width = std::max(width, scene.name.size());
            for (const Scene& scene : builtinScenes()) {
              if (*json) {
                std::cout << sceneToJson(scene).dump() << '\n';
                continue;
              }
              std::cout << fmt::format("{:<{}}  {}\n", scene.name, width, scene.description);
            }
            return kExitOk;
          }};
}

}  // namespace clothref::cli
