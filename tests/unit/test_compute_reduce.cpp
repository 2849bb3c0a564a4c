// compute reduce sum/min/max/ave against hand computation (relative 1e-12: a
// handful of additions), over atom attributes, per-atom computes, atom-style
// variables and local (per-contact) computes; replace; scalar vs vector.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "core/input/style_registry.h"
#include "core/io/thermo.h"
#include "core/input/variable.h"
#include "tests/unit/deck_runner.h"

// A namespace per file: the unit tests compile in unity batches (tests/CMakeLists.txt).
namespace test_compute_reduce {

using sable::test::Deck;
using sable::test::error_of;

namespace {

// Per-atom test compute: 10 * id.
class ComputeReduceTestPeratom : public sable::Compute {
 public:
  ComputeReduceTestPeratom(sable::Simulation& s, const sable::Args& a) : Compute(s, a) { peratom_flag = true; }
  void compute_peratom() override {
    peratom.resize(sim.atoms.n);
    for (std::size_t i = 0; i < sim.atoms.n; ++i) peratom[i] = 10.0 * sim.atoms.id[i];
  }
};

// Local test compute (like pair/gran/local): rows (1, 5), (2, -7), (3, 4).
class ComputeReduceTestLocal : public sable::Compute {
 public:
  ComputeReduceTestLocal(sable::Simulation& s, const sable::Args& a) : Compute(s, a) {
    local_flag = true;
    local_cols = 2;
  }
  void compute_local() override { local = {1, 5, 2, -7, 3, 4}; }
};

void three_grains(Deck& d) {
  d(R"(units si
atom_style granular
region box block 0 1 0 1 0 1 units box
create_box 1 box
create_atoms 1 single 0.5 0.5 0.9 units box
create_atoms 1 single 0.2 0.3 0.4 units box
create_atoms 1 single 0.7 0.1 0.2 units box
compute pa all test/reduce_peratom
compute loc all test/reduce_local
variable sq atom vx*vx)");
  sable::Atoms& a = d->atoms;
  const double v[3][3] = {{1.5, -2, 0.25}, {0.1, 0, 0}, {0, 0, -0.5}};
  const double w[3] = {3, -1, 0.5};  // omegaz
  const double r[3] = {0.05, 0.1, 0.025}, rho[3] = {2500, 1000, 3000};
  for (int i = 0; i < 3; ++i) {
    for (int k = 0; k < 3; ++k) a.v[3 * i + k] = v[i][k];
    a.omega[3 * i + 2] = w[i];
    a.set_radius_density(i, r[i], rho[i]);
  }
}

double mass(double r, double rho) { return 4.0 / 3.0 * std::numbers::pi * r * r * r * rho; }

}  // namespace

SABLE_COMPUTE("test/reduce_peratom", ComputeReduceTestPeratom);
SABLE_COMPUTE("test/reduce_local", ComputeReduceTestLocal);

TEST(ComputeReduce, SumMinMaxAveOverAtomInputs) {
  Deck d;
  three_grains(d);
  const std::string in = " x vx vz radius mass omegaz c_pa v_sq";
  d("compute s all reduce sum" + in + "\ncompute mn all reduce min" + in + "\ncompute mx all reduce max" + in +
    "\ncompute av all reduce ave" + in);
  const double m[3] = {mass(0.05, 2500), mass(0.1, 1000), mass(0.025, 3000)};
  const std::vector<std::vector<double>> vals = {
      {0.5, 0.2, 0.7}, {1.5, 0.1, 0}, {0.25, 0, -0.5}, {0.05, 0.1, 0.025},
      {m[0], m[1], m[2]}, {3, -1, 0.5}, {10, 20, 30}, {2.25, 0.01, 0}};
  sable::Compute* s = d->find_compute("s");
  ASSERT_FALSE(s->scalar_flag);  // several inputs: a global vector
  ASSERT_EQ(s->vector_size, 8);
  for (int q = 0; q < 8; ++q) {
    const auto& v = vals[q];
    const double sum = v[0] + v[1] + v[2], tol = 1e-12 * std::max(1.0, std::abs(sum));
    EXPECT_NEAR(s->vector(q + 1), sum, tol) << q;
    EXPECT_NEAR(d->find_compute("av")->vector(q + 1), sum / 3, tol) << q;
    EXPECT_EQ(d->find_compute("mn")->vector(q + 1), std::min({v[0], v[1], v[2]})) << q;
    EXPECT_EQ(d->find_compute("mx")->vector(q + 1), std::max({v[0], v[1], v[2]})) << q;
  }
}

TEST(ComputeReduce, OneInputIsAScalarAndGroupRestricts) {
  Deck d;
  three_grains(d);
  const int g = d->groups.find_or_create("lower");  // atoms 2 and 3
  d->atoms.mask[1] |= d->groups.bit(g);
  d->atoms.mask[2] |= d->groups.bit(g);
  d("compute s lower reduce sum vx\ncompute a lower reduce ave c_pa");
  sable::Compute* s = d->find_compute("s");
  ASSERT_TRUE(s->scalar_flag);
  EXPECT_EQ(s->vector_size, 0);
  EXPECT_NEAR(s->scalar(), 0.1, 1e-12);
  EXPECT_NEAR(d->find_compute("a")->scalar(), 25.0, 1e-12 * 25);
}

TEST(ComputeReduce, RegionRestrictsAndEmptySelectionGivesLiggghtsValues) {
  Deck d;
  three_grains(d);
  d("region top block 0 1 0 1 0.5 1 units box\nregion nowhere block 0 0.1 0.9 1 0.9 1 units box\n"
    "compute t all reduce/region top sum vx\n"
    "compute e all reduce/region nowhere min vx\ncompute f all reduce/region nowhere max vx\n"
    "compute g all reduce/region nowhere ave vx");
  EXPECT_NEAR(d->find_compute("t")->scalar(), 1.5, 1e-12);  // only atom 1 (z = 0.9)
  EXPECT_EQ(d->find_compute("e")->scalar(), 1e20);
  EXPECT_EQ(d->find_compute("f")->scalar(), -1e20);
  EXPECT_EQ(d->find_compute("g")->scalar(), 0.0);
}

TEST(ComputeReduce, ReplaceReportsTheRowOfTheExtreme) {
  Deck d;
  three_grains(d);
  // id and radius of the atom with the largest |omegaz| ... here: largest omegaz (atom 1), smallest (atom 2).
  d("compute hi all reduce max id radius omegaz replace 1 3 replace 2 3\n"
    "compute lo all reduce min id omegaz replace 1 2");
  sable::Compute* hi = d->find_compute("hi");
  EXPECT_EQ(hi->vector(1), 1);
  EXPECT_EQ(hi->vector(2), 0.05);
  EXPECT_EQ(hi->vector(3), 3);
  EXPECT_EQ(d->find_compute("lo")->vector(1), 2);
  EXPECT_EQ(d->find_compute("lo")->vector(2), -1);
  EXPECT_NE(error_of(d, "compute bad all reduce sum id vx replace 1 2").find("expected no 'replace'"),
            std::string::npos);
  EXPECT_NE(error_of(d, "compute bad all reduce max id vx replace 1 3").find("expected an input index in 1..2"),
            std::string::npos);
}

TEST(ComputeReduce, LocalInputsReduceOverAllRows) {
  Deck d;
  three_grains(d);
  d("compute l all reduce sum c_loc[1] c_loc[2]\ncompute lm all reduce max c_loc[1] c_loc[2] replace 1 2\n"
    "compute la all reduce ave c_loc[2]");
  EXPECT_EQ(d->find_compute("l")->vector(1), 6);
  EXPECT_EQ(d->find_compute("l")->vector(2), 2);
  EXPECT_EQ(d->find_compute("lm")->vector(1), 1);  // row of the max of column 2 (5)
  EXPECT_NEAR(d->find_compute("la")->scalar(), 2.0 / 3.0, 1e-12);
  EXPECT_NE(error_of(d, "compute bad all reduce sum c_loc").find("expected c_loc[N]"), std::string::npos);
}

TEST(ComputeReduce, ThermoAndVariablesSeeTheValues) {
  Deck d;
  three_grains(d);
  d("compute s all reduce sum vx vy\nvariable vy equal c_s[2]\nthermo_style custom step c_s[1] c_s[2]");
  double vy = 0;
  ASSERT_TRUE(d->variables->numeric("vy", vy));
  EXPECT_NEAR(vy, -2.0, 1e-12);
  EXPECT_NEAR(d->thermo->column("c_s[1]", sable::Args()), 1.6, 1e-12);
}

TEST(ComputeReduce, BadInputsNameTheWord) {
  Deck d;
  three_grains(d);
  EXPECT_NE(error_of(d, "compute r all reduce sum vx q").find("'q' in 'compute r all reduce sum vx q': expected a per-atom attribute"),
            std::string::npos);
  EXPECT_NE(error_of(d, "compute r all reduce sum c_nope").find("expected an existing compute ID (no compute 'nope')"),
            std::string::npos);
  d("variable e equal 2");
  EXPECT_NE(error_of(d, "compute r all reduce sum v_e").find("expected an atom-style variable"), std::string::npos);
  EXPECT_NE(error_of(d, "compute r all reduce").find("expected a reduce mode"), std::string::npos);
  EXPECT_NE(error_of(d, "compute r all reduce median vx").find("expected a reduce mode: sum, min, max or ave"),
            std::string::npos);
  EXPECT_NE(error_of(d, "compute r all reduce max").find("expected at least one input"), std::string::npos);
}

}  // namespace test_compute_reduce
