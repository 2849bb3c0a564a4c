// compute property/atom: per-atom copies of attributes (zero outside the
// group), read by compute reduce (c_ID, c_ID[k]), dump custom, atom- and
// equal-style variables; and f_ID / f_ID[k] / c_ID[k] of global fix and
// compute outputs in equal-style variables and fix ave/time. Values are copies
// or single reductions, so they must match exactly.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <unistd.h>

#include "core/engine/error.h"
#include "core/input/variable.h"
#include "tests/unit/deck_runner.h"

// A namespace per file: the unit tests compile in unity batches (tests/CMakeLists.txt).
namespace test_compute_property_atom {

using sable::test::Deck;
using sable::test::error_of;

namespace {

double var(Deck& d, const std::string& name) {
  double v = 0;
  EXPECT_TRUE(d->variables->numeric(name, v)) << name;
  return v;
}

// Three grains, the second in group "low".
void three_grains(Deck& d) {
  d(R"(units si
atom_style granular
region box block 0 1 0 1 0 1 units box
create_box 1 box
create_atoms 1 single 0.5 0.5 0.9 units box
create_atoms 1 single 0.2 0.3 0.4 units box
create_atoms 1 single 0.7 0.1 0.2 units box
group low id 2)");
  sable::Atoms& a = d->atoms;
  const double v[3] = {1.5, -2, 0.25};
  for (int i = 0; i < 3; ++i) {
    a.v[3 * i + 2] = v[i];
    a.omega[3 * i] = 10.0 * i;
    a.set_radius_density(i, 0.01 * (i + 1), 2500);
  }
}

}  // namespace

TEST(ComputePropertyAtom, VectorAndArrayCopyAttributesZeroOutsideTheGroup) {
  Deck d;
  three_grains(d);
  d("compute pz all property/atom z\ncompute p3 low property/atom id vz radius omegax mass");
  auto* pz = d->find_compute("pz");
  auto* p3 = d->find_compute("p3");
  ASSERT_TRUE(pz->peratom_flag && p3->peratom_flag);
  EXPECT_EQ(pz->peratom_cols, 0);
  EXPECT_EQ(p3->peratom_cols, 5);
  pz->peratom_now();
  p3->peratom_now();
  const auto& a = d->atoms;
  for (std::size_t i = 0; i < a.n; ++i) {
    EXPECT_EQ(pz->peratom[i], a.x[3 * i + 2]);
    const bool in = a.id[i] == 2;
    EXPECT_EQ(p3->peratom[5 * i + 0], in ? 2.0 : 0.0);
    EXPECT_EQ(p3->peratom[5 * i + 1], in ? a.v[3 * i + 2] : 0.0);
    EXPECT_EQ(p3->peratom[5 * i + 2], in ? a.radius[i] : 0.0);
    EXPECT_EQ(p3->peratom[5 * i + 3], in ? a.omega[3 * i] : 0.0);
    EXPECT_EQ(p3->peratom[5 * i + 4], in ? a.rmass[i] : 0.0);
  }
}

// The bed-height idiom of LIGGGHTS decks: reduce max over c_pz, read in an
// equal-style variable; c_ID[k] of an array; atom-style variables see c_ID.
TEST(ComputePropertyAtom, ReduceAndVariablesReadIt) {
  Deck d;
  three_grains(d);
  d(R"(compute pz all property/atom z
compute zmax all reduce max c_pz
compute pa all property/atom vz radius
compute r all reduce sum c_pa[1] c_pa[2]
compute rmin all reduce min c_pa[2]
variable h equal c_zmax
variable s equal c_r[2]
variable m equal c_rmin
variable twice atom 2*c_pz)");
  EXPECT_EQ(var(d, "h"), 0.9);
  EXPECT_DOUBLE_EQ(var(d, "s"), 0.01 + 0.02 + 0.03);
  EXPECT_EQ(var(d, "m"), 0.01);
  EXPECT_EQ(d->find_compute("r")->compute_vector(1), 1.5 + -2 + 0.25);
  std::vector<double> twice;
  ASSERT_TRUE(d->variables->atom_values("twice", twice));
  for (std::size_t i = 0; i < d->atoms.n; ++i) EXPECT_EQ(twice[i], 2 * d->atoms.x[3 * i + 2]);
}

// Two grains, the second alone in group low: property/atom array and vector
// in dump custom and compute reduce, byte for byte what LIGGGHTS 3.8 writes
// for the same deck (its run of it, with a gran pair style it needs, below).
TEST(ComputePropertyAtom, DumpCustomAndReduceMatchLiggghts) {
  Deck d;
  d(R"(units si
atom_style granular
boundary f f f
region box block 0 1 0 1 0 1 units box
create_box 1 box
create_atoms 1 single 0.5 0.5 0.9 units box
create_atoms 1 single 0.2 0.3 0.4 units box
group low id 2
set atom * diameter 0.02 density 2500
fix integr all nve/sphere
compute pa low property/atom radius z mass
compute pz all property/atom z
compute r all reduce sum c_pa[3] c_pz
thermo_style custom step atoms c_r[1] c_r[2])");
  const auto file = std::filesystem::temp_directory_path() / ("sable_pa_" + std::to_string(::getpid()) + ".dump");
  d("dump d all custom 1 " + file.string() + " id c_pa[1] c_pa[2] c_pa[3] c_pz\ndump_modify d sort id\nrun 0");
  std::ifstream in(file);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  std::filesystem::remove(file);
  EXPECT_EQ(text,
            "ITEM: TIMESTEP\n0\nITEM: NUMBER OF ATOMS\n2\nITEM: BOX BOUNDS ff ff ff\n0 1\n0 1\n0 1\n"
            "ITEM: ATOMS id c_pa[1] c_pa[2] c_pa[3] c_pz \n"
            "1 0 0 0 0.9 \n"
            "2 0.01 0.4 0.010472 0.4 \n");
  // LIGGGHTS prints SUM 0.010471975511965976244 1.3000000000000000444 for $(c_r[1]) $(c_r[2]).
  EXPECT_EQ(d->find_compute("r")->compute_vector(1), d->atoms.rmass[d->atoms.index_of(2)]);
  EXPECT_EQ(d->find_compute("r")->compute_vector(2), 0.9 + 0.4);
}

TEST(ComputePropertyAtom, BadAttributesNameTheWord) {
  Deck d;
  three_grains(d);
  EXPECT_NE(error_of(d, "compute p all property/atom").find("at least one atom attribute"), std::string::npos);
  EXPECT_NE(error_of(d, "compute p all property/atom z colour").find("'colour'"), std::string::npos);
  EXPECT_NE(error_of(d, "compute p all property/atom q").find("LIGGGHTS attribute of other atom styles"),
            std::string::npos);
  EXPECT_NE(error_of(d, "compute p all property/atom c_x").find("expected an atom attribute"), std::string::npos);
  d("compute p2 all property/atom x y");
  EXPECT_NE(error_of(d, "compute r all reduce max c_p2").find("c_p2[N]"), std::string::npos);
  EXPECT_NE(error_of(d, "compute r all reduce max c_p2[3]").find("in 1..2"), std::string::npos);
}

// f_ID[k] of a fix with a global vector (wall/gran: force on the wall) in an
// equal-style variable and in fix ave/time; f_ID without a scalar, an element
// past the end and c_ID of a per-atom compute are errors naming the reference.
TEST(GlobalReferences, FixVectorInVariablesAndAveTime) {
  Deck d;
  d(R"(units si
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
fix floor all wall/gran model hertz tangential history primitive type 1 zplane 0.0
create_atoms 1 single 0.005 0.005 0.00099 units box
set atom 1 diameter 0.002 density 2500
fix integr all nve/sphere
variable fz equal f_floor[3]
variable fx equal f_floor[1]
fix at all ave/time 1 1 1 f_floor[3] v_fz
run 1)");
  const double fz = d->find_fix("floor")->compute_vector(3);
  ASSERT_NE(fz, 0.0);  // the grain presses 10 um into the floor
  EXPECT_EQ(var(d, "fz"), fz);
  EXPECT_EQ(var(d, "fx"), d->find_fix("floor")->compute_vector(1));
  EXPECT_EQ(d->find_fix("at")->compute_vector(1), fz);
  EXPECT_EQ(d->find_fix("at")->compute_vector(2), fz);
  d("compute pz all property/atom z");
  d("variable bad equal f_floor[4]\nvariable nos equal f_floor\nvariable pa equal c_pz");  // evaluated when used
  EXPECT_NE(error_of(d, "print \"$(v_bad)\"").find("'f_floor[4]' (no such ID, or it has no vector element 4)"),
            std::string::npos);
  EXPECT_NE(error_of(d, "print \"$(v_nos)\"").find("'f_floor' (no such ID, or it has no global scalar)"),
            std::string::npos);
  EXPECT_NE(error_of(d, "print \"$(v_pa)\"").find("'c_pz' (no such ID, or it has no global scalar)"),
            std::string::npos);
  EXPECT_NE(error_of(d, "fix bad all ave/time 1 1 1 f_floor[4]").find("f_floor[4]"), std::string::npos);
}

// LAMMPS group functions take an optional region (count(all,low)): it was ignored.
TEST(GroupFunctions, RegionArgumentRestricts) {
  Deck d;
  three_grains(d);  // z = 0.9, 0.4, 0.2
  d(R"(region low block INF INF INF INF INF 0.5 units box
variable n equal count(all,low)
variable m equal mass(all,low)
variable zc equal xcm(all,z,low)
variable top equal bound(all,zmax,low))");
  const auto& a = d->atoms;
  EXPECT_EQ(var(d, "n"), 2.0);
  EXPECT_EQ(var(d, "m"), a.rmass[1] + a.rmass[2]);
  EXPECT_DOUBLE_EQ(var(d, "zc"), (a.rmass[1] * 0.4 + a.rmass[2] * 0.2) / (a.rmass[1] + a.rmass[2]));
  EXPECT_EQ(var(d, "top"), 0.4);
  d("variable bad equal count(all,nowhere)");
  EXPECT_NE(error_of(d, "print \"$(v_bad)\"").find("region 'nowhere' in count() does not exist"), std::string::npos);
}

// delete_atoms between runs, at the same step: the per-atom array and compute
// reduce's values must not be those cached for the atoms before. (A global
// scalar c_ID read again at that step still is: Compute::scalar() caches per
// step, as LIGGGHTS 3.8 does, which prints the stale 0.9 there too.)
TEST(ComputePropertyAtom, FreshAfterDeleteAtomsAtTheSameStep) {
  Deck d;
  three_grains(d);  // z = 0.9, 0.4, 0.2
  d(R"(compute pz all property/atom z
compute zmax all reduce max c_pz
compute both all reduce max c_pz vz
variable h equal c_zmax
variable hv equal c_both[1]
fix integr all nve/sphere
thermo_style custom step atoms c_zmax c_both[1]
run 0)");
  EXPECT_EQ(var(d, "h"), 0.9);
  EXPECT_EQ(var(d, "hv"), 0.9);
  d("region hi block INF INF INF INF 0.8 INF units box\ndelete_atoms region hi");
  EXPECT_EQ(var(d, "hv"), 0.4);
  EXPECT_EQ(var(d, "h"), 0.4);  // a global scalar read at this step is recomputed too (LIGGGHTS 3.8 keeps 0.9)
  d("compute zmax2 all reduce max c_pz\nvariable h2 equal c_zmax2");
  EXPECT_EQ(var(d, "h2"), 0.4);
  d("run 0");
  EXPECT_EQ(var(d, "h"), 0.4);
}

}  // namespace test_compute_property_atom
