// Deterministic threading: the same deck gives the same bits whatever the
// thread count and whether the contact loops run as AVX-512, AVX2 or SSE2 (core/engine/threads.h,
// GranKernel::pair_forces). The size thresholds are lowered so a small system
// takes every threaded path: the pair pass (ranges, cross entries and their
// slots), the neighbour build, the integrator, gravity, the wall (in blocks of
// 16 grains) and the checks, the per-atom passes on the pair pass's ranges.
// Step fusion (Simulation::run) must give the bits of the separate passes too.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/input/style_registry.h"
#include "core/engine/threads.h"
#include "tests/unit/deck_runner.h"

// A namespace per file: the unit tests compile in unity batches (tests/CMakeLists.txt).
namespace test_threads {

using sable::test::Deck;
constexpr sable::Simd kWide = sable::Simd::AVX512;  // the widest the CPU has (simd_level())

namespace {

// A periodic box of polydisperse grains falling on a floor: contacts across
// the periodic boundaries, a wall, rebuilds with history carried over.
const char* kDeck = R"D(units si
atom_style granular
boundary p p f
newton off
communicate single vel yes
region box block 0 0.012 0 0.012 0 0.03 units box
create_box 1 box
neighbor 0.0004 bin
neigh_modify delay 0
fix m1 all property/global youngsModulus peratomtype 1e7
fix m2 all property/global poissonsRatio peratomtype 0.3
fix m3 all property/global coefficientRestitution peratomtypepair 1 0.5
fix m4 all property/global coefficientFriction peratomtypepair 1 0.5
pair_style gran model hertz tangential history
pair_coeff * *
timestep 4e-6
lattice sc 0.00105
region fill block 0 0.012 0 0.012 0.0006 0.012 units box
create_atoms 1 region fill
variable dd atom 0.0008+0.0002*(id*0.6180339887-floor(id*0.6180339887))
variable vvx atom 0.2*((id*0.7548776662-floor(id*0.7548776662))-0.5)
variable vvz atom 0.2*((id*0.4142135624-floor(id*0.4142135624))-0.5)
set group all diameter v_dd
set group all density 2500
set group all vx v_vvx vz v_vvz
fix floor all wall/gran model hertz tangential history primitive type 1 zplane 0.0
fix grav all gravity 9.81 vector 0 0 -1
fix integr all nve/sphere
run 1500
)D";

struct State {
  std::vector<double> x, v, omega, f, torque;
  std::vector<long> id;
  long builds = 0, fused_steps = 0, folded_steps = 0, cleared_steps = 0, prescans = 0;
  std::size_t contacts = 0;  // touching pair entries at the end
  double floor_force[3] = {0, 0, 0};
  double freeze_force[3] = {0, 0, 0};  // f_fr, where the deck has fix fr
  bool operator==(const State& o) const {
    auto same = [](const std::vector<double>& a, const std::vector<double>& b) {
      return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0;
    };
    return id == o.id && std::memcmp(floor_force, o.floor_force, sizeof floor_force) == 0 &&
           std::memcmp(freeze_force, o.freeze_force, sizeof freeze_force) == 0 && same(x, o.x) && same(v, o.v) &&
           same(omega, o.omega) && same(f, o.f) && same(torque, o.torque);
  }
};

// `before_run`: commands inserted before the run (thermo output stops the
// deferred final half kick); `fusion` false: every pass separate.
State run(int threads, sable::Simd simd, const std::string& before_run = "", bool fusion = true,
          const std::string& deck_text = kDeck) {
  sable::ThreadSettings& ts = sable::thread_settings();
  const sable::ThreadSettings saved = ts;
  ts.pair_atoms = ts.pair_entries = ts.loop_work = 0;  // every loop threaded
  ts.wall_block = 16;
  ts.simd = simd;
#ifdef _OPENMP
  const int before = omp_get_max_threads();
  omp_set_num_threads(threads);
#endif
  std::string deck = deck_text;
  deck.insert(deck.find("run 1500"), before_run);
  Deck d;
  d->plan_rewrites = fusion ? sable::kAllRewrites : 0u;
  d(deck);
  ts = saved;
#ifdef _OPENMP
  omp_set_num_threads(before);
#endif
  const sable::Atoms& a = d->atoms;
  State s;
  s.x.assign(a.x.begin(), a.x.begin() + 3 * a.n);
  s.v.assign(a.v.begin(), a.v.begin() + 3 * a.n);
  s.omega.assign(a.omega.begin(), a.omega.begin() + 3 * a.n);
  s.f.assign(a.f.begin(), a.f.begin() + 3 * a.n);
  s.torque.assign(a.torque.begin(), a.torque.begin() + 3 * a.n);
  s.id.assign(a.id.begin(), a.id.begin() + a.n);
  s.builds = d->neighbor.builds;
  for (int k = 0; k < 3; ++k) s.floor_force[k] = d->find_fix("floor")->compute_vector(k + 1);
  if (sable::Fix* fr = d->find_fix("fr"))
    for (int k = 0; k < 3; ++k) s.freeze_force[k] = fr->compute_vector(k + 1);
  s.fused_steps = d->fused_steps;
  s.folded_steps = d->folded_steps;
  s.cleared_steps = d->cleared_steps;
  s.prescans = d->neighbor.prescans_used;
  if (const sable::ContactStore* h = d->pair->history())
    s.contacts = h->contacts();
  return s;
}

// kDeck in a two-type box (all grains still of type 1), with `extra`
// commands inserted before its `fix floor` line.
std::string two_type_deck(const std::string& extra = "") {
  std::string deck = kDeck;
  auto swap = [&](const std::string& from, const std::string& to) {
    const std::size_t at = deck.find(from);
    if (at == std::string::npos) throw std::logic_error("kDeck lacks: " + from);
    deck.replace(at, from.size(), to);
  };
  swap("create_box 1 box", "create_box 2 box");
  swap("youngsModulus peratomtype 1e7", "youngsModulus peratomtype 1e7 2e7");
  swap("poissonsRatio peratomtype 0.3", "poissonsRatio peratomtype 0.3 0.25");
  swap("coefficientRestitution peratomtypepair 1 0.5", "coefficientRestitution peratomtypepair 2 0.5 0.6 0.6 0.7");
  swap("coefficientFriction peratomtypepair 1 0.5", "coefficientFriction peratomtypepair 2 0.5 0.4 0.4 0.3");
  if (!extra.empty()) swap("fix floor", extra + "fix floor");
  return deck;
}

}  // namespace

TEST(Threads, BitIdenticalForAnyThreadCountAndVectorWidth) {
  const State serial = run(1, kWide);
  ASSERT_GT(serial.id.size(), 1000u);
  ASSERT_GT(serial.builds, 3);             // history carried across rebuilds
  ASSERT_GT(serial.contacts, 300u);        // a scene with many contacts
  ASSERT_LT(serial.floor_force[2], 0.0);   // grains press on the floor (in several wall blocks)
  // The widest variant the CPU has (kWide) against the narrower ones.
  EXPECT_TRUE(run(1, sable::Simd::SSE2) == serial) << "SSE2 and the widest contact loops differ";
  EXPECT_TRUE(run(1, sable::Simd::AVX2) == serial) << "AVX2 and the widest contact loops differ";
#ifdef _OPENMP
  EXPECT_TRUE(run(2, kWide) == serial) << "2 threads differ from 1";
  EXPECT_TRUE(run(3, kWide) == serial) << "3 threads differ from 1";
  // Ranges narrower than a grain's reach: cross entries that skip a range.
  EXPECT_TRUE(run(6, kWide) == serial) << "6 threads differ from 1";
  EXPECT_TRUE(run(2, kWide) == run(2, kWide)) << "2 threads differ run to run";
#endif
}

// Two atom types and a frozen group take the general gather (per-contact type
// pairs, freeze flags): the widest loops give the bits of SSE2 and of 2 threads.
TEST(Threads, TypesAndFrozenGrainsSameBitsForAnyWidth) {
  const std::string deck = two_type_deck(R"(region upper block 0 0.012 0 0.012 0.006 0.03 units box
set region upper type 2
region stuck block 0 0.006 0 0.006 0 0.002 units box
group stuck region stuck
fix fr stuck freeze
)");
  const State wide = run(1, kWide, "", true, deck);
  ASSERT_GT(wide.contacts, 300u);
  EXPECT_TRUE(run(1, sable::Simd::SSE2, "", true, deck) == wide) << "SSE2 and the widest contact loops differ";
#ifdef _OPENMP
  EXPECT_TRUE(run(2, kWide, "", true, deck) == wide) << "2 threads differ from 1";
#endif
}

// fix freeze in the pipelined step: each thread sums its frozen grains'
// forces in fixed blocks of 1024 atoms, and a block cut by a range bound is
// finished in atom order, so f_ID has the bits of one serial pass. Every third
// grain frozen (1331 grains, two blocks): 2 threads cut the first block, 3
// and 6 leave ranges inside it.
TEST(Threads, FreezeForceSameBitsForAnyThreadCount) {
  std::string deck = kDeck;
  deck.insert(deck.find("fix integr"), "group stuck id 1:100000:3\nfix fr stuck freeze\n");
  const State serial = run(1, kWide, "", true, deck);
  ASSERT_GT(serial.id.size(), 1024u);
  ASSERT_GT(serial.fused_steps, 1000);  // the pipelined step (all post_force fixes ranged)
  EXPECT_GT(std::fabs(serial.freeze_force[2]), 1e-4);  // gravity and contacts on ~440 grains of ~1.3e-5 N weight
#ifdef _OPENMP
  for (int t : {2, 3, 6}) EXPECT_TRUE(run(t, kWide, "", true, deck) == serial) << t << " threads differ from 1";
#endif
}

// Rigid clumps (fix rigid/small, bodies of three neighbours along x): the body
// passes are serial (sums in atom order) between the threaded pair and atom
// passes; the bodies are renumbered at each sort. The same bits for any count.
TEST(Threads, RigidBodiesSameBitsForAnyThreadCount) {
  std::string deck = kDeck;
  deck.replace(deck.find("fix integr all nve/sphere"), 25,
               "variable body atom floor(x/0.00315)+100*floor(y/0.00105)+10000*floor(z/0.00105)+1\n"
               "fix integr all rigid/small custom v_body");
  const State serial = run(1, kWide, "", true, deck);
  ASSERT_GT(serial.contacts, 100u);
  EXPECT_NE(serial.omega[0], 0.0);  // the bodies turn
#ifdef _OPENMP
  for (int t : {2, 3, 6}) EXPECT_TRUE(run(t, kWide, "", true, deck) == serial) << t << " threads differ from 1";
#endif
  // The bodies' two-phase tasks fused across steps (gravity not folded into them:
  // a body sums members that other threads' ranges hold): the bits of separate passes.
  const State separate = run(1, kWide, "", false, deck);
  EXPECT_EQ(separate.fused_steps, 0);
  EXPECT_EQ(serial.fused_steps, 1499);
  EXPECT_EQ(serial.folded_steps, 0);
  // ... which also zero the forces after placing the members and scan them for
  // the rebuild check (one region a step for the whole integration).
  EXPECT_EQ(serial.cleared_steps, 1500);
  EXPECT_EQ(separate.cleared_steps, 0);
  EXPECT_GT(serial.prescans, 1400);
  EXPECT_EQ(separate.prescans, 0);
  EXPECT_EQ(serial.builds, separate.builds);
  EXPECT_TRUE(serial == separate) << "fused and separate passes differ";
#ifdef _OPENMP
  EXPECT_TRUE(run(2, kWide, "thermo 7\n", true, deck) == separate) << "partly fused, 2 threads: differs";
#endif
}

// A final half kick deferred into the next initial pass, forces zeroed by the
// integrator and gravity (kDeck's last post_force fix) added by it: the same
// bits (and the same rebuilds) as separate passes.
TEST(StepFusion, SameBitsAsSeparatePasses) {
  const State separate = run(1, kWide, "", false);
  const State fused = run(1, kWide);
  EXPECT_EQ(separate.fused_steps, 0);
  EXPECT_EQ(separate.folded_steps, 0);
  EXPECT_EQ(run(1, kWide, "thermo 1\n").fused_steps, 0);  // output every step: no deferred kick
  EXPECT_EQ(fused.fused_steps, 1499);  // all but the last step
  EXPECT_EQ(fused.folded_steps, 1499);
  EXPECT_EQ(fused.builds, separate.builds);
  EXPECT_TRUE(fused == separate) << "fused and separate passes differ";
#ifdef _OPENMP
  EXPECT_TRUE(run(2, kWide) == separate) << "fused passes on 2 threads differ";
#endif
  const State some = run(1, kWide, "thermo 100\n");  // fused except around output steps
  EXPECT_EQ(some.fused_steps, 1485);
  EXPECT_EQ(some.folded_steps, 1485);
  EXPECT_TRUE(some == separate);
}

// Gravity before the wall: its addition is not the last one, so its pass is
// not folded; fusion still gives the bits of separate passes.
TEST(StepFusion, GravityFoldedOnlyAsTheLastPostForceFix) {
  std::string deck = kDeck;
  const std::string grav = "fix grav all gravity 9.81 vector 0 0 -1\n";
  deck.erase(deck.find(grav), grav.size());
  deck.insert(deck.find("fix floor"), grav);
  const State separate = run(1, kWide, "", false, deck);
  const State fused = run(1, kWide, "", true, deck);
  EXPECT_EQ(fused.fused_steps, 1499);
  EXPECT_EQ(fused.folded_steps, 0);
  EXPECT_TRUE(fused == separate) << "fused and separate passes differ";
  EXPECT_FALSE(fused == run(1, kWide)) << "the order of gravity and wall made no difference: the test shows nothing";
}

// An integrator on a named group joins the fused, pipelined step like one on
// `all`: grains outside the group keep their positions, velocities and spins
// bit for bit (the integrator's select), and the result equals separate passes.
// ("group id 1:100000:4": ids 1, 5, 9, ...; create_atoms numbers 1..N.)
TEST(StepFusion, NamedGroupIntegratorFusedWithTheBitsOfSeparatePasses) {
  std::string deck = kDeck;
  const std::string integ = "fix integr all nve/sphere";
  deck.replace(deck.find(integ), integ.size(), "group moving id 1:100000:4\ngroup still subtract all moving\n"
                                                   "fix integr moving nve/sphere");
  const State separate = run(1, kWide, "", false, deck);
  const State fused = run(1, kWide, "", true, deck);
  EXPECT_EQ(separate.fused_steps, 0);
  EXPECT_EQ(fused.fused_steps, 1499);
  EXPECT_TRUE(fused == separate) << "fused and separate passes differ";
#ifdef _OPENMP
  EXPECT_TRUE(run(2, kWide, "", true, deck) == separate) << "fused passes on 2 threads differ";
#endif
  // Outside the group: the lattice position and the initial velocity, exactly.
  Deck d;
  d(deck.substr(0, deck.find("run 1500")));
  const sable::Atoms& a = d->atoms;
  const std::vector<double> x0(a.x.begin(), a.x.begin() + 3 * a.n), v0(a.v.begin(), a.v.begin() + 3 * a.n);
  const std::vector<long> id0(a.id.begin(), a.id.begin() + a.n);
  std::size_t still = 0, moved = 0;
  for (std::size_t i = 0; i < fused.id.size(); ++i) {
    const std::size_t j = std::find(id0.begin(), id0.end(), fused.id[i]) - id0.begin();
    ASSERT_LT(j, id0.size());
    if ((fused.id[i] - 1) % 4 == 0) {
      moved += fused.x[3 * i + 2] != x0[3 * j + 2];
      continue;
    }
    bool same = true;
    for (int k = 0; k < 3; ++k) same = same && fused.x[3 * i + k] == x0[3 * j + k] && fused.v[3 * i + k] == v0[3 * j + k];
    still += same;
    EXPECT_TRUE(same) << "grain " << fused.id[i] << " is outside the group but moved";
  }
  EXPECT_GT(moved, fused.id.size() / 5);  // the group's grains fell
  EXPECT_EQ(still, fused.id.size() - (fused.id.size() + 3) / 4);
}

// Per-atom passes run on the pair pass's atom ranges while these describe the
// atoms and the thread count, else on equal parts; either way every atom once.
TEST(Threads, AtomPassesFollowThePairSplit) {
  sable::ThreadSettings& ts = sable::thread_settings();
  const sable::ThreadSettings saved = ts;
  ts.loop_work = 0;  // threaded at any size
  const std::size_t n = 1000;
  auto ranges = [&](const sable::AtomSplit& split) {
    std::vector<int> seen(n, 0);
    std::vector<std::array<std::size_t, 2>> r(sable::atom_pass_threads(), {0, 0});
    sable::for_atom_ranges(split, n, [&](int t, std::size_t lo, std::size_t hi) {
      r[t] = {lo, hi};
      for (std::size_t i = lo; i < hi; ++i) ++seen[i];
    });
    EXPECT_TRUE(std::all_of(seen.begin(), seen.end(), [](int c) { return c == 1; })) << "an atom missed or repeated";
    return r;
  };
#ifdef _OPENMP
  const int before = omp_get_max_threads();
  omp_set_num_threads(2);
  sable::AtomSplit split;
  split.n = n;
  split.lo = {0, 700, static_cast<int>(n)};
  auto r = ranges(split);
  EXPECT_EQ(r[0][1], 700u);
  EXPECT_EQ(r[1][0], 700u);
  split.n = n + 1;  // stale: describes other atoms
  r = ranges(split);
  EXPECT_EQ(r[0][1], n / 2);
  omp_set_num_threads(3);  // stale: another thread count
  split.n = n;
  r = ranges(split);
  EXPECT_EQ(r[1][0], n / 3);
  omp_set_num_threads(before);
#else
  ranges(sable::AtomSplit{});
#endif
  ts = saved;
}

// The run summary's thread balance: every pair pass of the run counted, each
// thread busy for part of the passes' wall time, never more.
TEST(Threads, BalanceCountsEveryThreadedPass) {
#ifdef _OPENMP
  const long p_builds = run(2, kWide).builds;
  const sable::ThreadBalance& p = sable::thread_balance(sable::PassKind::Pair);
  const sable::ThreadBalance& a = sable::thread_balance(sable::PassKind::Atoms);
  EXPECT_EQ(p.calls, 1500);  // one per step (the setup pass is before the count starts)
  // The fused integrate (with gravity) and the rebuild check's scan run in the
  // pair pass's ranges (pipelined step): passes of their own only for the
  // first step's initial pass and scan, the last step's final pass, and five
  // at each rebuild in the run (`builds` counts the setup's too): the atom
  // check, the look for lost atoms, the bins' slow-axis sample, the positions
  // kept for the next check and the wall's near-grain search (each thread on
  // its own grains).
  EXPECT_EQ(a.calls, 3 + 5 * (p_builds - 1)) << a.calls;
  for (const sable::ThreadBalance* b : {&p, &a}) {
    ASSERT_EQ(b->busy.size(), 2u);
    for (double s : b->busy) {
      EXPECT_GT(s, 0.0);
      EXPECT_LE(s, b->wall * (1 + 1e-9) + 1e-6);
    }
  }
#else
  GTEST_SKIP() << "built without OpenMP";
#endif
}

// With one atom type the contact loops read each coefficient once per chunk
// (PairChunk::tp0); with two types, per contact from the type-pair tables. The
// same grains all of type 1 in a two-type box: the same bits either way.
TEST(KernelSpecialisation, OneTypeSameBitsAsPerContactTypes) {
  const std::string two = two_type_deck();
  const State one = run(1, kWide), both = run(1, kWide, "", true, two);
  ASSERT_GT(one.contacts, 300u);
  EXPECT_TRUE(one == both) << "one-type and per-contact-type loops differ";
  EXPECT_TRUE(run(1, sable::Simd::SSE2, "", true, two) == one) << "per-contact-type SSE2 loop differs";
}

// SABLE_PAIR_TRACE: one line per threaded pair pass (the setup pass and each
// step), each thread's times ordered within the pass's wall time, and the
// summary script reads it. Large enough (5 000 grains, 3 list entries each)
// for the pair pass to thread at the default thresholds.
TEST(Threads, PairTraceWritesOnePassPerLine) {
#if defined(_OPENMP) && defined(SABLE_BINARY)
  std::string deck = kDeck;
  deck.replace(deck.find("block 0 0.012 0 0.012 0 0.03"), 28, "block 0 0.024 0 0.024 0 0.03");
  deck.replace(deck.find("block 0 0.012 0 0.012 0.0006 0.012"), 34, "block 0 0.024 0 0.024 0.0006 0.012");
  deck.replace(deck.find("run 1500"), 8, "run 20");
  const std::string in = "pair_trace_test.in", trace = "pair_trace_test.txt";
  std::FILE* f = std::fopen(in.c_str(), "w");
  ASSERT_TRUE(f);
  std::fputs(deck.c_str(), f);
  std::fclose(f);
  const std::string cmd = "SABLE_PAIR_TRACE=" + trace + " OMP_NUM_THREADS=2 OMP_WAIT_POLICY=passive " +
                          SABLE_BINARY + " -in " + in + " -log none > /dev/null 2>&1";
  ASSERT_EQ(std::system(cmd.c_str()), 0) << cmd;
  std::FILE* t = std::fopen(trace.c_str(), "r");
  ASSERT_TRUE(t);
  char line[1024];
  ASSERT_TRUE(std::fgets(line, sizeof line, t));
  EXPECT_EQ(line[0], '#');
  int passes = 0, new_lists = 0;
  while (std::fgets(line, sizeof line, t)) {
    double v[11];
    int kind = -1, used = 0;
    ASSERT_EQ(std::sscanf(line, "%lf %d %lf %lf %lf %lf %lf %lf %lf %lf %lf%n", &v[0], &kind, &v[2], &v[3], &v[4],
                          &v[5], &v[6], &v[7], &v[8], &v[9], &v[10], &used),
              11)
        << line;
    EXPECT_TRUE(line[used] == '\n' || line[used] == '\0') << "more than two threads' columns: " << line;
    ++passes;
    new_lists += kind == 2;
    for (int th = 0; th < 2; ++th) {
      const double* r = &v[3 + 4 * th];  // start, end of phase A, start of phase B, end
      EXPECT_LE(v[0], r[0]) << line;     // planned before the threads start
      EXPECT_TRUE(r[0] <= r[1] && r[1] <= r[2] && r[2] <= r[3] && r[3] <= v[2]) << line;
    }
  }
  std::fclose(t);
  EXPECT_EQ(passes, 21);  // the setup pass and 20 steps
  EXPECT_GE(new_lists, 1);
  std::string py;
  for (const char* c : {"/usr/bin/python3", "python3"})
    if (std::system((std::string(c) + " -c 'import numpy' > /dev/null 2>&1").c_str()) == 0) {
      py = c;
      break;
    }
  if (!py.empty()) {
    const std::string sum = std::string("PYTHONPATH=") + SABLE_SOURCE_DIR + " " + py + " -m sable_tools.bench.pair_trace " + trace;
    std::FILE* p = popen(sum.c_str(), "r");
    ASSERT_TRUE(p);
    std::string out;
    while (std::fgets(line, sizeof line, p)) out += line;
    EXPECT_EQ(pclose(p), 0) << out;
    EXPECT_NE(out.find("21 passes, 2 threads"), std::string::npos) << out;
    EXPECT_NE(out.find("phase B waiting"), std::string::npos) << out;
  }
  std::remove(in.c_str());
  std::remove(trace.c_str());
#else
  GTEST_SKIP() << "built without OpenMP";
#endif
}

// A fix whose post_force is not a per-atom task keeps the step off the
// pipelined plan; sable says which fix and what it costs, once per fix.
namespace {
class FixPlainPostForce : public sable::Fix {
 public:
  FixPlainPostForce(sable::Simulation& s, const sable::Args& a) : Fix(s, a) { hooks = sable::POST_FORCE; }
  void post_force() override {}
};
SABLE_FIX("test/plain_post_force", FixPlainPostForce);
}  // namespace

TEST(StepFusion, SlowPathNamedOncePerFix) {
  std::string deck = kDeck;
  deck.replace(deck.find("run 1500"), 8, "fix plain all test/plain_post_force\nrun 10\nrun 10\n");
  Deck d;
  const std::string out = sable::test::printed(deck, d);
  const std::string note = "Note: fix plain (test/plain_post_force) has a post_force that is not a per-atom task";
  const std::size_t first = out.find(note);
  ASSERT_NE(first, std::string::npos) << out;
  EXPECT_EQ(out.find(note, first + 1), std::string::npos) << "printed twice:\n" << out;
  EXPECT_EQ(d->fused_steps, 18);  // still fused, not pipelined: all but each run's last step
  std::string plain = kDeck;
  plain.replace(plain.find("run 1500"), 8, "run 10");
  Deck quiet;
  EXPECT_EQ(sable::test::printed(plain, quiet).find("Note: fix"), std::string::npos);
}

}  // namespace test_threads
