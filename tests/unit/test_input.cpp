// The deck language: variables, substitution, loops, conditionals, include.
#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>

#include "core/engine/error.h"
#include "core/input/variable.h"
#include "tests/unit/deck_runner.h"

// A namespace per file: the unit tests compile in unity batches (tests/CMakeLists.txt).
namespace test_input {

using sable::test::Deck;
using sable::test::printed;

TEST(Input, SubstitutionAndImmediateFormulas) {
  Deck d;
  const std::string out = printed(R"D(variable a equal 2
variable s string hello
variable x index 7.5
print "a=${a} s=${s} x=$x imm=$(v_a*3+1) fmt=$(1/3:%.3f)"
print 'single quotes keep ${a}'
variable b equal v_a^3+sqrt(16)   # comment after a formula
print "b=${b}")D",
                                  d);
  EXPECT_NE(out.find("a=2 s=hello x=7.5 imm=7 fmt=0.333"), std::string::npos) << out;
  EXPECT_NE(out.find("single quotes keep ${a}"), std::string::npos) << out;
  EXPECT_NE(out.find("b=12"), std::string::npos) << out;
}

TEST(Input, LoopWithNextJumpAndLabel) {
  Deck d;
  const std::string out = printed(R"D(variable i loop 3
variable total equal 0
label top
print "iteration ${i}"
next i
jump SELF top
print "after loop")D",
                                  d);
  EXPECT_NE(out.find("iteration 1\niteration 2\niteration 3\nafter loop"), std::string::npos) << out;
}

TEST(Input, LoopOverIndexValuesFromFile) {
  // jump SELF restarts the file from the top and skips to the label, as in LAMMPS.
  const char* path = "input_test_loop.in";
  {
    std::ofstream f(path);
    f << "variable r index 0.1 0.2 0.3\nlabel again\nprint \"r=${r}\" append input_test_loop.out screen no\nnext r\njump SELF again\n";
  }
  std::remove("input_test_loop.out");
  Deck d;
  d->input->file(path);
  std::ifstream in("input_test_loop.out");
  std::string all((std::istreambuf_iterator<char>(in)), {});
  EXPECT_EQ(all, "r=0.1\nr=0.2\nr=0.3\n");
}

TEST(Input, IfThenElifElse) {
  Deck d;
  const std::string out = printed(R"D(variable n equal 5
variable style string granular
if "${n} > 10" then "print big" elif "${n} > 3" "print medium" "print twice" else "print small"
if "${style} == granular" then "print is-granular"
if "${n} < 0" then "print negative" else "print non-negative")D",
                                  d);
  EXPECT_NE(out.find("medium\ntwice\nis-granular\nnon-negative"), std::string::npos) << out;
  EXPECT_EQ(out.find("big"), std::string::npos);
}

TEST(Input, IncludeAndContinuationLines) {
  {
    std::ofstream f("input_test_include.in");
    f << "variable inc equal 40+&\n  2\n";
  }
  Deck d;
  const std::string out = printed("include input_test_include.in\nprint \"inc=${inc}\"", d);
  EXPECT_NE(out.find("inc=42"), std::string::npos) << out;
}

TEST(Input, ThermoKeywordsAtomValuesAndGroupFunctions) {
  Deck d;
  const std::string out = printed(R"D(units si
atom_style granular
region box block 0 1 0 1 0 1 units box
create_box 1 box
create_atoms 1 single 0.25 0.5 0.5 units box
create_atoms 1 single 0.75 0.5 0.5 units box
variable cnt equal count(all)
variable xc equal xcm(all,x)
variable hi equal bound(all,xmax)
print "atoms=$(atoms) count=${cnt} xcm=${xc} xmax=${hi} x2=$(x[2]) step=$(step)")D",
                                  d);
  EXPECT_NE(out.find("atoms=2 count=2 xcm=0.5 xmax=0.75 x2=0.75 step=0"), std::string::npos) << out;
  // An empty group: LIGGGHTS' bounds start from +-1e20 (LAMMPS group.cpp, BIG), so that is what it returns.
  const std::string none = printed(R"D(group nobody id 99
variable lo equal bound(nobody,xmin)
variable up equal bound(nobody,xmax)
print "empty: ${lo} ${up}")D",
                                   d);
  EXPECT_NE(none.find("empty: 1e+20 -1e+20"), std::string::npos) << none;
}

TEST(Input, CommandLineIndexVariableWins) {
  // -var NAME VALUE defines an index variable that the deck's own definition does not override.
  Deck d;
  d->variables->define_index("seed", {"12345"});
  const std::string out = printed("variable seed index 999\nprint \"seed=${seed}\"", d);
  EXPECT_NE(out.find("seed=12345"), std::string::npos) << out;
}

TEST(Input, ErrorsNameFileLineAndWord) {
  Deck d;
  try {
    d("units si\nvariable a equal 1\nprint \"${b}\"");
    FAIL() << "expected an error";
  } catch (const sable::SableError& e) {
    EXPECT_NE(std::string(e.what()).find("test:3:"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("variable 'b' is not defined"), std::string::npos) << e.what();
  }
}

// `error MESSAGE` (sable's addition) stops at its own line with the deck's message, variables
// substituted; through `if` it is a deck's input check, silent while the check holds.
TEST(Input, ErrorCommandStopsAtItsLineWithTheDecksMessage) {
  Deck d;
  EXPECT_NO_THROW(d("variable NU equal 2\nif \"${NU} <= 0\" then \"error 'NU = ${NU}: expected NU > 0'\""));
  try {
    d("variable NP equal -1\nif \"${NP} <= 0\" then \"error 'NP = ${NP}: expected NP > 0'\"");
    FAIL() << "expected an error";
  } catch (const sable::SableError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("test:2:"), std::string::npos) << m;
    EXPECT_NE(m.find("stopped by the deck: NP = -1: expected NP > 0"), std::string::npos) << m;
  }
}

}  // namespace test_input
