// dump custom: the LIGGGHTS text format byte for byte (expected texts below were
// written by LIGGGHTS 3.8 for the same three grains), sorting, one file per
// snapshot, appending, and a run killed mid-way leaving every earlier snapshot complete.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <thread>

#include "core/engine/error.h"
#include "core/input/style_registry.h"
#include "tests/unit/deck_runner.h"

// A namespace per file: the unit tests compile in unity batches (tests/CMakeLists.txt).
namespace test_dump_custom {

using sable::test::Deck;
namespace fs = std::filesystem;

namespace {

// Per-atom test compute: column 1 = 10 * id, column 2 = radius (one value per atom with an extra word).
class ComputeDumpTestPeratom : public sable::Compute {
 public:
  ComputeDumpTestPeratom(sable::Simulation& s, const sable::Args& a) : Compute(s, a) {
    peratom_flag = true;
    peratom_cols = a.size() > 4 ? 0 : 2;
  }
  void compute_peratom() override {
    const sable::Atoms& at = sim.atoms;
    const int nc = std::max(1, peratom_cols);
    peratom.assign(at.n * nc, 0.0);
    for (std::size_t i = 0; i < at.n; ++i) {
      peratom[i * nc] = 10.0 * at.id[i];
      if (nc == 2) peratom[i * nc + 1] = at.radius[i];
    }
  }
};

// A fresh directory per test (parallel ctest runs never share files), removed
// when the test passes and kept for a look when it fails.
struct TestDir {
  std::string path;
  TestDir() {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    path = (fs::temp_directory_path() / ("sable_" + std::string(info->test_suite_name()) + "_" + info->name() + "_" +
                                         std::to_string(getpid())))
               .string();
    fs::remove_all(path);
    fs::create_directories(path);
  }
  ~TestDir() {
    if (!::testing::Test::HasFailure()) fs::remove_all(path);
  }
};

std::string slurp(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  std::stringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

// The grains of the LIGGGHTS fixture deck; values set directly (as `set atom ...` would).
void three_grains(Deck& d) {
  d(R"(units si
atom_style granular
atom_modify map array sort 0 0
boundary p f f
region box block 0 1 0 1 0 1 units box
create_box 1 box
create_atoms 1 single 0.5 0.5 0.9 units box
create_atoms 1 single 0.2 0.3 0.4 units box
create_atoms 1 single 0.7 0.1 0.2 units box)");
  sable::Atoms& a = d->atoms;
  const double v[3][3] = {{1.5, -2, 0.25}, {0.1, 0, 0}, {0, 0, -0.5}};
  const double w[3][3] = {{0, 0, 3}, {1, 2, 0}, {0, 0, 0}};
  const double r[3] = {0.05, 0.1, 0.025}, rho[3] = {2500, 1000, 3000};
  for (int i = 0; i < 3; ++i) {
    for (int k = 0; k < 3; ++k) {
      a.v[3 * i + k] = v[i][k];
      a.omega[3 * i + k] = w[i][k];
    }
    a.set_radius_density(i, r[i], rho[i]);
  }
}

struct Snapshot {
  long step = -1;
  std::vector<std::string> cols;
  std::vector<std::vector<double>> rows;
};

// Parses every snapshot of a dump file; false (with why) at the first one that is
// malformed or incomplete.
bool parse_dump(const std::string& text, std::vector<Snapshot>& out, std::string& why) {
  if (!text.empty() && text.back() != '\n') return why = "file ends inside a line", false;
  std::istringstream in(text);
  std::string line;
  auto next = [&](const std::string& expect_prefix) {
    if (!std::getline(in, line)) return why = "missing '" + expect_prefix + "'", false;
    if (line.compare(0, expect_prefix.size(), expect_prefix) != 0)
      return why = "expected '" + expect_prefix + "', got '" + line + "'", false;
    return true;
  };
  auto numbers = [&](std::size_t n, std::vector<double>& vals) {
    if (!std::getline(in, line)) return why = "missing data line", false;
    std::istringstream ls(line);
    vals.clear();
    double x;
    while (ls >> x) vals.push_back(x);
    if (vals.size() != n || !(ls.eof())) return why = "bad data line '" + line + "'", false;
    return true;
  };
  std::vector<double> vals;
  while (in.peek() != EOF) {
    Snapshot s;
    if (!next("ITEM: TIMESTEP") || !numbers(1, vals)) return false;
    s.step = static_cast<long>(vals[0]);
    if (!next("ITEM: NUMBER OF ATOMS") || !numbers(1, vals)) return false;
    const auto n = static_cast<std::size_t>(vals[0]);
    if (!next("ITEM: BOX BOUNDS ")) return false;
    for (int k = 0; k < 3; ++k)
      if (!numbers(2, vals)) return false;
    if (!next("ITEM: ATOMS ")) return false;
    std::istringstream cs(line.substr(12));
    for (std::string c; cs >> c;) s.cols.push_back(c);
    for (std::size_t r = 0; r < n; ++r) {
      if (!numbers(s.cols.size(), vals)) return false;
      s.rows.push_back(vals);
    }
    out.push_back(std::move(s));
  }
  return true;
}

}  // namespace

SABLE_COMPUTE("test/dump_peratom", ComputeDumpTestPeratom);

TEST(DumpCustom, WriteDumpMatchesLiggghtsByteForByte) {
  const TestDir tmp;
  const std::string& dir = tmp.path;
  Deck d;
  three_grains(d);
  // Store the atoms out of id order, so `sort id` has work to do.
  d->atoms.permute({2, 0, 1});
  d("write_dump all custom " + dir + "/wd.txt id type mass x y z vx fx omegaz radius diameter density modify sort id");
  // LIGGGHTS 3.8, same deck with `set atom ...`: byte for byte (trailing spaces included).
  EXPECT_EQ(slurp(dir + "/wd.txt"),
            "ITEM: TIMESTEP\n0\nITEM: NUMBER OF ATOMS\n3\nITEM: BOX BOUNDS pp ff ff\n0 1\n0 1\n0 1\n"
            "ITEM: ATOMS id type mass x y z vx fx omegaz radius diameter density \n"
            "1 1 1.309 0.5 0.5 0.9 1.5 0 3 0.05 0.1 2500 \n"
            "2 1 4.18879 0.2 0.3 0.4 0.1 0 0 0.1 0.2 1000 \n"
            "3 1 0.19635 0.7 0.1 0.2 0 0 0 0.025 0.05 3000 \n");
  // Parsed back, values agree with the state to %g's 6 significant digits (relative 5e-6).
  std::vector<Snapshot> snaps;
  std::string why;
  ASSERT_TRUE(parse_dump(slurp(dir + "/wd.txt"), snaps, why)) << why;
  ASSERT_EQ(snaps.size(), 1u);
  const sable::Atoms& a = d->atoms;
  for (const auto& row : snaps[0].rows) {
    const std::size_t i = a.index_of(static_cast<long>(row[0]));
    ASSERT_NE(i, sable::Atoms::npos);
    EXPECT_NEAR(row[2], a.rmass[i], 5e-6 * a.rmass[i]);
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(row[3 + k], a.x[3 * i + k], 5e-6 * std::abs(a.x[3 * i + k]));
    EXPECT_NEAR(row[6], a.v[3 * i], 5e-6 * std::abs(a.v[3 * i]));
    EXPECT_NEAR(row[11], a.density[i], 5e-6 * a.density[i]);
  }
  // Without sort, atoms come in storage order (3 1 2).
  d("write_dump all custom " + dir + "/unsorted.txt id x");
  snaps.clear();
  ASSERT_TRUE(parse_dump(slurp(dir + "/unsorted.txt"), snaps, why)) << why;
  ASSERT_EQ(snaps[0].rows.size(), 3u);
  EXPECT_EQ(snaps[0].rows[0][0], 3);
  EXPECT_EQ(snaps[0].rows[1][0], 1);
  EXPECT_EQ(snaps[0].rows[2][0], 2);
}

TEST(DumpCustom, FormatStringMatchesLiggghts) {
  const TestDir tmp;
  const std::string& dir = tmp.path;
  Deck d;
  three_grains(d);
  d("dump d all custom 1 " + dir + "/fmt.txt id type x vx\n"
    "dump_modify d format \"%d %5d %10.4f %.3e\"\n"
    "run 0");
  EXPECT_EQ(slurp(dir + "/fmt.txt"),
            "ITEM: TIMESTEP\n0\nITEM: NUMBER OF ATOMS\n3\nITEM: BOX BOUNDS pp ff ff\n0 1\n0 1\n0 1\n"
            "ITEM: ATOMS id type x vx \n"
            "1     1     0.5000 1.500e+00 \n"
            "2     1     0.2000 1.000e-01 \n"
            "3     1     0.7000 0.000e+00 \n");
  // A conversion that cannot print a number is refused at its deck line.
  try {
    d("dump_modify d format \"%d %s %g %g\"");
    FAIL() << "expected an error";
  } catch (const sable::SableError& e) {
    EXPECT_NE(std::string(e.what()).find("one printf conversion per column"), std::string::npos) << e.what();
  }
}

TEST(DumpCustom, ComputeVariableImageAndForceColumns) {
  const TestDir tmp;
  const std::string& dir = tmp.path;
  Deck d;
  three_grains(d);
  sable::Atoms& a = d->atoms;
  a.f[0] = 0.5;        // fx of atom 1
  a.torque[4] = -0.1;  // tqy of atom 2
  a.x[0] = 0.25;       // atom 1 wrapped once through periodic x: xu = 1.25
  a.image[0] = 1;
  d("compute pa all test/dump_peratom\n"
    "compute pv all test/dump_peratom vector\n"
    "variable twice atom 2*vx\n"
    "write_dump all custom " + dir + "/cols.txt id c_pa[1] c_pa[2] c_pv v_twice xu ix xs fx tqy modify sort id");
  std::vector<Snapshot> snaps;
  std::string why;
  ASSERT_TRUE(parse_dump(slurp(dir + "/cols.txt"), snaps, why)) << why;
  const auto& r = snaps[0].rows;
  ASSERT_EQ(r.size(), 3u);
  // Tolerance: %g prints 6 significant digits.
  EXPECT_EQ(r[0][1], 10);
  EXPECT_EQ(r[2][1], 30);
  EXPECT_DOUBLE_EQ(r[1][2], 0.1);
  EXPECT_EQ(r[1][3], 20);
  EXPECT_DOUBLE_EQ(r[0][4], 3.0);
  EXPECT_DOUBLE_EQ(r[0][5], 1.25);
  EXPECT_EQ(r[0][6], 1);
  EXPECT_DOUBLE_EQ(r[0][7], 0.25);
  EXPECT_DOUBLE_EQ(r[0][8], 0.5);
  EXPECT_DOUBLE_EQ(r[1][9], -0.1);
}

TEST(DumpCustom, SortByColumnThreshAndRegion) {
  const TestDir tmp;
  const std::string& dir = tmp.path;
  Deck d;
  three_grains(d);
  d("region low block 0 1 0 1 0 0.5 units box\n"
    "dump d all custom 1 " + dir + "/s.txt id vx\n"
    "dump_modify d sort -2 thresh vx > -1 region low\n"
    "run 0");
  std::vector<Snapshot> snaps;
  std::string why;
  ASSERT_TRUE(parse_dump(slurp(dir + "/s.txt"), snaps, why)) << why;
  // Atom 1 (z = 0.9) is outside the region; atoms 2, 3 sorted by vx descending.
  ASSERT_EQ(snaps[0].rows.size(), 2u);
  EXPECT_EQ(snaps[0].rows[0][0], 2);
  EXPECT_EQ(snaps[0].rows[1][0], 3);
}

TEST(DumpCustom, StarWritesOneFilePerSnapshot) {
  const TestDir tmp;
  const std::string& dir = tmp.path;
  Deck d;
  three_grains(d);
  d("fix i all nve/sphere\n"
    "dump d all custom 2 " + dir + "/snap.* id x y z\n"
    "run 5");
  std::vector<std::string> names;
  for (auto& e : fs::directory_iterator(dir)) names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  EXPECT_EQ(names, (std::vector<std::string>{"snap.0", "snap.2", "snap.4"}));  // no .tmp left behind
  for (long step : {0L, 2L, 4L}) {
    std::vector<Snapshot> snaps;
    std::string why;
    ASSERT_TRUE(parse_dump(slurp(dir + "/snap." + std::to_string(step)), snaps, why)) << why;
    ASSERT_EQ(snaps.size(), 1u);
    EXPECT_EQ(snaps[0].step, step);
    EXPECT_EQ(snaps[0].rows.size(), 3u);
  }
}

TEST(DumpCustom, SingleFileAppendsSnapshotsAcrossRuns) {
  const TestDir tmp;
  const std::string& dir = tmp.path;
  {
    std::ofstream(dir + "/old.txt") << "stale content\n";
  }
  Deck d;
  three_grains(d);
  d("fix i all nve/sphere\n"
    "timestep 0.01\n"
    "dump d all custom 1 " + dir + "/all.txt id x y z\n"
    "dump_modify d sort id\n"
    "run 3\n"
    "run 2");
  std::vector<Snapshot> snaps;
  std::string why;
  ASSERT_TRUE(parse_dump(slurp(dir + "/all.txt"), snaps, why)) << why;
  // Steps 0..5 once each: the second run does not repeat step 3.
  ASSERT_EQ(snaps.size(), 6u);
  for (long s = 0; s < 6; ++s) EXPECT_EQ(snaps[s].step, s);
  // Free flight: x = x0 + v t, printed with %g (6 significant digits).
  EXPECT_NEAR(snaps[5].rows[0][1], 0.5 + 1.5 * 0.05, 5e-6);
  // A new dump truncates its file unless told to append.
  d("undump d\ndump e all custom 1 " + dir + "/old.txt id\ndump_modify e append yes\nrun 0");
  const std::string text = slurp(dir + "/old.txt");
  EXPECT_EQ(text.rfind("stale content\nITEM: TIMESTEP\n5\n", 0), 0u) << text;
}

TEST(DumpCustom, FreeFallRunMatchesLiggghts) {
  // tests/decks/output_dumps.in run in LIGGGHTS 3.8 wrote this snapshot (27 grains
  // falling for 50 steps, user format %.10g): sable's file must be identical.
  const TestDir tmp;
  const std::string& dir = tmp.path;
  Deck d;
  d(R"(units si
atom_style granular
atom_modify map array
boundary p p f
region box block 0 0.1 0 0.1 0 0.1 units box
create_box 1 box
region inner block 0.01 0.09 0.01 0.09 0.01 0.09 units box
lattice sc 0.025
create_atoms 1 region inner
fix g all gravity 9.81 vector 0 0 -1
fix i all nve/sphere
timestep 1e-4)");
  d("dump s all custom 25 " + dir + "/snap.* id x y z\n"
    "dump_modify s format \"%d %.10g %.10g %.10g\" sort id\n"
    "run 50");
  EXPECT_EQ(slurp(dir + "/snap.50"),
            "ITEM: TIMESTEP\n"
            "50\n"
            "ITEM: NUMBER OF ATOMS\n"
            "27\n"
            "ITEM: BOX BOUNDS pp pp ff\n"
            "0 0.1\n"
            "0 0.1\n"
            "0 0.1\n"
            "ITEM: ATOMS id x y z \n"
            "1 0.025 0.025 0.024877375 \n"
            "2 0.05 0.025 0.024877375 \n"
            "3 0.075 0.025 0.024877375 \n"
            "4 0.025 0.05 0.024877375 \n"
            "5 0.05 0.05 0.024877375 \n"
            "6 0.075 0.05 0.024877375 \n"
            "7 0.025 0.075 0.024877375 \n"
            "8 0.05 0.075 0.024877375 \n"
            "9 0.075 0.075 0.024877375 \n"
            "10 0.025 0.025 0.049877375 \n"
            "11 0.05 0.025 0.049877375 \n"
            "12 0.075 0.025 0.049877375 \n"
            "13 0.025 0.05 0.049877375 \n"
            "14 0.05 0.05 0.049877375 \n"
            "15 0.075 0.05 0.049877375 \n"
            "16 0.025 0.075 0.049877375 \n"
            "17 0.05 0.075 0.049877375 \n"
            "18 0.075 0.075 0.049877375 \n"
            "19 0.025 0.025 0.074877375 \n"
            "20 0.05 0.025 0.074877375 \n"
            "21 0.075 0.025 0.074877375 \n"
            "22 0.025 0.05 0.074877375 \n"
            "23 0.05 0.05 0.074877375 \n"
            "24 0.075 0.05 0.074877375 \n"
            "25 0.025 0.075 0.074877375 \n"
            "26 0.05 0.075 0.074877375 \n"
            "27 0.075 0.075 0.074877375 \n");
}

#ifdef SABLE_BINARY
TEST(DumpCustom, KilledRunLeavesEveryWrittenSnapshotReadable) {
  const TestDir tmp;
  const std::string& dir = tmp.path;
  const std::string deck = dir + "/long.in", dump = dir + "/long.txt";
  std::ofstream(deck) << "units si\natom_style granular\nregion box block 0 1 0 1 0 1 units box\ncreate_box 1 box\n"
                         "create_atoms 1 single 0.5 0.5 0.5 units box\ncreate_atoms 1 single 0.2 0.3 0.4 units box\n"
                         "create_atoms 1 single 0.7 0.1 0.2 units box\nfix i all nve/sphere\n"
                         "dump d all custom 1 " << dump << " id type x y z vx vy vz\nrun 2000000000\n";
  const pid_t pid = fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {  // child: a fresh sable process (exec, so no state is shared with this test)
    const int null = open("/dev/null", O_WRONLY);
    dup2(null, 1);
    dup2(null, 2);
    execl(SABLE_BINARY, SABLE_BINARY, "-in", deck.c_str(), "-log", "none", static_cast<char*>(nullptr));
    _exit(127);
  }
  // Wait (by progress, not by the clock) until the file holds at least kWritten
  // snapshot headers, then kill it hard while it writes on.
  constexpr std::size_t kWritten = 20;
  std::size_t seen = 0;
  int status = 0;
  pid_t gone = 0;
  while (seen < kWritten && (gone = waitpid(pid, &status, WNOHANG)) == 0) {
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
    const std::string partial = fs::exists(dump) ? slurp(dump) : std::string();
    seen = 0;
    for (std::size_t at = partial.find("ITEM: TIMESTEP"); at != std::string::npos;
         at = partial.find("ITEM: TIMESTEP", at + 1))
      ++seen;
  }
  if (gone == 0) {
    kill(pid, SIGKILL);
    waitpid(pid, &status, 0);
  }
  ASSERT_TRUE(WIFSIGNALED(status)) << "sable exited by itself (status " << status << ") before it was killed";

  std::vector<Snapshot> snaps;
  std::string why;
  std::string text = slurp(dump);
  if (!parse_dump(text, snaps, why)) {
    // Only the snapshot in flight may be cut: a kill -9 can stop even one write() between pages.
    text = text.substr(0, text.rfind("ITEM: TIMESTEP"));
    snaps.clear();
    EXPECT_TRUE(parse_dump(text, snaps, why)) << why << " after " << snaps.size() << " snapshots";
  }
  // Every snapshot begun before the kill but the one in flight is there and whole.
  EXPECT_GE(snaps.size() + 1, seen);
  for (std::size_t s = 0; s < snaps.size(); ++s) {
    ASSERT_EQ(snaps[s].step, static_cast<long>(s));
    ASSERT_EQ(snaps[s].rows.size(), 3u);
  }
}
#endif

}  // namespace test_dump_custom
