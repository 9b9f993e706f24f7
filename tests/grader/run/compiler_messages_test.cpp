// Quoting the compiler: the first error with its context, without scratch paths.
#include "grader/grade/run/compiler_messages.h"

#include <gtest/gtest.h>

namespace clothref::grader {
namespace {

TEST(FirstCompilerError, QuotesTheFirstErrorWithoutScratchPaths) {
  const std::string log =
      "/tmp/clothref-grade-1-2/src-cloth/cloth.cpp: In member function 'void Cloth::x()':\n"
      "/tmp/clothref-grade-1-2/src-cloth/cloth.cpp:12:3: error: 'addSpring' was not declared\n"
      "   12 |   addSpring(1, 2);\n"
      "      |   ^~~~~~~~~\n"
      "/tmp/clothref-grade-1-2/src-cloth/cloth.cpp:20:1: error: second\n";
  const std::string quote = firstCompilerError(log, "cloth.cpp");
  EXPECT_EQ(quote.find("/tmp/"), std::string::npos) << quote;
  EXPECT_EQ(quote.rfind("cloth.cpp:12:3: error: 'addSpring' was not declared", 0), 0u) << quote;
  EXPECT_NE(quote.find("addSpring(1, 2);"), std::string::npos) << quote;
  EXPECT_EQ(quote.find("second"), std::string::npos) << quote;
}

TEST(FirstCompilerError, LinkErrors) {
  const std::string quote = firstCompilerError(
      "/usr/bin/ld: probe_driver.o: in function `main':\n"
      "driver.cpp:(.text+0x1): undefined reference to `Cloth::computeNormal()'\n",
      "cloth.cpp");
  EXPECT_NE(quote.find("undefined reference to `Cloth::computeNormal()'"), std::string::npos)
      << quote;
}

}  // namespace
}  // namespace clothref::grader
