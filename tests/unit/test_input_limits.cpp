// Issue 24: bad input ends in a clear, located error; limits that used to crash or hang.
#include <gtest/gtest.h>

#include <fstream>
#include <string>

#include "core/input/number_format.h"
#include "tests/unit/deck_runner.h"

// A namespace per file: the unit tests compile in unity batches (tests/CMakeLists.txt).
namespace sable::test::test_input_limits {
namespace {

const char* kPile = R"(units si
atom_style granular
boundary f f f
region box block 0 0.01 0 0.01 0 0.01 units box
create_box 1 box
neighbor 0.0002 bin
fix m1 all property/global youngsModulus peratomtype 1e7
fix m2 all property/global poissonsRatio peratomtype 0.3
fix m3 all property/global coefficientRestitution peratomtypepair 1 0.5
fix m4 all property/global coefficientFriction peratomtypepair 1 0.5
pair_style gran model hertz tangential history
pair_coeff * *
timestep 1e-6
fix i all nve/sphere
)";

TEST(NumberFormat, OneNumericConversion) {
  EXPECT_EQ(number_format_problem("%.3f", false), "");
  EXPECT_EQ(number_format_problem("x = %-12.4e m", false), "");
  EXPECT_EQ(number_format_problem("%lf%%", false), "");
  EXPECT_EQ(number_format_problem("%ld", true), "");
  EXPECT_NE(number_format_problem("%n", false), "");
  EXPECT_NE(number_format_problem("%s", false), "");
  EXPECT_NE(number_format_problem("%*d", true), "");
  EXPECT_NE(number_format_problem("%f%f", false), "");
  EXPECT_NE(number_format_problem("abc", false), "");
  EXPECT_NE(number_format_problem("%", false), "");
  EXPECT_NE(number_format_problem("%d", false), "");  // an int conversion reading a double
  EXPECT_NE(number_format_problem("%1000000f", false), "");
}

TEST(InputLimits, LoopValuesAreMadeLazily) {
  Deck d;
  // A loop of 1e9 values used to be built at once (minutes and gigabytes).
  const std::string out = printed("variable n loop 1000000000\nprint \"n=$n\"\nnext n\nprint \"n=$n\"\n"
                                  "variable p loop 8 10 pad\nnext p\nnext p\nprint \"p=$p\"\n", d);
  EXPECT_NE(out.find("n=1\n"), std::string::npos) << out;
  EXPECT_NE(out.find("n=2\n"), std::string::npos) << out;
  EXPECT_NE(out.find("p=10\n"), std::string::npos) << out;
}

TEST(InputLimits, LoopBoundsAreChecked) {
  Deck d;
  EXPECT_NE(error_of(d, "variable n loop 0").find("test:1: "), std::string::npos);
  EXPECT_NE(error_of(d, "variable n loop 3 2").find("loop would be empty"), std::string::npos);
  EXPECT_NE(error_of(d, "variable n loop -2 3 pad").find("negative loop start"), std::string::npos);
  EXPECT_EQ(error_of(d, "variable n loop -2 3\nnext n"), "(no error)");
}

TEST(InputLimits, NestingIsBounded) {
  Deck d;
  const std::string deep = std::string(100000, '(') + "1" + std::string(100000, ')');
  EXPECT_NE(error_of(d, "variable a equal " + deep).find("nested too deeply"), std::string::npos);
  std::string chain = "1";
  for (int k = 0; k < 20000; ++k) chain += "+1";  // a left-deep tree as tall as the chain
  EXPECT_NE(error_of(d, "variable b equal " + chain).find("nested too deeply"), std::string::npos);
  std::string ok = std::string(100, '(') + "2" + std::string(100, ')');
  EXPECT_EQ(error_of(d, "variable c equal " + ok), "(no error)");
}

TEST(InputLimits, EndlessJumpLoopStops) {
  TempDir t;
  const std::string path = t / "loop.in";
  std::ofstream(path) << "label top\nprint \"x\" screen no\njump SELF top\n";
  Deck d;
  const std::string e = error_of(d, "include " + path);
  EXPECT_NE(e.find("endless loop"), std::string::npos) << e;
  EXPECT_NE(e.find("loop.in:3:"), std::string::npos) << e;
}

// A loop that only adds atoms ends when its variable is exhausted (a counted loop
// of 20000 runs through); one that would add atoms for ever stops with an error.
TEST(InputLimits, LoopOnlyAddingAtomsStops) {
  TempDir t;
  const std::string head = "units si\natom_style granular\natom_modify map array\nboundary f f f\n"
                           "region box block 0 1 0 1 0 1 units box\ncreate_box 1 box\n";
  const std::string counted = t / "counted.in";
  std::ofstream(counted) << head << "variable i loop 20000\nlabel l\ncreate_atoms 1 single 0.5 0.5 0.5 units box\n"
                                    "next i\njump SELF l\n";
  Deck ok;
  EXPECT_EQ(error_of(ok, "include " + counted), "(no error)");
  EXPECT_EQ(ok->atoms.n, 20000u);
  const std::string endless = t / "endless.in";
  std::ofstream(endless) << head << "label l\ncreate_atoms 1 single 0.5 0.5 0.5 units box\njump SELF l\n";
  Deck d;
  const std::string e = error_of(d, "include " + endless);
  EXPECT_NE(e.find("only the atom count changing"), std::string::npos) << e;
  EXPECT_NE(e.find("endless.in:9:"), std::string::npos) << e;
  // An outer loop whose 'next' is missing: the inner loop's jumps between its
  // passes (their variable changes) do not hide it.
  const std::string nested = t / "nested.in";
  std::ofstream(nested) << head << "variable row loop 4\nlabel rows\nvariable col loop 4\nlabel cols\n"
                                   "create_atoms 1 single 0.5 0.5 0.5 units box\nnext col\njump SELF cols\njump SELF rows\n";
  Deck n;
  const std::string en = error_of(n, "include " + nested);
  EXPECT_NE(en.find("only the atom count changing"), std::string::npos) << en;
  EXPECT_NE(en.find("nested.in:14:"), std::string::npos) << en;
}

TEST(InputLimits, UnknownNamesAtTheirLine) {
  Deck d;
  d(kPile);
  const std::string e = error_of(d, "variable s equal 2*stepz");
  EXPECT_NE(e.find("test:1:"), std::string::npos) << e;
  EXPECT_NE(e.find("'stepz' is not a thermo keyword"), std::string::npos) << e;
  EXPECT_NE(error_of(d, "variable a atom 2*radiusz").find("'radiusz'"), std::string::npos);
  // A fix defined after the variable that names it still works (LIGGGHTS evaluates lazily).
  EXPECT_EQ(error_of(d, "variable w equal f_later[3]+x[1]+count(all)\n"
                        "create_atoms 1 single 0.005 0.005 0.005 units box\n"
                        "set group all diameter 0.002 density 2500\n"
                        "fix later all wall/gran model hertz tangential history primitive type 1 zplane 0.0\n"
                        "variable r atom radius*2+v_w\n"
                        "thermo_style custom step v_w\nthermo 1\nrun 2"),
            "(no error)");
}

TEST(InputLimits, ErrorsAtOutputNameTheVariable) {
  Deck d;
  d(kPile);
  d("create_atoms 1 single 0.005 0.005 0.005 units box\nset group all diameter 0.002 density 2500\n");
  const std::string e = error_of(d, "variable w equal f_never+1\nthermo_style custom step v_w\nthermo 1\nrun 2");
  EXPECT_NE(e.find("variable 'w' defined at test:1"), std::string::npos) << e;
  EXPECT_NE(e.find("test:4"), std::string::npos) << e;  // the run line
}

TEST(InputLimits, SetupReportsDeepOverlaps) {
  Deck d;
  d(kPile);
  d("create_atoms 1 single 0.005 0.005 0.005 units box\ncreate_atoms 1 single 0.005 0.005 0.0066 units box\n"
    "create_atoms 1 single 0.002 0.002 0.002 units box\nset group all diameter 0.002 density 2500\n");
  // Atoms 1 and 2: centres 1.6 mm apart, radius 1 mm: overlap 0.4 mm = 40 % of the radius.
  const std::string out = printed("run 0", d);
  EXPECT_NE(out.find("1 pair(s) of grains overlap by more than 10% of the smaller radius"), std::string::npos) << out;
  EXPECT_NE(out.find("atoms 1 and 2 by 0.0004 (40% of the smaller radius)"), std::string::npos) << out;
}

TEST(InputLimits, GrainsWiderThanTheBox) {
  Deck d;
  d(kPile);
  d("create_atoms 1 single 0.005 0.005 0.005 units box\ncreate_atoms 1 single 0.002 0.002 0.002 units box\n");
  // No `set diameter`: LIGGGHTS' default diameter is 1 m in a 1 cm box.
  const std::string big = printed("run 0", d);
  EXPECT_NE(big.find("WARNING: atom 1 has diameter 1, larger than the box along x (0.01)"), std::string::npos) << big;
  Deck w;
  w(kPile);
  w("create_atoms 1 single 0.005 0.005 0.005 units box\ncreate_atoms 1 single 0.001 0.001 0.001 units box\n"
    "set group all diameter 0.0099 density 2500\n");
  const std::string out = printed("run 0", w);
  EXPECT_NE(out.find("is as large as the box on every axis"), std::string::npos) << out;
}

}  // namespace
}  // namespace sable::test::test_input_limits
