// Quasi-static control: fix halt, compute unbalanced/force, fix damping/cundall.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "core/engine/threads.h"
#include "tests/unit/deck_runner.h"

#ifdef _OPENMP
#include <omp.h>

// A namespace per file: the unit tests compile in unity batches (tests/CMakeLists.txt).
namespace test_quasi_static {
#endif

using sable::test::Deck;
using sable::test::error_of;
using sable::test::printed;

namespace {

// Linear springs (kn = 2000 N/m), dashpots and friction that vanish at rest.
const char* kStiff = R"(units si
atom_style granular
boundary f f f
region box block -0.01 0.01 -0.01 0.01 -0.01 0.01 units box
create_box 1 box
neighbor 0.0004 bin
fix k1 all property/global kn peratomtypepair 1 2000
fix k2 all property/global kt peratomtypepair 1 1000
fix k3 all property/global gamman_abs peratomtypepair 1 0.02
fix k4 all property/global gammat_abs peratomtypepair 1 0.01
fix k5 all property/global coefficientFriction peratomtypepair 1 0.5
pair_style gran model hooke/stiffness tangential history absolute_damping on
pair_coeff * *
timestep 1e-6
)";

double norm(const double* v) { return std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]); }

// The numbers a deck printed after "tag": each line "tag a b c ..." as a row.
std::vector<std::vector<double>> rows_after(const std::string& out, const std::string& tag) {
  std::vector<std::vector<double>> rows;
  std::istringstream in(out);
  for (std::string line; std::getline(in, line);) {
    if (line.rfind(tag + " ", 0) != 0) continue;
    std::istringstream w(line.substr(tag.size()));
    std::vector<double> r;
    for (double x; w >> x;) r.push_back(x);
    rows.push_back(r);
  }
  return rows;
}

}  // namespace

// ---- compute unbalanced/force

// Three grains at rest under gravity: grain 1 (r 1 mm) presses into the floor,
// grain 2 (r 1.5 mm) leans on it at 30 degrees, grain 3 (frozen) touches grain 2
// from the side. Contact law at rest: F = kn overlap along the normal (no
// velocity: no dashpot; no tangential spring yet). By hand (YADE's
// unbalancedForce): free grains 1 and 2, net force = contacts + m g; contacts
// floor-1, 1-2, 2-3 (3 belongs to no free grain's net force but its contact
// counts). 1e-12 relative: the same few operations in another order.
// With fix damping/cundall 0.5 the force the step applies is smaller, but the
// ratio, which leaves the damping out as YADE does, is the same.
TEST(UnbalancedForce, ThreeGrainsByHand) {
  for (const bool damped : {false, true}) {
    Deck d;
    d(kStiff);
    d("create_atoms 1 single 0 0 0.00098 units box\n"
      "create_atoms 1 single 0.0012350 0 0.0031191 units box\n"
      "create_atoms 1 single 0.0036 0 0.0031191 units box\n"
      "set atom 1 diameter 0.002 density 2500\nset atom 2 diameter 0.003 density 2500\n"
      "set atom 3 diameter 0.0022 density 2500\ngroup fr id 3");
    d("fix floor all wall/gran model hooke/stiffness tangential history primitive type 1 zplane 0.0 "
      "absolute_damping on");
    d("fix g all gravity 9.81 vector 0 0 -1\nfix f fr freeze\nfix i all nve/sphere");
    if (damped) d("fix damp all damping/cundall 0.5");
    d("compute ub all unbalanced/force\nthermo_style custom step c_ub\nrun 0");
    const auto& a = d->atoms;
    const std::size_t i1 = a.index_of(1), i2 = a.index_of(2), i3 = a.index_of(3);
    const double kn = 2000, g = 9.81;
    const double* x1 = &a.x[3 * i1];
    const double* x2 = &a.x[3 * i2];
    const double* x3 = &a.x[3 * i3];
    // Contact forces on the first grain of each pair, along its unit normal.
    auto contact = [&](const double* xi, const double* xj, double ri, double rj, double f[3]) {
      const double dx[3] = {xi[0] - xj[0], xi[1] - xj[1], xi[2] - xj[2]};
      const double dist = norm(dx), overlap = ri + rj - dist;
      EXPECT_GT(overlap, 0);
      for (int k = 0; k < 3; ++k) f[k] = kn * overlap * dx[k] / dist;
    };
    const double r1 = 0.001, r2 = 0.0015, r3 = 0.0011;
    double f12[3], f23[3];
    contact(x1, x2, r1, r2, f12);
    contact(x2, x3, r2, r3, f23);
    const double fw = kn * (r1 - x1[2]);
    ASSERT_GT(fw, 0);
    ASSERT_GT(x2[2], r2);  // grain 2 clear of the floor
    const double m1 = a.rmass[i1], m2 = a.rmass[i2];
    const double net1[3] = {f12[0], f12[1], f12[2] + fw - m1 * g};
    const double net2[3] = {-f12[0] + f23[0], -f12[1] + f23[1], -f12[2] + f23[2] - m2 * g};
    const double mean_net = (norm(net1) + norm(net2)) / 2;
    const double mean_contact = (fw + norm(f12) + norm(f23)) / 3;
    const double expected = mean_net / mean_contact;
    sable::Compute* ub = d->find_compute("ub");
    EXPECT_NEAR(ub->compute_scalar(), expected, 1e-12 * expected) << (damped ? "damped" : "undamped");
    EXPECT_NEAR(ub->compute_vector(2), std::max(norm(net1), norm(net2)) / mean_contact, 1e-12 * expected);
    EXPECT_NEAR(ub->compute_vector(3), mean_net, 1e-12 * mean_net);
    EXPECT_NEAR(ub->compute_vector(4), mean_contact, 1e-12 * mean_contact);
    // The force the step applies: damped (halved at rest: u = dt/2 F/m points along F).
    const double applied = norm(&a.f[3 * i2]);
    EXPECT_NEAR(applied, (damped ? 0.5 : 1.0) * norm(net2), 1e-12 * norm(net2));
  }
}

// Grains in free fall touch nothing: +inf, which meets no '<' condition.
TEST(UnbalancedForce, NoContactIsInfinite) {
  Deck d;
  d(kStiff);
  d("create_atoms 1 single 0 0 0.005 units box\nset atom 1 diameter 0.002 density 2500\n"
    "fix g all gravity 9.81 vector 0 0 -1\nfix i all nve/sphere\ncompute ub all unbalanced/force\nrun 0");
  EXPECT_TRUE(std::isinf(d->find_compute("ub")->compute_scalar()));
}

// ---- fix damping/cundall

// YADE's law on one grain at rest-free fall: the force against the velocity at
// the force's time grows by alpha |F|, along it shrinks. A grain released at rest
// under gravity with alpha = 0.3 falls at g (1 - alpha): velocity Verlet is exact
// for a constant acceleration (1e-12 relative, round-off over 2000 steps).
TEST(DampingCundall, FreeFallAtReducedGravity) {
  Deck d;
  d(kStiff);
  d("create_atoms 1 single 0 0 0.009 units box\nset atom 1 diameter 0.002 density 2500\n"
    "fix g all gravity 9.81 vector 0 0 -1\nfix damp all damping/cundall 0.3\nfix i all nve/sphere\nrun 2000");
  const double t = 2000 * 1e-6, a = 9.81 * 0.7;
  EXPECT_NEAR(d->atoms.v[2], -a * t, 1e-12 * a * t);
  EXPECT_NEAR(d->atoms.x[2], 0.009 - 0.5 * a * t * t, 1e-12 * 0.009);
}

// Thrown upward, the same grain decelerates at g (1 + alpha) while it rises;
// the spin's torque is damped likewise (torque zero: stays zero). Exact at step 0.
TEST(DampingCundall, ForceAgainstMotionGrows) {
  Deck d;
  d(kStiff);
  d("create_atoms 1 single 0 0 0.005 units box\nset atom 1 diameter 0.002 density 2500 vz 1 omegax 3\n"
    "fix g all gravity 9.81 vector 0 0 -1\nfix damp all damping/cundall 0.3\nfix i all nve/sphere\nrun 0");
  const double mg = d->atoms.rmass[0] * 9.81;
  EXPECT_DOUBLE_EQ(d->atoms.f[2], -mg * 1.3);
  EXPECT_EQ(d->atoms.torque[0], 0.0);
}

namespace {

// ~300 grains of 1.7 to 2 mm on a loose lattice above a floor, x and y periodic,
// damping/cundall 0.7 after gravity; 2000 steps run.
const char* kBed = R"(units si
atom_style granular
boundary p p f
region box block 0 0.0105 0 0.0105 0 0.03 units box
create_box 1 box
neighbor 0.0004 bin
neigh_modify delay 0
fix m1 all property/global youngsModulus peratomtype 1e7
fix m2 all property/global poissonsRatio peratomtype 0.3
fix m3 all property/global coefficientRestitution peratomtypepair 1 0.5
fix m4 all property/global coefficientFriction peratomtypepair 1 0.5
pair_style gran model hertz tangential history
pair_coeff * *
timestep 1e-5
lattice sc 0.0021
region fill block 0 0.0104 0 0.0104 0.0011 0.027 units box
create_atoms 1 region fill
variable dia atom 0.0017+0.0003*(0.5+0.5*sin(id*12.9898))
set group all density 2500
set group all diameter v_dia
variable vx atom 0.05*sin(id*78.233)
variable vy atom 0.05*cos(id*37.719)
set group all vx v_vx vy v_vy
fix floor all wall/gran model hertz tangential history primitive type 1 zplane 0.0
fix g all gravity 9.81 vector 0 0 -1
fix damp all damping/cundall 0.7
fix i all nve/sphere
compute ub all unbalanced/force
compute ke all ke
thermo_style custom step ke c_ub f_floor[3]
thermo 2000
run 2000)";

}  // namespace

// A few hundred grains under gravity, dropped from a loose lattice onto a
// floor (x, y periodic: no side walls to carry weight), relax with
// damping/cundall 0.7 in 1 s (1e5 steps). Static equilibrium: the floor carries
// the whole weight (0.5 %); the kinetic energy drains below 1e-7 of m g d
// summed over the grains, and the unbalanced-force ratio falls from order 1
// below 1e-6. (Measured: ke 4e-9 m g d, floor = weight to 4e-8, ratio 0.44
// after 2000 steps, 1.2e-7 at the end. Cundall damping needs force to act: a
// grain rolling freely on the floor keeps its tiny speed.)
TEST(DampingCundall, RelaxesBedToStaticPacking) {
  Deck d;
  d(kBed);
  const auto& a = d->atoms;
  ASSERT_GE(a.n, 250u);
  double weight = 0, mgd = 0;
  for (std::size_t i = 0; i < a.n; ++i) {
    weight += a.rmass[i] * 9.81;
    mgd += a.rmass[i] * 9.81 * 2 * a.radius[i];
  }
  sable::Compute* ub = d->find_compute("ub");
  const double ub_early = ub->compute_scalar();
  d("run 98000");
  const double ke = d->find_compute("ke")->compute_scalar();
  const double floor = -d->find_fix("floor")->compute_vector(3);
  std::printf("[ measured ] %zu grains: ke/(m g d) %.3g, floor/weight - 1 = %.3g, ratio %.3g -> %.3g\n", a.n,
              ke / mgd, floor / weight - 1, ub_early, ub->compute_scalar());
  EXPECT_LT(ke, 1e-7 * mgd);
  EXPECT_NEAR(floor / weight, 1.0, 0.005);
  EXPECT_GT(ub_early, 0.1);
  EXPECT_LT(ub->compute_scalar(), 1e-6);
}

// The damping is a per-atom post-force task: the step stays fused and
// pipelined (fused_steps > 0) and gives the same bits as separate passes on
// one thread and as the fused plan on three threads (every loop threaded).
TEST(DampingCundall, FusedPlanSameBitsAnyThreadCount) {
  struct Out {
    std::vector<double> x, v, omega;
    long fused = 0;
  };
  auto run = [](int threads, bool fusion) {
    sable::ThreadSettings& ts = sable::thread_settings();
    const sable::ThreadSettings saved = ts;
    ts.pair_atoms = ts.pair_entries = ts.loop_work = 0;
#ifdef _OPENMP
    const int before = omp_get_max_threads();
    omp_set_num_threads(threads);
#endif
    Deck d;
    d->plan_rewrites = fusion ? sable::kAllRewrites : 0u;
    d(kBed);
    ts = saved;
#ifdef _OPENMP
    omp_set_num_threads(before);
#endif
    const auto& a = d->atoms;
    return Out{{a.x.begin(), a.x.begin() + 3 * a.n}, {a.v.begin(), a.v.begin() + 3 * a.n},
               {a.omega.begin(), a.omega.begin() + 3 * a.n}, d->fused_steps};
  };
  const Out serial = run(1, false), fused = run(1, true), threaded = run(3, true);
  EXPECT_EQ(serial.fused, 0);
  EXPECT_GT(fused.fused, 1000);
  for (const Out* o : {&fused, &threaded}) {
    EXPECT_EQ(o->x, serial.x);
    EXPECT_EQ(o->v, serial.v);
    EXPECT_EQ(o->omega, serial.omega);
  }
}

TEST(DampingCundall, WarnsAboutForceFixDefinedAfterIt) {
  Deck d;
  const std::string out = printed(std::string(kStiff) + R"(create_atoms 1 single 0 0 0.005 units box
set atom 1 diameter 0.002 density 2500
fix damp all damping/cundall 0.3
fix g all gravity 9.81 vector 0 0 -1
fix i all nve/sphere
run 0)",
                                  d);
  EXPECT_NE(out.find("its force is not damped"), std::string::npos) << out;
}

// ---- fix halt

namespace {

// One grain thrown up at 0.3 m/s under gravity: its kinetic energy (4.7e-7 J
// at first) falls below 5e-9 J near the top of its flight, around step 2750.
std::string thrown(const std::string& halt, const std::string& after) {
  return std::string(kStiff) + R"(timestep 1e-5
create_atoms 1 single 0 0 -0.009 units box
set atom 1 diameter 0.002 density 2500 vz 0.3
fix g all gravity 9.81 vector 0 0 -1
fix i all nve/sphere
compute ke all ke
variable ke equal c_ke
thermo_style custom step v_ke
thermo 50
)" + halt + "\nrun 100000\n" + after;
}

}  // namespace

// A run of 100000 steps stops at the first multiple of N = 50 at whose end
// the condition held: every thermo line before it (also at multiples of 50)
// had it false; the halt step's line is printed; the next command runs, and a
// following run continues from the halted step.
TEST(FixHalt, ContinueStopsAtFirstCheckWhereConditionHolds) {
  Deck d;
  const std::string out = printed(thrown("fix h all halt 50 v_ke < 5e-9 error continue",
                                         "print \"after halt: step $(step)\"\nunfix h\nrun 10"),
                                  d);
  std::smatch m;
  ASSERT_TRUE(std::regex_search(out, m, std::regex(R"(fix halt h: condition v_ke < 5e-09 met on step (\d+))"))) << out;
  const long step = std::stol(m[1]);
  EXPECT_EQ(step % 50, 0);
  EXPECT_GT(step, 2000);
  std::vector<std::pair<long, double>> ke;
  const std::regex thermo(R"(^\s*(\d+)\s+(\S+)\s*$)");
  std::istringstream in(out);
  for (std::string line; std::getline(in, line);)
    if (std::regex_match(line, m, thermo)) ke.push_back({std::stol(m[1]), std::stod(m[2])});
  ASSERT_GT(ke.size(), 40u);
  bool seen = false;
  for (auto& [s, e] : ke) {
    if (s < step) {
      EXPECT_GE(e, 5e-9) << "condition already held at step " << s;
    }
    if (s == step && !seen) {
      EXPECT_LT(e, 5e-9);
      seen = true;
    }
  }
  EXPECT_TRUE(seen) << "no thermo line at the halt step " << step;
  EXPECT_NE(out.find("after halt: step " + std::to_string(step)), std::string::npos) << out;
  EXPECT_EQ(d->step, step + 10);
}

// error hard (the default, as LAMMPS): the deck stops with the step and condition.
TEST(FixHalt, HardStopsTheDeckNamingTheStep) {
  Deck d;
  const std::string err = error_of(d, thrown("fix h all halt 50 v_ke < 5e-9", ""));
  EXPECT_NE(err.find("met on step"), std::string::npos) << err;
  EXPECT_NE(err.find("v_ke < 5e-09"), std::string::npos) << err;
  EXPECT_NE(err.find("test:"), std::string::npos) << err;
  EXPECT_EQ(d->step % 50, 0);
  EXPECT_LT(d->step, 100000);
}

// error soft: the run ends, the deck goes on, later runs are skipped (LAMMPS).
TEST(FixHalt, SoftSkipsLaterRuns) {
  Deck d;
  const std::string out = printed(thrown("fix h all halt 50 v_ke < 5e-9 error soft message no",
                                         "print \"goes on\"\nrun 100"),
                                  d);
  const long step = d->step;
  EXPECT_EQ(step % 50, 0);
  EXPECT_EQ(out.find("condition"), std::string::npos) << "message no";
  EXPECT_NE(out.find("goes on"), std::string::npos);
  EXPECT_NE(out.find("run 100 skipped"), std::string::npos) << out;
}

// Each operator, on the step number, checked every 10 steps of a 100-step run.
TEST(FixHalt, Operators) {
  struct Case {
    const char* cond;
    long step;
  } cases[] = {{"< 1000", 10}, {"<= 10", 10}, {"> 35", 40}, {">= 40", 40},
               {"== 70", 70},  {"!= 10", 20}, {"|^ 0", 10}, {"== 71", 100}};
  for (const Case& c : cases) {
    Deck d;
    d(std::string(kStiff) + "create_atoms 1 single 0 0 0 units box\nvariable s equal step\nfix h all halt 10 v_s " +
      c.cond + " error continue\nrun 100");
    EXPECT_EQ(d->step, c.step) << c.cond;
  }
  // xor: true when exactly one side is 0
  Deck d;
  d(std::string(kStiff) + "create_atoms 1 single 0 0 0 units box\nvariable s equal step-30\n"
                          "fix h all halt 10 v_s |^ 5 error continue\nrun 100");
  EXPECT_EQ(d->step, 30);
}

// tlimit: wall seconds since the run's first step, >= 0 at the first check.
TEST(FixHalt, Tlimit) {
  Deck d;
  d(std::string(kStiff) + "create_atoms 1 single 0 0 0 units box\nfix h all halt 20 tlimit >= 0 error continue\nrun 100");
  EXPECT_EQ(d->step, 20);
}

TEST(FixHalt, BadInput) {
  const std::string base = std::string(kStiff) + "create_atoms 1 single 0 0 0 units box\nvariable s equal step\n";
  auto err = [&](const std::string& line) {
    Deck d;
    return error_of(d, base + line);
  };
  EXPECT_NE(err("fix h all halt 10 v_nope < 1").find("no variable 'nope'"), std::string::npos);
  EXPECT_NE(err("fix h all halt 10 v_s =< 1").find("an operator"), std::string::npos);
  EXPECT_NE(err("fix h all halt 0 v_s < 1").find("N >= 1"), std::string::npos);
  EXPECT_NE(err("fix h all halt 10 v_s < nan").find("finite"), std::string::npos);
  EXPECT_NE(err("fix h all halt 10 v_s < 1 error maybe").find("hard, soft or continue"), std::string::npos);
  EXPECT_NE(err("fix h all halt 10 bondmax < 1").find("tlimit"), std::string::npos);
  EXPECT_NE(err("variable a atom x\nfix h all halt 10 v_a < 1").find("equal-style"), std::string::npos);
  // deleted after the fix was defined: at the next run
  EXPECT_NE(err("fix h all halt 10 v_s < 1\nvariable s delete\nrun 10").find("no variable 's'"), std::string::npos);
}

// ---- the relaxation loop deck: a piston of frozen grains is lowered by
// 0.15 mm five times; after each move the bed relaxes until the unbalanced
// force ratio is below 0.01 (checked every 100 steps) or 20000 steps pass.

namespace {

constexpr long kRelaxCap = 20000;
constexpr double kRelaxThreshold = 0.01;

// A RELAX record (i step steps ratio ke zpiston fpiston) of a relaxation that
// the halt ended: on a check step (multiple of 100) before the cap, with the
// ratio it printed below the threshold. A halt that never fires runs every
// relaxation to the cap, which this rejects.
bool stopped_by_halt(const std::vector<double>& r, double threshold) {
  const long steps = static_cast<long>(r[2]);
  return steps > 0 && steps < kRelaxCap && steps % 100 == 0 && r[3] < threshold;
}

std::vector<std::vector<double>> piston_records(const std::string& deck_text, Deck& d, std::string& out) {
  sable::test::TempDir tmp;
  const std::string path = tmp / "quasi_piston.in";  // `jump SELF` needs the deck as a file
  {
    std::ofstream f(path);
    f << deck_text;
  }
  out = printed("include " + path, d);
  return rows_after(out, "RELAX");
}

std::string piston_deck() {
  std::ifstream f(std::string(SABLE_SOURCE_DIR) + "/tests/decks/quasi_piston.in");
  std::stringstream s;
  s << f.rdbuf();
  return s.str();
}

}  // namespace

// Each record: the halt ended the relaxation on a check step with the ratio
// below 0.01 (every relaxation but the first, which starts from the settled
// bed's looser state and may run to the cap); the piston went down by exactly
// dz each time and each run continued from the halted step. (Measured: the
// first relaxation runs to the cap, the others stop at the threshold after
// 2100 to 5900 steps.)
TEST(QuasiStatic, PistonLoopDeckRelaxesEachStep) {
  Deck d;
  std::string out;
  const auto rec = piston_records(piston_deck(), d, out);
  ASSERT_EQ(rec.size(), 5u) << out;
  for (std::size_t k = 0; k < rec.size(); ++k) {
    const auto& r = rec[k];
    ASSERT_EQ(r.size(), 7u);
    EXPECT_EQ(r[0], k + 1);
    if (k > 0) {
      EXPECT_TRUE(stopped_by_halt(r, kRelaxThreshold))
          << "relaxation " << k + 1 << " not ended by the halt: " << r[2] << " steps, ratio " << r[3];
      EXPECT_EQ(r[1], rec[k - 1][1] + r[2]);  // each run continues from the halted step
      EXPECT_NEAR(rec[k - 1][5] - r[5], 1.5e-4, 1e-12);
    } else {
      EXPECT_TRUE(r[2] == kRelaxCap || stopped_by_halt(r, kRelaxThreshold)) << r[2] << " steps, ratio " << r[3];
    }
  }
  // The set strain: five steps of dz from where the first one started.
  EXPECT_NEAR(rec[0][5] + 1.5e-4 - rec[4][5], 5 * 1.5e-4, 1e-12);
}

// Positive control for the check above: the same deck with a halt whose
// condition cannot hold (the ratio is never negative) and two moves instead of
// five runs every relaxation to the cap, and stopped_by_halt says so, while the
// same records read with a threshold above their ratios would pass were the cap
// not checked.
TEST(QuasiStatic, HaltThatNeverFiresIsCaught) {
  std::string text = piston_deck();
  const std::string halt = "fix h all halt 100 v_ub < 0.01 error continue", loop = "variable i loop 5";
  ASSERT_NE(text.find(halt), std::string::npos) << "the deck's relaxation halt changed";
  ASSERT_NE(text.find(loop), std::string::npos) << "the deck's loop changed";
  text.replace(text.find(halt), halt.size(), "fix h all halt 100 v_ub < 0 error continue");
  text.replace(text.find(loop), loop.size(), "variable i loop 2");
  Deck d;
  std::string out;
  const auto rec = piston_records(text, d, out);
  ASSERT_EQ(rec.size(), 2u) << out;
  for (const auto& r : rec) {
    ASSERT_EQ(r.size(), 7u);
    EXPECT_EQ(r[2], kRelaxCap);
    EXPECT_FALSE(stopped_by_halt(r, kRelaxThreshold));
    EXPECT_FALSE(stopped_by_halt(r, 2 * r[3] + 1));  // the cap alone rejects it
  }
}

}  // namespace test_quasi_static
