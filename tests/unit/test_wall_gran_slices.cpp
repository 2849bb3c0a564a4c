// compute wall/gran/slices: grains at rest pressed into a plane wall with
// chosen overlaps carry analytic Hertz forces; each slice holds the forces of
// the contacts whose height falls in it, the slices sum to f_ID[1], contacts
// outside [lo, hi] are clamped or dropped, and the slices reach thermo
// variables and fix ave/time (mode vector, hdf5).
#include <gtest/gtest.h>
#include <hdf5.h>

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "core/engine/compute.h"
#include "core/engine/fix.h"
#include "core/input/variable.h"
#include "tests/unit/deck_runner.h"
#include "tests/unit/right_wall_scene.h"

// A namespace per file: the unit tests compile in unity batches (tests/CMakeLists.txt).
namespace test_wall_gran_slices {

using sable::test::Deck;
using sable::test::error_of;
using sable::test::TempDir;

namespace {

using namespace sable::test::right_wall;
const char* kHead = kScene;

struct Grain {
  double y, delta;
};

// Grains at rest touching the right wall with overlap delta at height y (no
// integrator: nothing moves, so every step's forces are the same).
void place(Deck& d, const std::vector<Grain>& gs) {
  d(kHead);
  for (const Grain& g : gs)
    d("create_atoms 1 single " + std::to_string(kWall - kR + g.delta) + " " + std::to_string(g.y) + " 0 units box");
  for (std::size_t i = 0; i < d->atoms.n; ++i) d->atoms.set_radius_density(i, kR, kRho);
}

std::vector<double> slices(Deck& d, const char* id) {
  sable::Compute* c = d->find_compute(id);
  std::vector<double> s;
  for (int i = 1; i <= c->vector_size; ++i) s.push_back(c->vector(i));
  return s;
}

// Heights 0.5, 2.5, 4.5 and 7.5 mm (2r = 1.6 mm apart at least: no grain pairs).
const std::vector<Grain> kFour = {{0.0005, 1e-5}, {0.0025, 2e-5}, {0.0045, 4e-6}, {0.0075, 3e-5}};

}  // namespace

// Five slices of [0, 10 mm], 2 mm each: grains in slices 1, 2, 3 and 4, none in 5.
TEST(WallGranSlices, EachSliceHoldsItsContactsHertzForce) {
  Deck d;
  place(d, kFour);
  d("variable H equal 0.01");
  d("compute sl all wall/gran/slices right 5 dim y lo 0 hi v_H");
  d("run 3");
  const std::vector<double> s = slices(d, "sl");
  ASSERT_EQ(s.size(), 5u);
  for (int k = 0; k < 4; ++k) EXPECT_NEAR(s[k], hertz(kFour[k].delta), 1e-12 * hertz(kFour[k].delta)) << "slice " << k + 1;
  EXPECT_EQ(s[4], 0.0);
  // The slices sum to the wall's force of the last force pass (the grains' push, > 0 on the right wall).
  double sum = 0;
  for (double v : s) sum += v;
  const double fx = d->find_fix("right")->compute_vector(1);
  EXPECT_GT(fx, 0.0);
  EXPECT_NEAR(sum, fx, 1e-14 * fx);
}

// hi follows its variable at each invocation: halving H moves the 4.5 and 7.5 mm
// grains above hi, into the top slice (clamp, the default) or out (drop).
TEST(WallGranSlices, OutsideContactsClampedOrDropped) {
  Deck d;
  place(d, kFour);
  d("variable H equal 0.004");
  d("compute cl all wall/gran/slices right 2 dim y lo 0.001 hi v_H");
  d("compute dr all wall/gran/slices right 2 dim y lo 0.001 hi v_H outside drop");
  d("run 0");
  const std::vector<double> c = slices(d, "cl"), r = slices(d, "dr");
  const double f0 = hertz(kFour[0].delta), f1 = hertz(kFour[1].delta), f2 = hertz(kFour[2].delta),
               f3 = hertz(kFour[3].delta);
  // slices [1, 2.5) and [2.5, 4] mm: y = 0.5 below lo, y = 2.5 on the boundary goes up.
  EXPECT_NEAR(c[0], f0, 1e-12 * f0);
  EXPECT_NEAR(c[1], f1 + f2 + f3, 1e-12 * (f1 + f2 + f3));
  EXPECT_EQ(r[0], 0.0);
  EXPECT_NEAR(r[1], f1, 1e-12 * f1);
  EXPECT_NEAR(c[0] + c[1], d->find_fix("right")->compute_vector(1), 1e-14 * (f0 + f1 + f2 + f3));
}

// Only the compute's group counts; c_ID[i] reaches equal-style variables and fix
// ave/time mode vector, whose HDF5 file holds the same numbers.
TEST(WallGranSlices, GroupVariablesAndAveTimeHdf5) {
  TempDir tmp;
  std::vector<double> s;
  {
    Deck d;
    place(d, kFour);
    d("group low id 1 2");
    d("compute sl low wall/gran/slices right 2 dim y lo 0 hi 0.008");
    d("variable s1 equal c_sl[1]");
    d("fix at all ave/time 1 1 2 c_sl mode vector hdf5 " + (tmp / "sl.h5"));
    d("thermo_style custom step c_sl[1] c_sl[2]");
    d("run 4");
    s = slices(d, "sl");
    double v = 0;
    ASSERT_TRUE(d->variables->numeric("s1", v));
    EXPECT_EQ(v, s[0]);
    EXPECT_EQ(d->find_fix("at")->compute_vector(1), s[0]);
  }
  const double f0 = hertz(kFour[0].delta), f1 = hertz(kFour[1].delta);
  EXPECT_NEAR(s[0], f0 + f1, 1e-12 * (f0 + f1));  // grains 3 and 4 are not in the group
  EXPECT_EQ(s[1], 0.0);
  const hid_t f = H5Fopen((tmp / "sl.h5").c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  ASSERT_GE(f, 0);
  const hid_t ds = H5Dopen2(f, "values", H5P_DEFAULT);
  ASSERT_GE(ds, 0);
  const hid_t sp = H5Dget_space(ds);
  hsize_t dims[3] = {0, 0, 0};
  ASSERT_EQ(H5Sget_simple_extent_ndims(sp), 3);
  H5Sget_simple_extent_dims(sp, dims, nullptr);
  EXPECT_EQ(dims[0], 3u);  // steps 0, 2, 4
  EXPECT_EQ(dims[1], 2u);  // slices
  std::vector<double> vals(dims[0] * dims[1] * dims[2]);
  EXPECT_GE(H5Dread(ds, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, vals.data()), 0);
  EXPECT_EQ(vals[vals.size() - 2], s[0]);
  EXPECT_EQ(vals[vals.size() - 1], s[1]);
  H5Sclose(sp);
  H5Dclose(ds);
  H5Fclose(f);
}

// Bad input names the line and the word.
TEST(WallGranSlices, BadInputNamesTheWord) {
  Deck d;
  place(d, kFour);
  d("fix cyl all wall/gran model hertz tangential history primitive type 1 zcylinder 0.05 0 0");
  d("variable a atom x");
  const std::string pre = "compute s all wall/gran/slices ";
  EXPECT_NE(error_of(d, pre + "nowall 2 dim y lo 0 hi 1").find("test:1"), std::string::npos);
  EXPECT_NE(error_of(d, pre + "nowall 2 dim y lo 0 hi 1").find("nowall"), std::string::npos);
  EXPECT_NE(error_of(d, pre + "cyl 2 dim y lo 0 hi 1").find("xplane, yplane or zplane"), std::string::npos);
  EXPECT_NE(error_of(d, pre + "m1 2 dim y lo 0 hi 1").find("m1"), std::string::npos);
  EXPECT_NE(error_of(d, pre + "right 0 dim y lo 0 hi 1").find("1..100000"), std::string::npos);
  EXPECT_NE(error_of(d, pre + "right 2 dim w lo 0 hi 1").find("'w'"), std::string::npos);
  EXPECT_NE(error_of(d, pre + "right 2 dim y low 0 hi 1").find("'low'"), std::string::npos);
  EXPECT_NE(error_of(d, pre + "right 2 dim y lo 0 hi v_a").find("v_a"), std::string::npos);
  EXPECT_NE(error_of(d, pre + "right 2 dim y lo 0 hi 1 outside keep").find("'keep'"), std::string::npos);
  EXPECT_NE(error_of(d, pre + "right 2 dim y lo 0").find("missing word at the end"), std::string::npos);
  // hi not above lo: found when evaluated, naming the step and both values.
  d("variable H equal -1");
  d(pre + "right 2 dim y lo 0 hi v_H");
  d("run 0");
  const std::string e = error_of(d, "variable q equal c_s[1]\nprint $(v_q)");
  EXPECT_NE(e.find("not above lo"), std::string::npos) << e;
}

// Moving grains hitting the wall (dashpots on): the slices are the wall's last
// force pass, so they sum to f_ID[1] to rounding at every step, while the same
// contacts re-evaluated at output (wall/gran/local, after final_integrate's
// half kick) differ; the test fails if the slices re-evaluated too.
TEST(WallGranSlices, SumIsTheForcePassWhileGrainsMove) {
  Deck d;
  place(d, kFour);
  for (std::size_t i = 0; i < d->atoms.n; ++i) d->atoms.v[3 * i] = 0.05 * static_cast<double>(i + 1);
  d("fix i all nve/sphere");
  d("compute sl all wall/gran/slices right 4 dim y lo 0 hi 0.008");
  d("compute wl all wall/gran/local force");
  int checked = 0;
  for (int k = 0; k < 20; ++k) {
    d("run 3");
    double sum = 0, relocal = 0;
    for (double v : slices(d, "sl")) sum += v;
    sable::Compute* wl = d->find_compute("wl");
    wl->local_now();
    for (std::size_t r = 0; r < wl->local_rows(); ++r) relocal -= wl->local[r * wl->local_cols + 3];  // fx column
    const double fx = d->find_fix("right")->compute_vector(1);
    if (fx == 0.0) continue;
    EXPECT_NEAR(sum, fx, 1e-13 * std::fabs(fx)) << "step " << d->step;
    EXPECT_GT(std::fabs(relocal - fx), 1e-6 * std::fabs(fx)) << "step " << d->step;
    ++checked;
  }
  EXPECT_GE(checked, 10);
}

// Local rows: every contact of the group's grains with this wall only (a left
// wall's contacts are not listed), id, the point on the wall, the force on the wall.
TEST(WallGranSlices, LocalRowsAreThisWallsContacts) {
  Deck d;
  place(d, kFour);
  d("fix left all wall/gran model hertz tangential history primitive type 1 xplane 0.0");
  d("create_atoms 1 single 0.00079 0.003 0 units box");  // on the left wall, overlap 1e-5
  d->atoms.set_radius_density(d->atoms.n - 1, kR, kRho);
  d("compute sl all wall/gran/slices right 2 dim y lo 0 hi 0.008");
  d("run 2");
  sable::Compute* c = d->find_compute("sl");
  c->local_now();
  ASSERT_EQ(c->local_cols, 7);
  EXPECT_EQ(c->local_names, (std::vector<std::string>{"id", "x", "y", "z", "fx", "fy", "fz"}));
  ASSERT_EQ(c->local_rows(), 4u);
  double sum = 0;
  for (std::size_t r = 0; r < 4; ++r) {
    const double* row = &c->local[r * 7];
    const int id = static_cast<int>(row[0]);
    ASSERT_GE(id, 1);
    ASSERT_LE(id, 4);
    const double f = hertz(kFour[id - 1].delta);
    EXPECT_EQ(row[1], kWall);
    EXPECT_EQ(row[2], d->atoms.x[3 * d->atoms.index_of(id) + 1]);
    EXPECT_NEAR(row[4], f, 1e-12 * f);  // on the wall: + x
    EXPECT_EQ(row[5], 0.0);
    sum += row[4];
  }
  EXPECT_NEAR(sum, d->find_fix("right")->compute_vector(1), 1e-14 * sum);
  EXPECT_LT(d->find_fix("left")->compute_vector(1), 0.0);  // the left wall is pushed along -x
}

// Grains deleted after the force pass: its atom indices no longer hold, so the
// contacts are re-evaluated at the new state (the grains are at rest: the same Hertz forces).
TEST(WallGranSlices, AfterDeletingGrainsTheContactsAreReevaluated) {
  Deck d;
  place(d, kFour);
  d("compute sl all wall/gran/slices right 5 dim y lo 0 hi 0.01");
  d("run 1");
  d("group gone id 1 3");
  d("delete_atoms group gone");
  const std::vector<double> s = slices(d, "sl");
  EXPECT_EQ(s[0], 0.0);
  EXPECT_NEAR(s[1], hertz(kFour[1].delta), 1e-12 * hertz(kFour[1].delta));
  EXPECT_EQ(s[2], 0.0);
  EXPECT_NEAR(s[3], hertz(kFour[3].delta), 1e-12 * hertz(kFour[3].delta));
  sable::Compute* c = d->find_compute("sl");
  c->local_now();
  EXPECT_EQ(c->local_rows(), 2u);
}

}  // namespace test_wall_gran_slices
