// Same deck, same physics: runs decks in LIGGGHTS 3.8 (Debian package
// `liggghts`, skipped when it is not installed) and in sable, and compares
// positions, velocities and spins after the run.
//  * Every model combination (4 normal x 3 tangential x 3 rolling) for two
//    colliding, spinning grains plus a shearing plane or a cylinder wall,
//    150 steps: agreement to ~1e-12 relative (round-off of a different
//    evaluation order). Tolerance 1e-9.
//  * 1400 grains in a periodic box falling on a floor (hertz, history,
//    epsd2, two materials), 1000 steps of collisions: with
//    `historyResetAtRebuild on` (LIGGGHTS' reset of separated pairs' history at
//    the next neighbour rebuild, see contact_models/pair_gran.h) the runs
//    agree to round-off growth; tolerance 1e-8.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include <unistd.h>

#include "tests/unit/deck_runner.h"

// A namespace per file: the unit tests compile in unity batches (tests/CMakeLists.txt).
namespace test_contact_liggghts {

using sable::test::Deck;

namespace {

bool have_liggghts() { return std::system("command -v liggghts > /dev/null 2>&1") == 0; }

// Runs deck text in LIGGGHTS and returns the numbers of every output line starting with "R ".
std::vector<std::vector<double>> liggghts_rows(const std::string& text, const std::string& tag) {
  // One file per test and process: ctest runs tests in parallel in the same folder.
  const std::string file = "liggghts_compare_" + tag + "_" + std::to_string(getpid()) + ".in";
  std::ofstream(file) << text;
  std::unique_ptr<FILE, int (*)(FILE*)> p(popen(("liggghts -in " + file + " -echo none -log none 2>&1").c_str(), "r"),
                                          pclose);
  std::vector<std::vector<double>> rows;
  std::array<char, 8192> buf;
  while (p && fgets(buf.data(), buf.size(), p.get())) {
    std::string line(buf.data());
    if (line.rfind("R ", 0) != 0) continue;
    std::istringstream in(line.substr(2));
    std::vector<double> r;
    for (double x; in >> x;) r.push_back(x);
    rows.push_back(r);
  }
  std::remove(file.c_str());
  return rows;
}

const char* kQ[] = {"x", "y", "z", "vx", "vy", "vz", "omegax", "omegay", "omegaz"};

std::string print_line(const std::vector<long>& ids) {
  std::string vars, line = "print \"R";
  for (long id : ids)
    for (const char* q : kQ) {
      const std::string v = std::string(q) + std::to_string(id);
      vars += "variable " + v + " equal " + q + "[" + std::to_string(id) + "]\n";
      line += " ${" + v + "}";
    }
  return vars + line + "\"\n";
}

std::vector<double> sable_row(Deck& d, const std::vector<long>& ids) {
  std::vector<double> r;
  const auto& at = d->atoms;
  for (long id : ids) {
    const std::size_t i = at.index_of(id);
    for (int k = 0; k < 3; ++k) r.push_back(at.x[3 * i + k]);
    for (int k = 0; k < 3; ++k) r.push_back(at.v[3 * i + k]);
    for (int k = 0; k < 3; ++k) r.push_back(at.omega[3 * i + k]);
  }
  return r;
}

double worst_rel(const std::vector<double>& a, const std::vector<double>& b) {
  double w = a.size() == b.size() ? 0.0 : 1e300;
  for (std::size_t k = 0; k < std::min(a.size(), b.size()); ++k)
    w = std::max(w, std::fabs(a[k] - b[k]) / std::max(std::fabs(a[k]), 1e-12));
  return w;
}

std::string pair_case(const std::string& model, const std::string& wall) {
  std::string s = R"(units si
atom_style granular
atom_modify map array
boundary f f f
newton off
communicate single vel yes
region reg block -0.1 0.1 -0.1 0.1 -0.1 0.1 units box
create_box 1 reg
neighbor 0.002 bin
neigh_modify delay 0
fix m1 all property/global youngsModulus peratomtype 5.e6
fix m2 all property/global poissonsRatio peratomtype 0.45
fix m3 all property/global coefficientRestitution peratomtypepair 1 0.9
fix m4 all property/global coefficientFriction peratomtypepair 1 0.5
fix m5 all property/global characteristicVelocity scalar 2.
fix m6 all property/global kn peratomtypepair 1 2000
fix m7 all property/global kt peratomtypepair 1 1500
fix m8 all property/global gamman peratomtypepair 1 300
fix m9 all property/global gammat peratomtypepair 1 200
fix m10 all property/global coefficientRollingFriction peratomtypepair 1 0.3
)";
  if (model.find("hertz/stiffness") != std::string::npos)
    s += "fix m6 all property/global kn peratomtypepair 1 2e6\nfix m7 all property/global kt peratomtypepair 1 1.5e6\n"
         "fix m8 all property/global gamman peratomtypepair 1 3e4\nfix m9 all property/global gammat peratomtypepair 1 2e4\n";
  s += "pair_style gran " + model + "\npair_coeff * *\n";
  s += R"(timestep 0.000001
create_atoms 1 single 0.00001 0.00002 0
create_atoms 1 single 0.0019 0.0005 0.0001
set atom 1 diameter 0.002 density 2500 vx 0.1 omegaz 3 omegax 1
set atom 2 diameter 0.002 density 2500 vx -0.1 vy 0.05 omegay -2
)";
  if (!wall.empty()) s += "fix w all wall/gran " + model + " primitive type 1 " + wall + "\n";
  s += "fix integr all nve/sphere\nrun 150\n";
  return s;
}

}  // namespace

TEST(ContactLiggghts, EveryModelCombinationMatchesLiggghts) {
  if (!have_liggghts()) GTEST_SKIP() << "liggghts is not installed";
  std::vector<std::string> models;
  for (const char* n : {"hertz", "hooke", "hooke/stiffness", "hertz/stiffness"})
    for (const char* t : {"off", "no_history", "history"})
      for (const char* r : {"off", "cdt", "epsd2"})
        models.push_back(std::string("model ") + n + " tangential " + t + " rolling_friction " + r);
  const std::vector<std::string> walls = {"zplane -0.0003 shear x 0.02", "zcylinder 0.0017 0 0 shear z 0.1",
                                          "zcylinder 0.0017 0 0 shear x 5"};
  // Cases: every model with the shearing plane; the history models with the two cylinders; a few keywords.
  std::vector<std::pair<std::string, std::string>> cases;
  for (auto& m : models) cases.push_back({m, walls[0]});
  for (auto& m : models)
    if (m.find("tangential history") != std::string::npos && m.find("rolling_friction off") != std::string::npos)
      for (int w : {1, 2}) cases.push_back({m, walls[w]});
  cases.push_back({"model hertz tangential history rolling_friction cdt limitForce on tangential_damping off", ""});
  cases.push_back({"model hooke tangential history rolling_friction epsd2 ktToKnUser on", ""});
  cases.push_back({"model hertz tangential history rolling_friction epsd2 torsionTorque on", walls[0]});
  // One LIGGGHTS process runs all cases, separated by `clear`; model keywords go after the wall arguments.
  std::string all;
  for (auto& [m, w] : cases) {
    std::string deck = pair_case(m, w);
    const auto kw = m.find(" rolling_friction ");
    const std::string models_only = m.substr(0, m.find(' ', kw + 18) == std::string::npos ? m.size() : m.find(' ', kw + 18));
    const std::string keywords = m.substr(models_only.size());
    if (!w.empty() && !keywords.empty()) {  // LIGGGHTS wants model keywords after the wall arguments
      const std::string from = "wall/gran " + m + " primitive type 1 " + w;
      deck.replace(deck.find(from), from.size(), "wall/gran " + models_only + " primitive type 1 " + w + keywords);
    }
    all += deck + print_line({1, 2}) + "clear\n";
  }
  const auto rows = liggghts_rows(all, "models");
  ASSERT_EQ(rows.size(), cases.size()) << "LIGGGHTS did not run every case";
  double worst = 0;
  for (std::size_t c = 0; c < cases.size(); ++c) {
    Deck d;
    d(pair_case(cases[c].first, cases[c].second));
    const double w = worst_rel(rows[c], sable_row(d, {1, 2}));
    worst = std::max(worst, w);
    EXPECT_LT(w, 1e-9) << cases[c].first << " / wall " << cases[c].second;
  }
  std::printf("%zu model/wall cases vs LIGGGHTS: worst relative difference %.2e\n", cases.size(), worst);
}

TEST(ContactLiggghts, ManyGrainsPeriodicMatchLiggghtsWithItsHistoryConvention) {
  if (!have_liggghts()) GTEST_SKIP() << "liggghts is not installed";
  const std::string deck = R"(atom_style granular
atom_modify map array
boundary p p f
newton off
communicate single vel yes
units si
region reg block 0 0.02 0 0.02 0 0.04 units box
create_box 2 reg
neighbor 0.0005 bin
neigh_modify delay 0
fix m1 all property/global youngsModulus peratomtype 5.e6 1e7
fix m2 all property/global poissonsRatio peratomtype 0.45 0.3
fix m3 all property/global coefficientRestitution peratomtypepair 2 0.8 0.7 0.7 0.6
fix m4 all property/global coefficientFriction peratomtypepair 2 0.5 0.4 0.4 0.3
fix m5 all property/global coefficientRollingFriction peratomtypepair 2 0.1 0.1 0.1 0.1
pair_style gran model hertz tangential history rolling_friction epsd2 HISTORYKW
pair_coeff * *
timestep 0.000005
lattice sc 0.0021
region ins block 0 0.02 0 0.02 0.002 0.03 units box
create_atoms 1 region ins
variable vx atom 0.1*sin(id*1.7)
variable vy atom 0.1*cos(id*2.3)
variable vz atom -0.2+0.05*sin(id*0.7)
set group all diameter 0.002 density 2500
set group all vx v_vx vy v_vy vz v_vz
set atom 1*50 type 2
fix w all wall/gran model hertz tangential history rolling_friction epsd2 primitive type 2 zplane 0.0
fix g all gravity 9.81 vector 0 0 -1
fix integr all nve/sphere
run 1000
)";
  const std::vector<long> ids = {1, 77, 500, 938, 1234, 1400};
  auto with = [&](const std::string& kw) {
    std::string s = deck;
    s.replace(s.find("HISTORYKW"), 9, kw);
    return s;
  };
  const auto rows = liggghts_rows(with("") + print_line(ids), "grains");
  ASSERT_EQ(rows.size(), 1u);
  Deck d;
  d(with("historyResetAtRebuild on"));
  ASSERT_EQ(d->atoms.n, 1400u);
  const double w = worst_rel(rows[0], sable_row(d, ids));
  std::printf("1400 grains, 1000 steps vs LIGGGHTS: worst relative difference %.2e (%ld neighbour builds)\n", w,
              d->neighbor.builds);
  EXPECT_LT(w, 1e-8);
}

}  // namespace test_contact_liggghts
