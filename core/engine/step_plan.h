#pragma once
// The step as data (docs/ARCHITECTURE.md, "The step"): the stages of a step,
// built once per run from what the fixes declare (their hooks and atom tasks).
// The plain plan runs every hook as LIGGGHTS does; fusion, gravity folding,
// pipelining and the displacement prescan are rewrites of it, each giving the
// same bits (tests/unit/test_step_plan.cpp). `info plan` prints it.
#include <string>
#include <vector>

#include "core/engine/fix.h"

namespace sable {

class Simulation;

// A step is "quiet" when nobody looks at the grains after it (no thermo, dump
// or end-of-step fix due, not the run's last step): a fused plan defers its
// second half kick to the next step's first atom pass. A stage runs always,
// only on loud or quiet steps, or only after a loud or a quiet step.
enum class When : unsigned char { Always, Loud, Quiet, AfterLoud, AfterQuiet };

// One operation on a thread's atoms [lo, hi), composed by the plan.
struct AtomOp {
  enum Kind : unsigned char {
    AddMassAccel,  // f += m a (a folded fix gravity)
    SecondHalf,    // the integrator's second half kick (Fix::range FINAL_INTEGRATE)
    FirstHalf,     // its first half kick and drift (Fix::range INITIAL_INTEGRATE)
    BothHalves,    // SecondHalf then FirstHalf in one loop (Fix::range FINAL_THEN_INITIAL)
    ClearForces,   // f = torque = 0
    PostForce,     // a fix's post_force task
    Prescan,       // the rebuild check's displacement scan (Neighbor::prescan_range)
  } kind;
  Fix* fix = nullptr;
  int phase = 0;  // two-phase integrators: 0 (their bodies), then 1 (their members)
  double accel[3] = {0, 0, 0};
  std::string describe() const;
};

struct Stage {
  enum Kind : unsigned char {
    Hook,       // fix->hook() as LIGGGHTS calls it
    AtomPass,   // ops on every thread's atoms (blocks of atoms for single-phase ops)
    Rebuild,    // neighbour list check and rebuild
    ForcePass,  // pair forces, then ops on each range as soon as its forces are final
    Check,      // stop on a non-finite velocity
    Output,     // thermo and dumps
  } kind;
  When when = When::Always;
  explicit Stage(Kind k, When w = When::Always) : kind(k), when(w) {}
  Fix* fix = nullptr;  // Hook
  FixHook hook = INITIAL_INTEGRATE;
  std::vector<AtomOp> ops;  // AtomPass, ForcePass
  // The fixes of ops, each once in the order of its first op, with its last op's
  // hook (a fused integrator: INITIAL_INTEGRATE): whose begin() and end() the
  // stage calls. Set by build_plan after the rewrites.
  std::vector<std::pair<Fix*, FixHook>> calls;
  std::string describe() const;
};

struct StepPlan {
  std::vector<Stage> stages;
  std::vector<std::string> rewrites;  // applied, in order
  bool defers = false;                 // quiet steps exist (the plan was fused)
  Fix* integrator = nullptr;           // the fused integrator
  Fix* folded = nullptr;               // the gravity folded into it on quiet steps
  std::string describe() const;
};

// Rewrites a plan may take; `Simulation::plan_rewrites` selects them (tests turn each off).
enum PlanRewrite : unsigned {
  kFuse = 1u << 0,      // one integrator: both halves and the force clear in one atom pass
  kFold = 1u << 1,      // a last fix gravity on all into that pass on quiet steps
  kPipeline = 1u << 2,  // post_force tasks (and the next first half) inside the force pass
  kPrescan = 1u << 3,   // the rebuild check's scan in the pass that last moved the atoms
  kAllRewrites = kFuse | kFold | kPipeline | kPrescan,
};

StepPlan plain_plan(const Simulation& sim);
StepPlan fuse(StepPlan p);
StepPlan fold_gravity(StepPlan p);
StepPlan pipeline(StepPlan p, bool has_pair);
StepPlan prescan(StepPlan p);
// The plain plan with the rewrites `mask` allows, in the order above.
StepPlan build_plan(const Simulation& sim, unsigned mask);

// Runs `ops` over every thread's atoms (begin/end of each fix serially around them).
void run_atom_ops(Simulation& sim, const Stage& s);
// Runs `ops` on one thread's atoms [lo, hi): single-phase ops block by block.
void run_ops_on_range(Simulation& sim, const std::vector<AtomOp>& ops, int t, std::size_t lo, std::size_t hi,
                      double* fix_seconds = nullptr);
// begin()/end() of each fix the ops call (serially, before and after a pass).
void begin_ops(const Stage& s);
void end_ops(const Stage& s);

}  // namespace sable
