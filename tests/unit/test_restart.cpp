// write_restart / read_restart: a run split by a restart continues bit for bit
// like the uninterrupted run (pair history, wall history and insert/pack state
// re-attach when the deck declares its styles again, the LIGGGHTS way), and
// damaged, foreign or wrong-version files stop with a message naming the file.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>

#include "core/engine/error.h"
#include "core/io/restart.h"
#include "fixes/fix_wall_gran.h"
#include "tests/unit/deck_runner.h"

// A namespace per file: the unit tests compile in unity batches (tests/CMakeLists.txt).
namespace test_restart {

using sable::test::Deck;
using sable::test::error_of;
using sable::test::TempDir;
using sable::test::entry_history;
namespace fs = std::filesystem;

namespace {

// A scratch directory per test, removed afterwards.
// Box and groups: what the restart file carries.
const char* kHead = R"(units si
atom_style granular
atom_modify map array
boundary f f f
newton off
communicate single vel yes
region box block 0 0.02 0 0.02 0 0.04 units box
create_box 1 box
group grains initialize)";

// What a LIGGGHTS deck declares again after read_restart: 300 grains poured
// onto a floor between four side walls, Hertz with tangential history everywhere.
const char* kBody = R"(neighbor 0.0004 bin
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
region ins block 0 0.02 0 0.02 0 0.008 units box
fix ins grains insert/pack seed 32452867 distributiontemplate pdd insert_every once overlapcheck yes all_in yes &
    vel uniform 0 0 -0.3 0.3 0.3 0.3 particles_in_region 300 region ins
fix grav all gravity 9.81 vector 0 0 -1
fix integr all nve/sphere)";

const char* kWalls[] = {"floor", "xw", "xe", "ys", "yn"};

template <class T>
void expect_bits(const std::vector<T>& a, const std::vector<T>& b, std::size_t n, const char* what) {
  ASSERT_GE(a.size(), n) << what;
  ASSERT_GE(b.size(), n) << what;
  EXPECT_EQ(0, std::memcmp(a.data(), b.data(), n * sizeof(T))) << what << " differs";
}

const sable::HistoryStore& wall_history(sable::Simulation& s, const char* wall) {
  auto* f = dynamic_cast<sable::FixWallGran*>(s.find_fix(wall));
  if (!f) throw std::runtime_error(std::string("no wall/gran fix ") + wall);
  return f->history();
}

void expect_same_state(sable::Simulation& a, sable::Simulation& b) {
  ASSERT_EQ(a.atoms.n, b.atoms.n);
  EXPECT_EQ(a.step, b.step);
  EXPECT_EQ(0, std::memcmp(&a.time, &b.time, sizeof(double)));
  const std::size_t n = a.atoms.n;
  expect_bits(a.atoms.id, b.atoms.id, n, "id");
  expect_bits(a.atoms.mask, b.atoms.mask, n, "mask");
  expect_bits(a.atoms.image, b.atoms.image, 3 * n, "image");
  expect_bits(a.atoms.x, b.atoms.x, 3 * n, "x");
  expect_bits(a.atoms.v, b.atoms.v, 3 * n, "v");
  expect_bits(a.atoms.omega, b.atoms.omega, 3 * n, "omega");
  expect_bits(a.atoms.f, b.atoms.f, 3 * n, "f");
  expect_bits(a.atoms.torque, b.atoms.torque, 3 * n, "torque");
  for (const char* w : kWalls) {
    const sable::HistoryStore &wa = wall_history(a, w), &wb = wall_history(b, w);
    ASSERT_EQ(wa.count(), wb.count()) << w;
    for (std::size_t r = 0; r < wa.count(); ++r) {
      ASSERT_TRUE(wa.key(r) == wb.key(r)) << w;
      expect_bits(std::vector<double>(wa.row(r), wa.row(r) + wa.size()),
                  std::vector<double>(wb.row(r), wb.row(r) + wb.size()), wa.size(), w);
    }
  }
  auto* ha = a.pair->history();
  auto* hb = b.pair->history();
  ASSERT_TRUE(ha && hb);
  std::vector<int> ta, tb;  // in contact, per list entry (rows may be numbered differently)
  for (int r : ha->row) ta.push_back(r >= 0);
  for (int r : hb->row) tb.push_back(r >= 0);
  expect_bits(ta, tb, ta.size(), "contact flags");
  const std::vector<double> va = entry_history(*ha), vb = entry_history(*hb);
  expect_bits(va, vb, va.size(), "contact history");
}

// Touching pairs with a non-zero tangential spring; grains whose wall spring is non-zero.
std::size_t active_pair_history(sable::Simulation& s) {
  auto* h = s.pair->history();
  std::size_t c = 0;
  for (std::size_t k = 0; k < h->row.size(); ++k) {
    const double* v = h->history(k);
    bool nz = false;
    for (int m = 0; v && m < h->size; ++m) nz = nz || v[m] != 0.0;
    c += nz;
  }
  return c;
}
std::size_t active_wall_history(sable::Simulation& s) {
  std::size_t c = 0;
  for (const char* w : kWalls) {
    const sable::HistoryStore& h = wall_history(s, w);
    for (std::size_t r = 0; r < h.count(); ++r) {
      bool nz = false;
      for (int m = 0; m < h.size(); ++m) nz = nz || h.row(r)[m] != 0.0;
      c += nz;
    }
  }
  return c;
}

void write_bytes(const std::string& path, const std::string& bytes) { std::ofstream(path, std::ios::binary) << bytes; }
std::string read_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

}  // namespace

// (A) run; run in one process vs (B) run; write_restart; fresh process: read_restart; declare again; run.
TEST(Restart, SplitRunContinuesBitIdentically) {
  TempDir tmp;
  const std::string file = tmp / "pour.restart";
  Deck a;
  a(kHead)(kBody)("run 1500")("run 1500");

  Deck b;
  b(kHead)(kBody)("run 1500");
  // The restart moment has grain-grain and grain-wall contacts with live tangential springs.
  EXPECT_GT(active_pair_history(*b), 5u);
  EXPECT_GT(active_wall_history(*b), 5u);
  std::printf("restart moment: %zu grain-grain and %zu grain-wall contacts with tangential history\n",
              active_pair_history(*b), active_wall_history(*b));
  b("write_restart " + file);

  Deck c;
  c("units si\natom_style granular\nread_restart " + file);
  EXPECT_EQ(c->step, 1500);
  EXPECT_EQ(c->atoms.n, 300u);
  c(kBody)("run 1500");
  expect_same_state(*a, *c);
  EXPECT_GT(active_pair_history(*c), 5u);
  EXPECT_DOUBLE_EQ(c->find_fix("ins")->compute_vector(1), 300.0);  // insert/pack counters came back

  // Read and written again before any run: the pending history and fix states pass through.
  Deck e;
  e("units si\natom_style granular\nread_restart " + file + "\nwrite_restart " + (tmp / "again.restart"));
  Deck g;
  g("units si\natom_style granular\nread_restart " + (tmp / "again.restart"))(kBody)("run 1500");
  expect_same_state(*a, *g);
}

// A folder missing on the way to the file is made (as LIGGGHTS does), and the file reads back.
TEST(Restart, MakesMissingFolders) {
  TempDir tmp;
  const std::string file = tmp / "post/restart/pour.restart";
  Deck b;
  b(kHead)(kBody)("run 10")("write_restart " + file);
  Deck c;
  c("units si\natom_style granular\nread_restart " + file);
  EXPECT_EQ(c->step, 10);
  EXPECT_EQ(c->atoms.n, b->atoms.n);
}

// The run continues bit for bit also when it is split twice and the second file
// is written by a restarted run (state that passes through two restarts).
TEST(Restart, TwoRestartsInARow) {
  TempDir tmp;
  Deck a;
  a(kHead)(kBody)("run 600")("run 600")("run 600");
  Deck b;
  b(kHead)(kBody)("run 600")("write_restart " + (tmp / "r.*"));
  Deck c;
  c("units si\natom_style granular\nread_restart " + (tmp / "r.*"))(kBody)("run 600")("write_restart " + (tmp / "r.*"));
  Deck d;
  d("units si\natom_style granular\nread_restart " + (tmp / "r.*"));
  EXPECT_EQ(d->step, 1200);  // '*' picks the largest step
  d(kBody)("run 600");
  expect_same_state(*a, *d);
}

// The file describes itself: pair model and history slot names, wall columns, fix states.
TEST(Restart, FileNamesModelSlotsColumnsAndFixStates) {
  TempDir tmp;
  Deck b;
  b(kHead)(kBody)("run 300")("write_restart " + (tmp / "r.*"));
  const std::string path = tmp / "r.300";
  ASSERT_TRUE(fs::exists(path));
  for (auto& e : fs::directory_iterator(tmp.dir)) EXPECT_EQ(e.path().filename().string(), "r.300");  // no temp left
  const std::string s = sable::restart::summary(path);
  EXPECT_NE(s.find(b->pair->describe()), std::string::npos) << s;
  for (auto& slot : b->pair->history()->slots) EXPECT_NE(s.find(" " + slot.name), std::string::npos) << s;
  EXPECT_NE(s.find("ins (insert/pack"), std::string::npos) << s;
  EXPECT_EQ(read_bytes(path).rfind("SABLE RESTART\nformat 3\n", 0), 0u);

  Deck c;
  c("units si\natom_style granular\nread_restart " + path);
  EXPECT_EQ(c->atoms.ncolumns(), 0);  // wall history is in the walls' fix states
  EXPECT_NE(s.find("floor (wall/gran"), std::string::npos) << s;
  c(kBody);
  EXPECT_GT(wall_history(*c, "floor").count(), 0u);  // the floor re-attached to its contacts
  EXPECT_EQ(c->groups.find("grains"), b->groups.find("grains"));
}

// Stored state that nobody claims, or history the new pair style cannot keep, is dropped with a warning.
TEST(Restart, UnclaimedStateIsReported) {
  TempDir tmp;
  Deck b;
  b(kHead)(kBody)("run 1500")("write_restart " + (tmp / "r"));
  Deck c;
  c("units si\natom_style granular\nread_restart " + (tmp / "r"));
  const std::string out = sable::test::printed(R"(neighbor 0.0004 bin
timestep 5e-6
fix m1 all property/global youngsModulus peratomtype 1e7
fix m2 all property/global poissonsRatio peratomtype 0.3
fix m3 all property/global coefficientRestitution peratomtypepair 1 0.5
fix m4 all property/global coefficientFriction peratomtypepair 1 0.5
pair_style gran model hertz tangential no_history
pair_coeff * *
fix ins all viscous 0.0
run 1)",
                                               c);
  EXPECT_NE(out.find("keeps none: it is dropped"), std::string::npos) << out;
  EXPECT_NE(out.find("was style insert/pack"), std::string::npos) << out;
}

TEST(Restart, BadFilesNameTheFileAndTheProblem) {
  TempDir tmp;
  Deck b;
  b(kHead)(kBody)("run 200")("write_restart " + (tmp / "good"));
  const std::string good = read_bytes(tmp / "good");
  auto read_error = [&](const std::string& name, const std::string& bytes) {
    write_bytes(tmp / name, bytes);
    Deck d;
    return error_of(d, "units si\natom_style granular\nread_restart " + (tmp / name));
  };
  // Truncated anywhere: inside the header, the sections, or just before the end section.
  for (std::size_t len : {std::size_t{5}, std::size_t{16}, std::size_t{30}, good.size() / 2, good.size() - 1}) {
    const std::string e = read_error("cut", good.substr(0, len));
    EXPECT_NE(e.find("restart file '" + (tmp / "cut") + "'"), std::string::npos) << e;
    EXPECT_NE(e.find("truncated"), std::string::npos) << len << ": " << e;
    EXPECT_NE(e.find("test:3: 'read_restart"), std::string::npos) << e;  // deck location
  }
  std::string flipped = good;
  flipped[good.size() / 2] ^= 0x20;
  EXPECT_NE(read_error("flip", flipped).find("is corrupt"), std::string::npos);
  std::string v9 = good;
  v9.replace(v9.find("format 3"), 8, "format 9");
  EXPECT_NE(read_error("v9", v9).find("has restart format 9, but this sable reads format 3"), std::string::npos);
  EXPECT_NE(read_error("text", "ITEM: TIMESTEP\n0\n").find("is not a sable restart file"), std::string::npos);
  using namespace std::string_literals;  // the header of a LIGGGHTS 3.8 restart file, embedded zeros included
  const std::string lig = "\0\0\0\0Z\0\0\0Version LIGGGHTS-PUBLIC 3.8.0, compiled 2022-01-26"s;
  EXPECT_NE(read_error("lig", lig).find("is a LIGGGHTS/LAMMPS restart file"), std::string::npos);
  {
    Deck d;
    EXPECT_NE(error_of(d, "units si\nread_restart " + (tmp / "absent")).find("cannot be opened"), std::string::npos);
  }
  {
    Deck d;
    const std::string e = error_of(d, std::string(kHead) + "\nread_restart " + (tmp / "good"));
    EXPECT_NE(e.find("the box already exists"), std::string::npos) << e;
  }
}

}  // namespace test_restart
