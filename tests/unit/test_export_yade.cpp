// sable --export-yade (tools/export_yade.h): what cannot be translated is an
// error naming the deck file, line and command; what can appears in the
// script. The physics of the script is checked by running it in YADE through
// reference_runs/compare.py (decks input_scripts/compare/yade_*.in, stored
// YADE results in reference_runs/reference/yade_*/yade/).
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>

#include "core/error.h"
#include "core/input.h"
#include "core/simulation.h"
#include "tests/unit/deck_runner.h"
#include "tools/export_yade.h"

using sable::test::TempDir;

namespace {

const std::string kHead = R"(units si
atom_style granular
atom_modify map array
boundary f f f
region box block -0.01 0.01 -0.01 0.01 -0.01 0.01 units box
create_box 2 box
neighbor 0.0005 bin
fix m1 all property/global youngsModulus peratomtype 1e7 2e7
fix m2 all property/global poissonsRatio peratomtype 0.3 0.25
fix m3 all property/global coefficientRestitution peratomtypepair 2 0.5 0.6 0.6 0.7
fix m4 all property/global coefficientFriction peratomtypepair 2 0.4 0.3 0.3 0.2
pair_style gran model hertz tangential history
pair_coeff * *
timestep 1e-6
create_atoms 1 single 0 0 0.0011 units box
create_atoms 1 single 0.003 0 0.0011 units box
set group all diameter 0.002 density 2500 vz -0.5
fix integr all nve/sphere
)";

// Exports deck text (written to deck.in) and returns the script, or "ERROR: " + the message.
std::string exported(const TempDir& tmp, const std::string& deck) {
  std::ofstream(tmp / "deck.in") << deck;
  sable::Simulation sim;
  sim.screen = nullptr;
  sable::Input in(sim);
  try {
    sable::export_yade(sim, in, tmp / "deck.in", tmp / "script.py");
  } catch (const sable::SableError& e) {
    return std::string("ERROR: ") + e.what();
  }
  std::stringstream s;
  s << std::ifstream(tmp / "script.py").rdbuf();
  return s.str();
}

}  // namespace

TEST(ExportYade, UntranslatableFixNamesFileLineAndCommand) {
  TempDir tmp;
  const std::string e = exported(tmp, kHead + "fix v all viscous 0.1\nrun 10\n");
  EXPECT_NE(e.find("deck.in:19: 'fix v all viscous 0.1'"), std::string::npos) << e;
  EXPECT_NE(e.find("fix style 'viscous' is not translated"), std::string::npos) << e;
}

TEST(ExportYade, SceneChangeAfterTheFirstRunIsRefused) {
  TempDir tmp;
  const std::string e = exported(tmp, kHead + "run 10\nunfix integr\nrun 10\n");
  EXPECT_NE(e.find("deck.in:20: 'unfix integr'"), std::string::npos) << e;
  EXPECT_NE(e.find("not translated"), std::string::npos) << e;
}

TEST(ExportYade, UntranslatableExpressionInPrintIsRefused) {
  TempDir tmp;
  const std::string e = exported(tmp, kHead + "compute k all ke\nrun 10\nvariable q equal c_k\nprint \"OBSERVABLE k ${q}\"\n");
  EXPECT_NE(e.find("deck.in:22"), std::string::npos) << e;
  EXPECT_NE(e.find("cannot translate 'c_k'"), std::string::npos) << e;
}

TEST(ExportYade, ScriptHoldsGrainsLawRunAndObservables) {
  TempDir tmp;
  const std::string s = exported(tmp, kHead + "variable q equal vz[2]\nthermo_style custom step v_q\nthermo 5\nrun 10\n"
                                              "variable i loop 2\nlabel l\nvariable w equal omegax[$i]*2^2\n"
                                              "print \"OBSERVABLE w_$i ${w}\"\nnext i\njump SELF l\n");
  ASSERT_EQ(s.find("ERROR"), std::string::npos) << s;
  EXPECT_NE(s.find("Law2_ScGeom_MindlinPhys_Mindlin()"), std::string::npos);
  EXPECT_NE(s.find(" (2, 1, 0.0030000000000000001, 0, 0.0011000000000000001, 0.001,"), std::string::npos) << s;
  EXPECT_NE(s.find("_run(10, 5, "), std::string::npos);
  EXPECT_NE(s.find("print('' + 'OBSERVABLE w_1 ' + _fmt((_b(1).state.angVel[0]*2**2)) + '')"), std::string::npos) << s;
  EXPECT_NE(s.find("print('' + 'OBSERVABLE w_2 ' + _fmt((_b(2).state.angVel[0]*2**2)) + '')"), std::string::npos) << s;
  // LIGGGHTS' Hertz dashpot as YADE's betan = sqrt(5/6) |ln e| / sqrt(ln^2 e + pi^2), type pair 1-2 (e = 0.6)
  const double l = std::log(0.6), b = std::sqrt(5.0 / 6.0) * -l / std::sqrt(l * l + M_PI * M_PI);
  char want[64];
  std::snprintf(want, sizeof want, "(0, 1, %.17g)", b);
  EXPECT_NE(s.find(want), std::string::npos) << want << "\n" << s;
}

// YADE's Hertz wall contact takes R = r/2; the wall material the exporter
// writes must give YADE's formulas LIGGGHTS' stiffness with R = r:
// E*_YADE = sqrt(2) Y*, G_YADE / (2 - nu_YADE) = 2 sqrt(2) G* (export_yade.cpp).
TEST(ExportYade, HertzWallMaterialRestoresLiggghtsStiffness) {
  TempDir tmp;
  const std::string s =
      exported(tmp, kHead + "fix w all wall/gran model hertz tangential history primitive type 2 zplane 0\nrun 10\n");
  std::smatch m;
  ASSERT_TRUE(std::regex_search(s, m, std::regex(R"(FrictMat\(young=([^,]+), poisson=([^,]+), frictionAngle=math.atan\(0.29999999999999999\), density=1000\)\)  # wall w)")))
      << s;
  const double Eb = std::stod(m[1]), nb = std::stod(m[2]), Ea = 1e7, na = 0.3, Ew = 2e7, nw = 0.25;
  const double Y = 1 / ((1 - na * na) / Ea + (1 - nw * nw) / Ew);
  const double G = 1 / (2 * (2 - na) * (1 + na) / Ea + 2 * (2 - nw) * (1 + nw) / Ew);
  const double Ey = Ea * Eb / ((1 - na * na) * Eb + (1 - nb * nb) * Ea);
  const double Gy = 0.5 * (Ea / (2 * (1 + na)) + Eb / (2 * (1 + nb)));
  EXPECT_NEAR(Ey / (std::sqrt(2.0) * Y), 1.0, 1e-12);
  EXPECT_NEAR(Gy / (2 - 0.5 * (na + nb)) / (2 * std::sqrt(2.0) * G), 1.0, 1e-12);
}
