// fix ave/time and fix ave/histo: averages and counts against hand computation
// (1e-12), file formats against LIGGGHTS 3.8 output, HDF5 read back with the
// HDF5 C API, and a kill -9 test: every file a killed run leaves must parse.
#include <gtest/gtest.h>
#include <hdf5.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "core/engine/compute.h"
#include "core/engine/error.h"
#include "core/input/style_registry.h"
#include "tests/unit/deck_runner.h"

// A namespace per file: the unit tests compile in unity batches (tests/CMakeLists.txt).
namespace test_fix_ave {

using sable::test::Deck;
using sable::test::error_of;
using sable::test::TempDir;
namespace fs = std::filesystem;

namespace {

std::string read_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}
std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream ss(text);
  for (std::string l; std::getline(ss, l);) out.push_back(l);
  return out;
}
// Whitespace-separated numbers of a line; false if any word is not a whole number.
bool numbers(const std::string& line, std::vector<double>& out) {
  out.clear();
  std::istringstream ss(line);
  for (std::string w; ss >> w;) {
    char* end = nullptr;
    out.push_back(std::strtod(w.c_str(), &end));
    if (*end) return false;
  }
  return true;
}

// Global vector (i * step, i = 1..3): exact, step-dependent inputs for mode vector.
class ComputeStepVec : public sable::Compute {
 public:
  ComputeStepVec(sable::Simulation& s, const sable::Args& a) : Compute(s, a) { vector_size = 3; }
  double compute_vector(int i) override { return i * static_cast<double>(sim.step); }
};
SABLE_COMPUTE("test/stepvec", ComputeStepVec);

const char* kBox = R"(units si
atom_style granular
region box block -1 1 -1 1 -1 1 units box
create_box 1 box
variable s equal step*step
variable t equal step)";

double rel(double a, double b) { return std::fabs(a - b) / std::max(1.0, std::fabs(b)); }

}  // namespace

// Nrepeat samples Nevery apart before each multiple of Nfreq, averaged: at step 10 the mean of steps 6, 8, 10.
TEST(FixAveTime, ScalarAveragesAndFileMatchHandComputation) {
  TempDir tmp;
  Deck d;
  d(kBox)("fix a all ave/time 2 3 10 v_s v_t file " + (tmp / "a.txt"))("run 30");
  auto* f = d->find_fix("a");
  EXPECT_LT(rel(f->compute_vector(1), (26.0 * 26 + 28.0 * 28 + 30.0 * 30) / 3), 1e-12);
  EXPECT_LT(rel(f->compute_scalar(), (26.0 * 26 + 28.0 * 28 + 30.0 * 30) / 3), 1e-12);
  EXPECT_EQ(f->compute_vector(2), 28.0);
  EXPECT_EQ(read_text(tmp / "a.txt"),
            "# Time-averaged data for fix a\n# TimeStep v_s v_t\n10 66.6667 8\n20 326.667 18\n30 786.667 28\n");
  // A second run continues the schedule without repeating step 30.
  d("run 10");
  EXPECT_EQ(lines_of(read_text(tmp / "a.txt")).back(), "40 1446.67 38");
}

TEST(FixAveTime, RunningWindowOffAndStart) {
  Deck d;
  d(kBox);
  d("fix one all ave/time 5 1 5 v_s");
  d("fix run all ave/time 5 1 5 v_s ave running");
  d("fix win all ave/time 5 1 5 v_s ave window 2");
  d("fix st all ave/time 5 1 5 v_s ave running start 10");
  d("fix off all ave/time 2 3 10 v_s v_t ave running off 2");
  d("run 20");
  EXPECT_EQ(d->find_fix("one")->compute_scalar(), 400.0);
  EXPECT_LT(rel(d->find_fix("run")->compute_scalar(), (0 + 25 + 100 + 225 + 400) / 5.0), 1e-12);  // outputs at 0..20
  EXPECT_LT(rel(d->find_fix("win")->compute_scalar(), (225 + 400) / 2.0), 1e-12);
  EXPECT_LT(rel(d->find_fix("st")->compute_scalar(), (100 + 225 + 400) / 3.0), 1e-12);
  const double s10 = (36 + 64 + 100) / 3.0, s20 = (256 + 324 + 400) / 3.0;
  EXPECT_LT(rel(d->find_fix("off")->compute_vector(1), (s10 + s20) / 2), 1e-12);
  EXPECT_EQ(d->find_fix("off")->compute_vector(2), 20.0);  // not averaged: the last sample
}

TEST(FixAveTime, VectorModeRowsAndFile) {
  TempDir tmp;
  Deck d;
  d(kBox)("compute sv all test/stepvec");
  d("fix v all ave/time 1 4 10 c_sv c_sv ave running mode vector file " + (tmp / "v.txt"));
  d("run 20");
  // Samples at 7..10 and 17..20: means 8.5 and 18.5, running mean 13.5, times the row number.
  for (int r = 1; r <= 3; ++r) EXPECT_LT(rel(d->find_fix("v")->compute_vector(r), 13.5 * r), 1e-12);
  EXPECT_EQ(read_text(tmp / "v.txt"),
            "# Time-averaged data for fix v\n# TimeStep Number-of-rows\n# Row c_sv c_sv\n"
            "10 3\n1 8.5 8.5\n2 17 17\n3 25.5 25.5\n20 3\n1 13.5 13.5\n2 27 27\n3 40.5 40.5\n");
}

TEST(FixAveTime, ErrorsNameTheWord) {
  Deck d;
  d(kBox)("compute sv all test/stepvec");
  EXPECT_NE(error_of(d, "fix a all ave/time 3 1 10 v_s")
                .find("'10' in 'fix a all ave/time 3 1 10 v_s': expected Nfreq a multiple of Nevery"),
            std::string::npos);
  EXPECT_NE(error_of(d, "fix a all ave/time 2 6 10 v_s").find("expected Nrepeat with (Nrepeat-1)*Nevery < Nfreq"),
            std::string::npos);
  EXPECT_NE(error_of(d, "fix a all ave/time 1 1 10 c_nope").find("'c_nope'"), std::string::npos);
  EXPECT_NE(error_of(d, "fix a all ave/time 1 1 10 c_sv").find("expected a global scalar"), std::string::npos);
  EXPECT_NE(error_of(d, "fix a all ave/time 1 1 10 c_sv[4]").find("1..3"), std::string::npos);
  EXPECT_NE(error_of(d, "fix a all ave/time 1 1 10 v_s mode vector").find("variables cannot be used with mode vector"),
            std::string::npos);
  EXPECT_NE(error_of(d, "fix a all ave/time 1 1 10 v_s overwrite").find("'overwrite' needs 'ave running'"),
            std::string::npos);
  EXPECT_NE(error_of(d, "fix a all ave/time 1 1 10 v_s bogus").find("'bogus'"), std::string::npos);
}

// x of 9 atoms against hand counts, for the three ways of treating values outside [lo, hi].
TEST(FixAveHisto, PerAtomCountsMatchHandCounts) {
  TempDir tmp;
  Deck d;
  std::string box = kBox;
  box.replace(box.find("-1 1 -1 1 -1 1"), 14, "-2 2 -2 2 -2 2");
  d(box);
  for (double x : {0.05, 0.15, 0.25, 0.3, 0.35, 0.95, 1.0, -0.5, 1.5})
    d("create_atoms 1 single " + std::to_string(x) + " 0 0 units box");
  d("group some id 1 2 3");
  d("variable twice atom 2*x");
  d("fix ig all ave/histo 1 1 10 0 1 4 x mode vector file " + (tmp / "h.txt"));
  d("fix en all ave/histo 1 1 10 0 1 4 x mode vector beyond end");
  d("fix ex all ave/histo 1 1 10 0 1 4 x mode vector beyond extra");
  d("fix gr some ave/histo 1 1 10 0 1 4 x mode vector");
  d("fix va all ave/histo 1 1 10 0 2 4 v_twice mode vector");
  d("fix ru all ave/histo 1 1 10 0 1 4 x mode vector ave running");
  d("run 20");
  auto stats = [&](const char* id) {
    auto* f = d->find_fix(id);
    return std::vector<double>{f->compute_vector(1), f->compute_vector(2), f->compute_vector(3), f->compute_vector(4)};
  };
  EXPECT_EQ(stats("ig"), (std::vector<double>{7, 2, -0.5, 1.5}));
  EXPECT_EQ(stats("en"), (std::vector<double>{9, 0, -0.5, 1.5}));
  EXPECT_EQ(stats("ex"), (std::vector<double>{9, 0, -0.5, 1.5}));
  EXPECT_EQ(stats("gr"), (std::vector<double>{3, 0, 0.05, 0.25}));
  EXPECT_EQ(stats("va"), (std::vector<double>{7, 2, -1.0, 3.0}));
  EXPECT_EQ(stats("ru"), (std::vector<double>{21, 6, -0.5, 1.5}));  // outputs at 0, 10, 20 summed
  // Bins [0,.25) [.25,.5) [.5,.75) [.75,1]: 0.25 goes up, 1.0 = hi to the last bin.
  const auto l = lines_of(read_text(tmp / "h.txt"));
  ASSERT_EQ(l.size(), 3u + 3 * 5);
  EXPECT_EQ(l[0], "# Histogrammed data for fix ig");
  EXPECT_EQ(l[1], "# TimeStep Number-of-bins Total-counts Missing-counts Min-value Max-value");
  EXPECT_EQ(l[2], "# Bin Coord Count Count/Total");
  EXPECT_EQ(l[13], "20 4 7 2 -0.5 1.5");
  EXPECT_EQ(l[14], "1 0.125 2 0.285714");
  EXPECT_EQ(l[15], "2 0.375 3 0.428571");
  EXPECT_EQ(l[16], "3 0.625 0 0");
  EXPECT_EQ(l[17], "4 0.875 2 0.285714");
}

// A global scalar histogrammed over time: steps 1..10 in 5 bins of width 2.
TEST(FixAveHisto, GlobalScalarOverTime) {
  TempDir tmp;
  Deck d;
  d(kBox)("fix h all ave/histo 1 10 10 0 10 5 v_t file " + (tmp / "g.txt"))("run 10");
  const auto l = lines_of(read_text(tmp / "g.txt"));
  ASSERT_EQ(l.size(), 9u);
  EXPECT_EQ(l[3], "10 5 10 0 1 10");
  const char* want[] = {"1 1 1 0.1", "2 3 2 0.2", "3 5 2 0.2", "4 7 2 0.2", "5 9 3 0.3"};
  for (int b = 0; b < 5; ++b) EXPECT_EQ(l[4 + b], want[b]);
  Deck e;
  e(kBox);
  EXPECT_NE(error_of(e, "fix h all ave/histo 1 1 10 0 1 4 x")
                .find("expected a global value, or 'mode vector' for per-atom values"),
            std::string::npos);
  EXPECT_NE(error_of(e, "fix h all ave/histo 1 1 10 1 0 4 x").find("expected hi > lo"), std::string::npos);
  EXPECT_NE(
      error_of(e, "fix h all ave/histo 1 1 10 0 1 4 x v_t mode vector").find("all global, all per-atom or all local"),
      std::string::npos);
}

// The same deck in LIGGGHTS 3.8.0 wrote these files (4 grains, two touching; global
// vectors, window averages, local contact forces, per-atom velocities with extra bins).
TEST(FixAve, FilesMatchLiggghts) {
  TempDir tmp;
  Deck d;
  d(R"(units si
atom_style granular
atom_modify map array
boundary f f f
newton off
communicate single vel yes
region reg block 0 0.1 0 0.1 0 0.1 units box
create_box 1 reg
neighbor 0.002 bin
neigh_modify delay 0
fix m1 all property/global youngsModulus peratomtype 5e6
fix m2 all property/global poissonsRatio peratomtype 0.45
fix m3 all property/global coefficientRestitution peratomtypepair 1 0.3
fix m4 all property/global coefficientFriction peratomtypepair 1 0.5
pair_style gran model hertz tangential history
pair_coeff * *
timestep 1e-5
create_atoms 1 single 0.05 0.05 0.05 units box
create_atoms 1 single 0.05 0.05 0.0539 units box
create_atoms 1 single 0.0539 0.05 0.05 units box
create_atoms 1 single 0.02 0.02 0.02 units box
set atom * diameter 0.004 density 2500
velocity all set 0.01 0.02 -0.03
fix g all gravity 9.81 vector 0 0 -1
fix i all nve/sphere
compute red all reduce sum vx vy vz
compute pl all pair/gran/local id force)");
  const std::string dir = tmp.dir.string() + "/";
  d("fix at all ave/time 10 2 50 c_red mode vector file " + dir + "at.txt");
  d("fix at2 all ave/time 10 2 50 c_red c_red ave running mode vector file " + dir + "at2.txt title2 \"# custom two\"");
  d("fix at4 all ave/time 5 1 25 c_red[1] c_red[3] ave window 3 file " + dir + "at4.txt");
  d("fix ah2 all ave/histo 10 1 50 -1 1 4 c_pl[4] c_pl[6] mode vector file " + dir + "ah2.txt beyond end ave window 2");
  d("fix ah3 all ave/histo 5 2 50 -0.05 0.05 5 vx vy vz fz mode vector file " + dir +
    "ah3.txt beyond extra ave running");
  d("run 200");
  const std::pair<const char*, const char*> ref[] = {
      {"at.txt", R"(# Time-averaged data for fix at
# TimeStep Number-of-rows
# Row c_red
50 3
1 0.04
2 0.08
3 -0.137658
100 3
1 0.04
2 0.08
3 -0.157278
150 3
1 0.04
2 0.08
3 -0.176898
200 3
1 0.04
2 0.08
3 -0.196518
)"},
      {"at2.txt", R"(# Time-averaged data for fix at2
# custom two
# Row c_red c_red
50 3
1 0.04 0.04
2 0.08 0.08
3 -0.137658 -0.137658
100 3
1 0.04 0.04
2 0.08 0.08
3 -0.147468 -0.147468
150 3
1 0.04 0.04
2 0.08 0.08
3 -0.157278 -0.157278
200 3
1 0.04 0.04
2 0.08 0.08
3 -0.167088 -0.167088
)"},
      {"at4.txt", R"(# Time-averaged data for fix at4
# TimeStep c_red[1] c_red[3]
0 0.04 -0.12
25 0.04 -0.124905
50 0.04 -0.12981
75 0.04 -0.13962
100 0.04 -0.14943
125 0.04 -0.15924
150 0.04 -0.16905
175 0.04 -0.17886
200 0.04 -0.18867
)"},
      {"ah2.txt", R"(# Histogrammed data for fix ah2
# TimeStep Number-of-bins Total-counts Missing-counts Min-value Max-value
# Bin Coord Count Count/Total
0 4 4 0 -0.132175 0
1 -0.75 0 0
2 -0.25 2 0.5
3 0.25 2 0.5
4 0.75 0 0
50 4 4 0 -0.132175 0
1 -0.75 0 0
2 -0.25 2 0.5
3 0.25 2 0.5
4 0.75 0 0
100 4 0 0 1e+20 -1e+20
1 -0.75 0 0
2 -0.25 0 0
3 0.25 0 0
4 0.75 0 0
150 4 0 0 1e+20 -1e+20
1 -0.75 0 0
2 -0.25 0 0
3 0.25 0 0
4 0.75 0 0
200 4 0 0 1e+20 -1e+20
1 -0.75 0 0
2 -0.25 0 0
3 0.25 0 0
4 0.75 0 0
)"},
      {"ah3.txt", R"(# Histogrammed data for fix ah3
# TimeStep Number-of-bins Total-counts Missing-counts Min-value Max-value
# Bin Coord Count Count/Total
50 7 32 0 -0.130538 0.139526
1 -0.05 6 0.1875
2 -0.04 2 0.0625
3 -0.02 2 0.0625
4 0 8 0.25
5 0.02 10 0.3125
6 0.04 0 0
7 0.05 4 0.125
100 7 64 0 -0.135443 0.139526
1 -0.05 12 0.1875
2 -0.04 4 0.0625
3 -0.02 4 0.0625
4 0 16 0.25
5 0.02 20 0.3125
6 0.04 0 0
7 0.05 8 0.125
150 7 96 0 -0.140348 0.139526
1 -0.05 18 0.1875
2 -0.04 6 0.0625
3 -0.02 6 0.0625
4 0 24 0.25
5 0.02 30 0.3125
6 0.04 0 0
7 0.05 12 0.125
200 7 128 0 -0.145253 0.139526
1 -0.05 24 0.1875
2 -0.04 8 0.0625
3 -0.02 8 0.0625
4 0 32 0.25
5 0.02 40 0.3125
6 0.04 0 0
7 0.05 16 0.125
)"},
  };
  for (auto& [name, text] : ref) EXPECT_EQ(read_text(dir + name), text) << name;
}

// HDF5 datasets hold the same numbers as f_ID (bit for bit) and open normally once the run is over.
TEST(FixAve, Hdf5FilesReadBack) {
  TempDir tmp;
  {
    Deck d;
    d(kBox);
    for (double x : {0.05, 0.3, 0.35, 0.95}) d("create_atoms 1 single " + std::to_string(x) + " 0 0 units box");
    d("fix a all ave/time 2 3 10 v_s v_t hdf5 " + (tmp / "a.h5"));
    d("fix h all ave/histo 1 1 10 0 1 4 x mode vector hdf5 " + (tmp / "h.h5"));
    d("run 30");
  }  // fixes closed: the files are complete
  const hid_t f = H5Fopen((tmp / "a.h5").c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  ASSERT_GE(f, 0);
  auto read = [](hid_t file, const char* name, hid_t type, std::vector<hsize_t>& dims, void* out) {
    const hid_t ds = H5Dopen2(file, name, H5P_DEFAULT);
    EXPECT_GE(ds, 0) << name;
    const hid_t sp = H5Dget_space(ds);
    dims.assign(H5Sget_simple_extent_ndims(sp), 0);
    H5Sget_simple_extent_dims(sp, dims.data(), nullptr);
    if (out) {
      EXPECT_GE(H5Dread(ds, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, out), 0);
    }
    H5Sclose(sp);
    H5Dclose(ds);
  };
  std::vector<hsize_t> dims;
  std::int64_t steps[3];
  double values[6];
  read(f, "step", H5T_NATIVE_INT64, dims, steps);
  ASSERT_EQ(dims, std::vector<hsize_t>{3});
  read(f, "values", H5T_NATIVE_DOUBLE, dims, values);
  ASSERT_EQ(dims, (std::vector<hsize_t>{3, 2}));
  EXPECT_EQ(steps[0], 10);
  EXPECT_EQ(steps[2], 30);
  EXPECT_EQ(values[0], (36.0 + 64 + 100) / 3);
  EXPECT_EQ(values[4], (26.0 * 26 + 28.0 * 28 + 30.0 * 30) / 3);
  EXPECT_EQ(values[5], 28.0);
  EXPECT_TRUE(H5Aexists(f, "columns") > 0);
  H5Fclose(f);

  const hid_t g = H5Fopen((tmp / "h.h5").c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  ASSERT_GE(g, 0);
  std::int64_t hsteps[4];
  double counts[16], stats[16], coord[4];
  read(g, "step", H5T_NATIVE_INT64, dims, hsteps);
  ASSERT_EQ(dims, std::vector<hsize_t>{4});  // 0, 10, 20, 30
  read(g, "counts", H5T_NATIVE_DOUBLE, dims, counts);
  ASSERT_EQ(dims, (std::vector<hsize_t>{4, 4}));
  read(g, "stats", H5T_NATIVE_DOUBLE, dims, stats);
  read(g, "coord", H5T_NATIVE_DOUBLE, dims, coord);
  EXPECT_EQ(std::vector<double>(counts + 12, counts + 16), (std::vector<double>{1, 2, 0, 1}));
  EXPECT_EQ(std::vector<double>(stats + 12, stats + 16), (std::vector<double>{4, 0, 0.05, 0.95}));
  EXPECT_EQ(coord[1], 0.375);
  H5Fclose(g);
}

namespace {

// The deck killed below: 300 grains poured with walls, ave/time and ave/histo to text and
// HDF5, one growing dump file and one file per snapshot.
const char* kKillDeck = R"(units si
atom_style granular
atom_modify map array
boundary f f f
newton off
region box block 0 0.02 0 0.02 0 0.04 units box
create_box 1 box
neighbor 0.0004 bin
neigh_modify delay 0
timestep 5e-6
fix m1 all property/global youngsModulus peratomtype 1e7
fix m2 all property/global poissonsRatio peratomtype 0.3
fix m3 all property/global coefficientRestitution peratomtypepair 1 0.5
fix m4 all property/global coefficientFriction peratomtypepair 1 0.5
pair_style gran model hertz tangential history
pair_coeff * *
fix floor all wall/gran model hertz tangential history primitive type 1 zplane 0.0
fix xw all wall/gran model hertz tangential history primitive type 1 xplane 0.0
fix xe all wall/gran model hertz tangential history primitive type 1 xplane 0.02
fix ys all wall/gran model hertz tangential history primitive type 1 yplane 0.0
fix yn all wall/gran model hertz tangential history primitive type 1 yplane 0.02
fix pts all particletemplate/sphere 15485863 atom_type 1 density constant 2500 radius constant 0.0008
fix pdd all particledistribution/discrete 32452843 1 pts 1.0
region ins block 0 0.02 0 0.02 0 0.03 units box
fix ins all insert/pack seed 32452867 distributiontemplate pdd insert_every once overlapcheck yes all_in yes &
    vel uniform 0 0 -0.3 0.3 0.3 0.3 particles_in_region 300 region ins
fix grav all gravity 9.81 vector 0 0 -1
fix integr all nve/sphere
compute k all ke
fix at all ave/time 10 1 10 c_k f_floor[3] file ave.txt hdf5 ave.h5
fix ah all ave/histo 10 2 20 -0.5 0.5 10 vz mode vector file histo.txt hdf5 histo.h5
dump d1 all custom 50 dump.txt id type x y z vx vy vz
dump d2 all custom 500 snap.*.txt id x y z
thermo 100
run 100000000
)";

// A kill -9 can stop even a single write() at a page boundary (the kernel checks for
// fatal signals between pages), so the record being written when the kill came may be
// cut. Everything before it must be complete: drop the cut tail before checking.
std::string complete_lines(const std::string& text) { return text.substr(0, text.rfind('\n') + 1); }

// Snapshots of a dump custom file, each complete; returns how many. With
// last_may_be_cut, a growing file's final snapshot may be short (see above).
int parse_dump(const std::string& raw, const std::string& name, bool last_may_be_cut = false) {
  const std::string text = last_may_be_cut ? complete_lines(raw) : raw;
  const auto l = lines_of(text);
  EXPECT_TRUE(text.empty() || text.back() == '\n') << name << " ends inside a line";
  std::size_t i = 0;
  int snaps = 0;
  std::vector<double> v;
  while (i < l.size()) {
    EXPECT_EQ(l[i], "ITEM: TIMESTEP") << name << " line " << i;
    EXPECT_EQ(l.at(i + 2), "ITEM: NUMBER OF ATOMS") << name;
    const std::size_t n = std::stoul(l.at(i + 3));
    EXPECT_EQ(l.at(i + 4).rfind("ITEM: BOX BOUNDS", 0), 0u) << name;
    const std::string head = l.at(i + 8);
    EXPECT_EQ(head.rfind("ITEM: ATOMS", 0), 0u) << name;
    std::vector<double> cols;
    numbers(head.substr(11), cols);
    const std::size_t ncols = std::count(head.begin(), head.end(), ' ') - 2;  // LIGGGHTS' trailing space
    if (last_may_be_cut && i + 9 + n > l.size()) break;  // the snapshot in flight at the kill
    EXPECT_LE(i + 9 + n, l.size()) << name << ": snapshot cut short";
    for (std::size_t k = 0; k < n && i + 9 + k < l.size(); ++k) {
      EXPECT_TRUE(numbers(l[i + 9 + k], v)) << name << ": " << l[i + 9 + k];
      EXPECT_EQ(v.size(), ncols) << name << ": " << l[i + 9 + k];
    }
    i += 9 + n;
    ++snaps;
  }
  return snaps;
}

}  // namespace

// kill -9 at several moments: every line of every text file written before the kill
// is complete (only the record in flight may be cut), every finished dump snapshot
// whole, and the HDF5 files open and read, holding the rows of the text files.
TEST(FixAve, KilledRunLeavesReadableFiles) {
  for (int delay_ms : {100, 350, 600}) {
    TempDir tmp;
    std::ofstream(tmp / "kill.in") << kKillDeck;
    const pid_t pid = ::fork();
    ASSERT_GE(pid, 0);
    if (pid == 0) {
      if (::chdir(tmp.dir.c_str()) != 0) ::_exit(127);
      ::execl(SABLE_BINARY, SABLE_BINARY, "-in", "kill.in", "-log", "log.txt", "-screen", "none", (char*)nullptr);
      ::_exit(127);
    }
    // Kill a while after the first outputs appear (a loaded machine may start slowly).
    for (int t = 0; t < 2000 && read_text(tmp / "ave.txt").size() < 200; ++t)
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    std::this_thread::sleep_for(std::chrono::milliseconds(delay_ms));
    ::kill(pid, SIGKILL);
    int status = 0;
    ::waitpid(pid, &status, 0);
    ASSERT_TRUE(WIFSIGNALED(status)) << "sable ended by itself before the kill (status " << status << ")";

    // ave/time text: 2 header lines, then "step c_k f_floor[3]" lines.
    const std::string at = complete_lines(read_text(tmp / "ave.txt"));
    ASSERT_FALSE(at.empty());
    const auto al = lines_of(at);
    ASSERT_GE(al.size(), 3u) << "no output before the kill at " << delay_ms << " ms";
    EXPECT_EQ(al[1], "# TimeStep c_k f_floor[3]");
    std::vector<double> v;
    for (std::size_t k = 2; k < al.size(); ++k) {
      EXPECT_TRUE(numbers(al[k], v)) << al[k];
      EXPECT_EQ(v.size(), 3u) << al[k];
    }
    // ave/histo text: 3 header lines, then blocks of 1 + 10 lines.
    const std::string ht = complete_lines(read_text(tmp / "histo.txt"));
    auto hl = lines_of(ht);
    ASSERT_GE(hl.size(), 3u);
    hl.resize(hl.size() - (hl.size() - 3) % 11);  // a block in flight at the kill may be cut
    for (std::size_t k = 3; k < hl.size(); ++k) {
      EXPECT_TRUE(numbers(hl[k], v)) << hl[k];
      EXPECT_EQ(v.size(), (k - 3) % 11 == 0 ? 6u : 4u) << hl[k];
    }
    // Dumps: the growing file and each finished per-snapshot file.
    EXPECT_GT(parse_dump(read_text(tmp / "dump.txt"), "dump.txt", true), 0);
    for (auto& e : fs::directory_iterator(tmp.dir)) {
      const std::string f = e.path().filename().string();
      if (f.rfind("snap.", 0) == 0 && f.find(".tmp") == std::string::npos) {
        EXPECT_EQ(parse_dump(read_text(e.path()), f), 1);
      }
    }
    const std::string log = read_text(tmp / "log.txt");
    EXPECT_TRUE(log.empty() || log.back() == '\n');

    // HDF5: a killed SWMR writer's file opens for SWMR reading; `step` counts the complete records.
    const hid_t f = H5Fopen((tmp / "ave.h5").c_str(), H5F_ACC_RDONLY | H5F_ACC_SWMR_READ, H5P_DEFAULT);
    ASSERT_GE(f, 0) << "ave.h5 does not open after kill at " << delay_ms << " ms";
    const hid_t ds = H5Dopen2(f, "step", H5P_DEFAULT), dv = H5Dopen2(f, "values", H5P_DEFAULT);
    ASSERT_GE(ds, 0);
    ASSERT_GE(dv, 0);
    hsize_t n = 0, vd[2] = {0, 0};
    const hid_t ss = H5Dget_space(ds), sv = H5Dget_space(dv);
    H5Sget_simple_extent_dims(ss, &n, nullptr);
    H5Sget_simple_extent_dims(sv, vd, nullptr);
    EXPECT_GE(n, 1u);
    EXPECT_GE(vd[0], n);
    EXPECT_EQ(vd[1], 2u);
    std::vector<std::int64_t> steps(n);
    std::vector<double> vals(vd[0] * 2);
    EXPECT_GE(H5Dread(ds, H5T_NATIVE_INT64, H5S_ALL, H5S_ALL, H5P_DEFAULT, steps.data()), 0);
    EXPECT_GE(H5Dread(dv, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, vals.data()), 0);
    // Each record equals its text line (written first), printed the LIGGGHTS way.
    ASSERT_LE(n, al.size() - 2);
    for (hsize_t r = 0; r < n; ++r) {
      char buf[128];
      std::snprintf(buf, sizeof buf, "%ld %g %g", static_cast<long>(steps[r]), vals[2 * r], vals[2 * r + 1]);
      EXPECT_EQ(al[2 + r], buf);
    }
    H5Sclose(ss);
    H5Sclose(sv);
    H5Dclose(ds);
    H5Dclose(dv);
    H5Fclose(f);
    const hid_t g = H5Fopen((tmp / "histo.h5").c_str(), H5F_ACC_RDONLY | H5F_ACC_SWMR_READ, H5P_DEFAULT);
    ASSERT_GE(g, 0);
    const hid_t dc = H5Dopen2(g, "counts", H5P_DEFAULT);
    hsize_t cd[2] = {0, 0};
    const hid_t sc = H5Dget_space(dc);
    H5Sget_simple_extent_dims(sc, cd, nullptr);
    EXPECT_EQ(cd[1], 10u);
    std::vector<double> counts(cd[0] * cd[1]);
    EXPECT_GE(H5Dread(dc, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, counts.data()), 0);
    H5Sclose(sc);
    H5Dclose(dc);
    H5Fclose(g);
  }
}

}  // namespace test_fix_ave
