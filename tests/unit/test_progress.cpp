// Long runs report step, % done, particle-steps/s and time left.
#include <gtest/gtest.h>

#include <cstdio>
#include <string>

#include "tests/unit/deck_runner.h"

// A namespace per file: the unit tests compile in unity batches (tests/CMakeLists.txt).
namespace test_progress {

using sable::test::Deck;

TEST(Progress, LinesCarryStepPercentRateAndTimeLeft) {
  Deck d;
  FILE* out = std::tmpfile();
  d->screen = out;
  d->progress_every_s = 0.0;  // every step instead of every 10 s, to see the format
  d(R"(units si
atom_style granular
region box block 0 1 0 1 0 1 units box
create_box 1 box
create_atoms 1 single 0.5 0.5 0.5 units box
fix i all nve/sphere
run 4)");
  std::rewind(out);
  std::string text;
  char buf[512];
  while (std::fgets(buf, sizeof buf, out)) text += buf;
  std::fclose(out);
  EXPECT_NE(text.find("Progress: step 1, 25.0% done,"), std::string::npos) << text;
  EXPECT_NE(text.find("particle-steps/s,"), std::string::npos) << text;
  EXPECT_NE(text.find("s left"), std::string::npos) << text;
  EXPECT_NE(text.find("Loop time of"), std::string::npos) << text;
}

}  // namespace test_progress
