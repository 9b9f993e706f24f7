// isUnder (grader/grade/submission/neighbours.h): the one test of which folder a cover hides, used
// by the confinement, the fallback's private mounts and the list of our folders.
#include "grader/grade/submission/neighbours.h"

#include <gtest/gtest.h>

namespace clothref::grader {
namespace {

TEST(IsUnder, AFolderAndWhatIsInsideItButNotASiblingWithTheSamePrefix) {
  EXPECT_TRUE(isUnder("/srv/subs", "/srv/subs"));
  EXPECT_TRUE(isUnder("/srv/subs/alice/src", "/srv/subs"));
  EXPECT_FALSE(isUnder("/srv/subs-old/alice", "/srv/subs"));
  EXPECT_FALSE(isUnder("/srv", "/srv/subs"));
}

TEST(IsUnder, TheRootHoldsEveryPathAndTrailingSlashesDoNotMatter) {
  EXPECT_TRUE(isUnder("/tmp/x", "/"));
  EXPECT_TRUE(isUnder("/", "/"));
  EXPECT_TRUE(isUnder("/srv/subs/alice", "/srv/subs/"));
  EXPECT_TRUE(isUnder("/srv/subs/", "/srv/subs"));
  EXPECT_FALSE(isUnder("/srv/subsidiary", "/srv/subs/"));
}

TEST(IsUnder, ComparedLexicallyAfterNormalising) {
  EXPECT_TRUE(isUnder("/srv/other/../subs/alice", "/srv/subs"));
  EXPECT_FALSE(isUnder("/srv/subs/../other", "/srv/subs"));
  EXPECT_TRUE(isUnder("/srv/./subs//alice", "/srv/subs"));
}

}  // namespace
}  // namespace clothref::grader
