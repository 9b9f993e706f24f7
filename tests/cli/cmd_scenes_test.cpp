// `clothref scenes`: one line per built-in scene, the descriptions in one column however long the
// longest name (tools/clothref/cmd_scenes.cpp).
#include <gtest/gtest.h>

#include <sstream>
#include <string>
#include <vector>

#include "clothref/scene/scene.h"
#include "test_util.h"

namespace clothref {
namespace {

TEST(ScenesCli, DescriptionsStartInOneColumn) {
  const auto [code, output] = test::runCli("scenes", test::Capture::StdoutOnly);
  EXPECT_EQ(code, 0);
  std::vector<std::string> lines;
  std::istringstream in(output);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  const std::vector<Scene>& scenes = builtinScenes();
  ASSERT_EQ(lines.size(), scenes.size()) << output;
  std::size_t column = std::string::npos;
  for (std::size_t k = 0; k < scenes.size(); ++k) {
    const std::size_t at = lines[k].find(scenes[k].description);
    ASSERT_NE(at, std::string::npos) << lines[k];
    EXPECT_EQ(lines[k].rfind(scenes[k].name + " ", 0), 0u) << lines[k];
    if (column == std::string::npos) column = at;
    EXPECT_EQ(at, column) << "misaligned: " << lines[k];
  }
}

}  // namespace
}  // namespace clothref
