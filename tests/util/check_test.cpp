// util/check.h: a CHECK that holds does nothing; one that fails aborts naming file:line, the
// condition and the message.
#include "util/check.h"

#include <gtest/gtest.h>

namespace gv {
namespace {

TEST(Check, HoldingChecksDoNothing) {
  int evaluated = 0;
  CHECK(++evaluated == 1);
  CHECK_MSG(evaluated == 1, "evaluated {} times", evaluated);
  EXPECT_EQ(evaluated, 1);  // the condition runs once, in Release builds too
}

TEST(CheckDeathTest, FailingChecksAbortWithFileLineAndMessage) {
  GTEST_FLAG_SET(death_test_style, "threadsafe");
  const int cells = 3;
  EXPECT_DEATH(CHECK(cells == 4), "check_test.cpp:[0-9]+: CHECK failed: cells == 4");
  EXPECT_DEATH(CHECK_MSG(cells == 4, "{} cells", cells),
               "CHECK failed: cells == 4: 3 cells");
}

}  // namespace
}  // namespace gv
