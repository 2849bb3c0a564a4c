#include "core/engine/step_plan.h"

#include <algorithm>
#include <chrono>
#include <cstdio>

#include "core/engine/simulation.h"
#include "core/engine/threads.h"

namespace sable {

namespace {
const char* hook_name(FixHook h) {
  switch (h) {
    case INITIAL_INTEGRATE: return "initial_integrate";
    case POST_INTEGRATE: return "post_integrate";
    case PRE_FORCE: return "pre_force";
    case POST_FORCE: return "post_force";
    case FINAL_INTEGRATE: return "final_integrate";
    case END_OF_STEP: return "end_of_step";
    case FINAL_THEN_INITIAL: return "final_integrate + initial_integrate";
  }
  return "?";
}

const char* when_name(When w) {
  switch (w) {
    case When::Always: return "";
    case When::Loud: return "[loud steps] ";
    case When::Quiet: return "[quiet steps] ";
    case When::AfterLoud: return "[after a loud step] ";
    case When::AfterQuiet: return "[after a quiet step] ";
  }
  return "";
}

// "fix ID (style, role)": the role it plays at hook h (Fix::role).
std::string fix_name(const Fix* f, FixHook h) {
  const std::string role = role_name(f->role(h));
  return "fix " + f->id + " (" + f->style + (role.empty() ? "" : ", " + role) + ")";
}

bool two_phase(const AtomOp& op) {
  return (op.kind == AtomOp::FirstHalf && (op.fix->two_phase_tasks & INITIAL_INTEGRATE)) ||
         (op.kind == AtomOp::SecondHalf && (op.fix->two_phase_tasks & FINAL_INTEGRATE));
}

// Ops that treat each atom on their own, with no state per call: run block by block
// (a block's arrays stay in L1 across the ops; each atom sees the same operations in
// the same order, so the same bits).
bool blockwise(const AtomOp& op) {
  switch (op.kind) {
    case AtomOp::AddMassAccel:
    case AtomOp::ClearForces: return true;
    case AtomOp::FirstHalf:
    case AtomOp::SecondHalf: return !two_phase(op);
    case AtomOp::BothHalves: return true;
    default: return false;
  }
}

FixHook hook_of(const AtomOp& op) {
  switch (op.kind) {
    case AtomOp::FirstHalf: return INITIAL_INTEGRATE;
    case AtomOp::SecondHalf: return FINAL_INTEGRATE;
    case AtomOp::BothHalves: return FINAL_THEN_INITIAL;
    default: return POST_FORCE;
  }
}

bool moves_atoms(const AtomOp& op) { return op.kind == AtomOp::FirstHalf || op.kind == AtomOp::BothHalves; }

bool calls_fix(const AtomOp& op) { return op.fix && op.kind != AtomOp::AddMassAccel; }

void run_op(Simulation& sim, const AtomOp& op, int t, std::size_t lo, std::size_t hi) {
  Atoms& at = sim.atoms;
  switch (op.kind) {
    case AtomOp::AddMassAccel: {  // as fix gravity adds it
      double* __restrict f = at.f.data();
      const double* __restrict m = at.rmass.data();
      const double a0 = op.accel[0], a1 = op.accel[1], a2 = op.accel[2];
      for (std::size_t i = lo; i < hi; ++i) {
        f[3 * i] += m[i] * a0;
        f[3 * i + 1] += m[i] * a1;
        f[3 * i + 2] += m[i] * a2;
      }
      return;
    }
    case AtomOp::ClearForces: {
      double *f = at.f.data(), *tq = at.torque.data();
#pragma omp simd
      for (std::size_t k = 3 * lo; k < 3 * hi; ++k) f[k] = tq[k] = 0.0;
      return;
    }
    case AtomOp::Prescan: sim.neighbor.prescan_range(at, t, lo, hi); return;
    default: {
      Fix::AtomRange r;
      r.thread = t, r.lo = lo, r.hi = hi, r.phase = op.phase;
      op.fix->range(hook_of(op), r);
    }
  }
}

constexpr std::size_t kBlock = 128;

// Ops [a, b) of one phase on [lo, hi): runs of blockwise ops block by block.
void run_phase(Simulation& sim, const std::vector<AtomOp>& ops, std::size_t a, std::size_t b, int t, std::size_t lo,
               std::size_t hi, double* fix_s) {
  using clock = std::chrono::steady_clock;
  while (a < b) {
    std::size_t e = a + 1;
    if (blockwise(ops[a])) {
      while (e < b && blockwise(ops[e])) ++e;
      for (std::size_t x = lo; x < hi; x += kBlock)
        for (std::size_t k = a; k < e; ++k) run_op(sim, ops[k], t, x, std::min(hi, x + kBlock));
    } else if (fix_s && ops[a].kind == AtomOp::PostForce) {
      // One clock pair for a run of post-force tasks: a clock read costs as much
      // as a small fix's range, and small decks have many of them.
      while (e < b && !blockwise(ops[e]) && ops[e].kind == AtomOp::PostForce) ++e;
      const auto t0 = clock::now();
      for (std::size_t k = a; k < e; ++k) run_op(sim, ops[k], t, lo, hi);
      *fix_s += std::chrono::duration<double>(clock::now() - t0).count();
    } else {
      run_op(sim, ops[a], t, lo, hi);
    }
    a = e;
  }
}
}  // namespace

void run_ops_on_range(Simulation& sim, const std::vector<AtomOp>& ops, int t, std::size_t lo, std::size_t hi,
                      double* fix_seconds) {
  std::size_t split = 0;  // ops of phase 0 come first
  while (split < ops.size() && ops[split].phase == 0) ++split;
  run_phase(sim, ops, 0, split, t, lo, hi, fix_seconds);
  if (split == ops.size()) return;
  atom_pass_barrier();  // phase 1 reads what every thread's phase 0 wrote
  run_phase(sim, ops, split, ops.size(), t, lo, hi, fix_seconds);
}

// Stage::calls of an op list.
static std::vector<std::pair<Fix*, FixHook>> fixes_called(const std::vector<AtomOp>& ops) {
  std::vector<std::pair<Fix*, FixHook>> out;
  for (const AtomOp& op : ops) {
    if (!calls_fix(op)) continue;
    auto it = std::find_if(out.begin(), out.end(), [&](auto& p) { return p.first == op.fix; });
    if (it == out.end()) out.emplace_back(op.fix, hook_of(op));
    else it->second = hook_of(op);
  }
  return out;
}

void begin_ops(const Stage& s) {
  for (auto& [f, h] : s.calls) f->begin(h);
}

void end_ops(const Stage& s) {
  for (auto& [f, h] : s.calls) f->end(h);
}

void run_atom_ops(Simulation& sim, const Stage& s) {
  begin_ops(s);
  sim.atoms.for_ranges([&](int t, std::size_t lo, std::size_t hi) { run_ops_on_range(sim, s.ops, t, lo, hi); });
  end_ops(s);
}

// ---- The plain plan and its rewrites.

StepPlan plain_plan(const Simulation& sim) {
  StepPlan p;
  auto hooks = [&](FixHook h) {
    for (auto& f : sim.fixes)
      if (f->hooks & h) {
        Stage s{Stage::Hook};
        s.fix = f.get(), s.hook = h;
        p.stages.push_back(s);
      }
  };
  hooks(INITIAL_INTEGRATE);
  hooks(POST_INTEGRATE);
  p.stages.push_back(Stage{Stage::Rebuild});
  hooks(PRE_FORCE);
  Stage clear{Stage::AtomPass};
  clear.ops.push_back(AtomOp{AtomOp::ClearForces});
  p.stages.push_back(clear);
  p.stages.push_back(Stage{Stage::ForcePass});
  hooks(POST_FORCE);
  hooks(FINAL_INTEGRATE);
  hooks(END_OF_STEP);
  p.stages.push_back(Stage{Stage::Check});
  p.stages.push_back(Stage{Stage::Output});
  return p;
}

namespace {
std::vector<Stage*> hook_stages(StepPlan& p, FixHook h) {
  std::vector<Stage*> out;
  for (Stage& s : p.stages)
    if (s.kind == Stage::Hook && s.hook == h) out.push_back(&s);
  return out;
}

Stage* find_pass(StepPlan& p, Stage::Kind kind, When when) {
  for (Stage& s : p.stages)
    if (s.kind == kind && s.when == when) return &s;
  return nullptr;
}

bool two_phase_integrator(const StepPlan& p) { return p.integrator->two_phase_tasks & INITIAL_INTEGRATE; }

// The integrator's first half as ops (a two-phase one: both phases).
void add_first_half(std::vector<AtomOp>& ops, Fix* f) {
  ops.push_back(AtomOp{AtomOp::FirstHalf, f, 0});
  if (f->two_phase_tasks & INITIAL_INTEGRATE) ops.push_back(AtomOp{AtomOp::FirstHalf, f, 1});
}
}  // namespace

// One integrator holding both halves as atom tasks (not one that prescribes motion
// by the step's time: its first half cannot run ahead in the last step's pass):
// its first half runs as an atom pass; on quiet steps its second half waits for that pass of the next step (only
// the bodies' phase: the first half places the members again), and, when no fix runs
// between it and the force pass, the pass zeroes the forces too.
StepPlan fuse(StepPlan p) {
  auto first = hook_stages(p, INITIAL_INTEGRATE), last = hook_stages(p, FINAL_INTEGRATE);
  if (first.size() != 1 || last.size() != 1 || first[0]->fix != last[0]->fix) return p;
  Fix* f = first[0]->fix;
  constexpr unsigned kBoth = INITIAL_INTEGRATE | FINAL_INTEGRATE;
  if ((f->atom_tasks & kBoth) != kBoth || f->traits.prescribes_motion) return p;
  p.integrator = f;
  p.defers = true;
  last[0]->when = When::Loud;
  const bool clear = hook_stages(p, POST_INTEGRATE).empty() && hook_stages(p, PRE_FORCE).empty();
  Stage after_loud{Stage::AtomPass, When::AfterLoud}, after_quiet{Stage::AtomPass, When::AfterQuiet};
  add_first_half(after_loud.ops, f);
  if ((f->atom_tasks & FINAL_THEN_INITIAL) && !(f->two_phase_tasks & kBoth)) {
    after_quiet.ops.push_back(AtomOp{AtomOp::BothHalves, f, 0});
  } else {
    after_quiet.ops.push_back(AtomOp{AtomOp::SecondHalf, f, 0});
    add_first_half(after_quiet.ops, f);
  }
  const int phase = after_loud.ops.back().phase;
  for (Stage* s : {&after_loud, &after_quiet})
    if (clear) s->ops.push_back(AtomOp{AtomOp::ClearForces, nullptr, phase});
  const auto at = p.stages.begin() + (first[0] - p.stages.data());
  p.stages.insert(p.stages.erase(at), {after_loud, after_quiet});
  if (clear)
    p.stages.erase(std::find_if(p.stages.begin(), p.stages.end(), [](const Stage& s) {
      return s.kind == Stage::AtomPass && s.when == When::Always && s.ops.size() == 1 &&
             s.ops[0].kind == AtomOp::ClearForces;
    }));
  for (Stage& s : p.stages)
    if (s.kind == Stage::Check) s.when = When::Loud;  // a deferred kick: next step's checks see it
  p.rewrites.push_back("fuse");
  return p;
}

// A last post_force fix that only adds m a to every grain (gravity on all) folds into
// the fused first pass on quiet steps: the same additions in the same order. Not into
// a two-phase integrator (its bodies sum members that other threads' ranges hold).
StepPlan fold_gravity(StepPlan p) {
  if (!p.integrator || two_phase_integrator(p)) return p;
  auto post = hook_stages(p, POST_FORCE);
  if (post.empty()) return p;
  const Fix* g = post.back()->fix;
  if (!g->traits.accelerates || g->groupbit != 1u) return p;  // m a on every grain, nothing else
  post.back()->when = When::Loud;
  p.folded = post.back()->fix;
  AtomOp add{AtomOp::AddMassAccel, p.folded};
  std::copy(g->traits.acceleration, g->traits.acceleration + 3, add.accel);
  auto& ops = find_pass(p, Stage::AtomPass, When::AfterQuiet)->ops;
  ops.insert(ops.begin(), add);
  p.rewrites.push_back("fold gravity");
  return p;
}

// When every post_force fix is a single-phase atom task (a two-phase one needs every
// grain's force before its second phase), each thread runs them on its atoms inside
// the force pass as soon as their pair forces are final, and on quiet steps the next
// step's first pass too (single-phase integrators): one parallel region a step.
StepPlan pipeline(StepPlan p, bool has_pair) {
  if (!p.integrator || !has_pair) return p;
  auto post = hook_stages(p, POST_FORCE);
  for (Stage* s : post)
    if (!(s->fix->atom_tasks & POST_FORCE) || (s->fix->two_phase_tasks & POST_FORCE)) return p;
  Stage loud{Stage::ForcePass, When::Loud}, quiet{Stage::ForcePass, When::Quiet};
  for (Stage* s : post) {
    loud.ops.push_back(AtomOp{AtomOp::PostForce, s->fix});
    if (s->when != When::Loud) quiet.ops.push_back(AtomOp{AtomOp::PostForce, s->fix});
  }
  const bool next_first = !two_phase_integrator(p);
  if (next_first) {
    auto after_quiet = std::find_if(p.stages.begin(), p.stages.end(),
                                    [](const Stage& s) { return s.kind == Stage::AtomPass && s.when == When::AfterQuiet; });
    quiet.ops.insert(quiet.ops.end(), after_quiet->ops.begin(), after_quiet->ops.end());
    p.stages.erase(after_quiet);
  }
  p.stages.erase(std::remove_if(p.stages.begin(), p.stages.end(),
                                [](const Stage& s) { return s.kind == Stage::Hook && s.hook == POST_FORCE; }),
                 p.stages.end());
  auto force = std::find_if(p.stages.begin(), p.stages.end(), [](const Stage& s) { return s.kind == Stage::ForcePass; });
  force = p.stages.erase(force);
  if (quiet.ops.size() == loud.ops.size()) {  // nothing folded, nothing for the next step: one stage
    loud.when = When::Always;
    p.stages.insert(force, loud);
  } else {
    p.stages.insert(force, {loud, quiet});
  }
  p.rewrites.push_back(next_first ? "pipeline (post_force and the next first half)" : "pipeline (post_force)");
  return p;
}

// The rebuild check's displacement scan in the pass that last moved the atoms (while
// they are in cache), when no post_integrate fix moves them after it: the pipelined
// quiet force pass, or a two-phase integrator's placing phase.
StepPlan prescan(StepPlan p) {
  if (!p.integrator || !hook_stages(p, POST_INTEGRATE).empty()) return p;
  bool any = false;
  for (Stage& s : p.stages) {
    const bool moves = std::any_of(s.ops.begin(), s.ops.end(), moves_atoms);
    if (!moves) continue;
    if (s.kind == Stage::AtomPass && !two_phase_integrator(p)) continue;  // x stays in cache for the force pass
    s.ops.push_back(AtomOp{AtomOp::Prescan, nullptr, s.ops.back().phase});
    any = true;
  }
  if (any) p.rewrites.push_back("prescan");
  return p;
}

StepPlan build_plan(const Simulation& sim, unsigned mask) {
  StepPlan p = plain_plan(sim);
  if (mask & kFuse) p = fuse(std::move(p));
  if (mask & kFold) p = fold_gravity(std::move(p));
  if (mask & kPipeline) p = pipeline(std::move(p), sim.pair != nullptr);
  if (mask & kPrescan) p = prescan(std::move(p));
  for (Stage& s : p.stages) s.calls = fixes_called(s.ops);
  return p;
}

// ---- What `info plan` prints.

std::string AtomOp::describe() const {
  const std::string ph = phase ? " (phase 2)" : "";
  switch (kind) {
    case AddMassAccel: return "add m a of " + fix_name(fix, POST_FORCE);
    case SecondHalf: return fix_name(fix, FINAL_INTEGRATE) + ": second half kick" + ph;
    case FirstHalf: return fix_name(fix, INITIAL_INTEGRATE) + ": first half kick and drift" + ph;
    case BothHalves: return fix_name(fix, FINAL_THEN_INITIAL) + ": second half kick, first half kick and drift (one loop)";
    case ClearForces: return "clear forces";
    case PostForce: return fix_name(fix, POST_FORCE) + ": post_force";
    case Prescan: return "scan displacements for the rebuild check";
  }
  return "?";
}

std::string Stage::describe() const {
  std::string s = when_name(when);
  auto list = [&] {
    std::string o;
    for (const AtomOp& op : ops) o += (o.empty() ? "" : "; ") + op.describe();
    return o;
  };
  switch (kind) {
    case Hook: return s + hook_name(hook) + ": " + fix_name(fix, hook);
    case AtomPass: return s + "atom pass: " + list();
    case Rebuild: return s + "neighbour list check (rebuild when due)";
    case ForcePass: return s + "force pass" + (ops.empty() ? "" : ", then on each range: " + list());
    case Check: return s + "stop on a non-finite velocity";
    case Output: return s + "thermo and dumps when due";
  }
  return s;
}

std::string StepPlan::describe() const {
  std::string rw;
  for (const auto& r : rewrites) rw += (rw.empty() ? "" : ", ") + r;
  std::string out = "Step plan (" + (rw.empty() ? std::string("plain") : "rewrites: " + rw) + "):";
  for (std::size_t k = 0; k < stages.size(); ++k) {
    char n[32];
    std::snprintf(n, sizeof n, "\n  %2zu. ", k + 1);
    out += n + stages[k].describe();
  }
  if (defers)
    out += "\n  (a quiet step has no thermo, dump or end_of_step fix due and is not the run's last: its second "
           "half kick runs in the next step's first pass)";
  return out;
}

}  // namespace sable
