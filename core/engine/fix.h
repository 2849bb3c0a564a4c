#pragma once
// Base of all fixes (LIGGGHTS `fix ID group style args`). A fix overrides the
// hooks it needs and says so in `hooks`, so the step loop calls only those;
// what it is (its traits) it fills in once as data; the roles it may hold
// beyond that are small interfaces: global output (core/engine/global_output.h,
// every fix's base) and rigid bodies (rigid_bodies(), core/engine/rigid_bodies.h).
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "core/engine/global_output.h"
#include "core/input/args.h"
#include "core/engine/threads.h"

namespace sable {

class Simulation;
class RigidBodies;  // core/engine/rigid_bodies.h
class YadeScript;   // core/io/yade_script.h

enum FixHook : unsigned {
  INITIAL_INTEGRATE = 1u << 0,
  POST_INTEGRATE = 1u << 1,
  PRE_FORCE = 1u << 2,
  POST_FORCE = 1u << 3,
  FINAL_INTEGRATE = 1u << 4,
  END_OF_STEP = 1u << 5,
  // Not a hook but a task an integrator may offer: the second half kick of the
  // last step, then the first half kick and drift of this one, on the same atoms
  // in one loop (the bits of the two tasks in a row; the plan's fuse uses it).
  FINAL_THEN_INITIAL = 1u << 6,
};

// The role a fix plays at a hook: a named bundle of hooks and tasks that the
// traits qualify. `info plan` names it; core asks it instead of a style name.
enum class FixRole : unsigned char {
  None,              // pre_force, post_integrate, end_of_step: the fix's own work
  Integrator,        // initial/final_integrate: grains advanced from their forces (nve/sphere)
  RigidBodies,       // the same for whole bodies (rigid_bodies() is set)
  PrescribedMotion,  // the same, the motion imposed from the step's time (traits.prescribes_motion)
  ForceContributor,  // post_force adding to the forces (gravity, addforce, walls, damping)
  Constraint,        // post_force setting or removing force components (traits.constraint)
};
const char* role_name(FixRole r);

// What a fix is, filled in once (constructor, or init for what the deck decides
// later) and read by core instead of asking the fix. Speeds that change during a
// run (Fix::max_speed) stay functions.
struct FixTraits {
  bool constraint = false;         // post_force sets or zeroes force components (freeze, setforce, aveforce, enforce2d)
  bool prescribes_motion = false;  // integrates by the step's time (fix move): the plan keeps it on its own step
  bool freezes_group = false;      // its group's grains count as infinitely heavy in contacts (fix freeze)
  bool keeps_plane = false;        // its post_force never puts force or spin out of a 2D plane
  // May it make a grain turn (integrate or set omega)? If no fix may and every omega
  // is 0 at setup, contacts skip rotation (Atoms::rotation). Unset: if it integrates.
  std::optional<bool> turns_grains;
  // Its post_force only adds m a to each grain of its group (fix gravity): the time
  // step's speed estimate, multisphere's body gravity and the plan's folding read a.
  bool accelerates = false;
  double acceleration[3] = {0, 0, 0};
  double acceleration_norm() const;  // |a|; 0 when it does not accelerate
};

class Fix : public GlobalOutput {
 public:
  Fix(Simulation& sim, const Args& args);  // args: ID group style ...
  virtual ~Fix() = default;
  Fix(const Fix&) = delete;
  Fix& operator=(const Fix&) = delete;

  Simulation& sim;
  Args args;
  std::string id, style;
  int group = 0;           // group index
  std::uint32_t groupbit = 1;
  unsigned hooks = 0;
  int nevery = 1;          // end_of_step period
  FixTraits traits;
  FixRole role(FixHook h) const;  // at hook h (None where it holds no hook h)

  virtual void init() {}        // before each run (after all commands are known)
  virtual void setup() {}       // after the first force evaluation of a run
  // The hooks: a fix overrides those it needs, or declares them as atom_tasks
  // (below), which the defaults then run on every thread's atom range.
  virtual void initial_integrate() { run_task(INITIAL_INTEGRATE); }
  virtual void post_integrate() {}
  virtual void pre_force() {}
  virtual void post_force() { run_task(POST_FORCE); }
  virtual void final_integrate() { run_task(FINAL_INTEGRATE); }
  virtual void end_of_step() {}
  virtual void post_run() {}
  // `fix_modify` keywords this fix understands; return false to reject.
  virtual bool modify_param(const Args&, std::size_t&) { return false; }

  // The rigid-body role: set by a fix that moves grains as members of bodies.
  virtual const RigidBodies* rigid_bodies() const { return nullptr; }

  // sable --export-yade: this fix's part of the YADE script, from its parsed
  // members (core/io/yade_script.h). A style with no translation refuses at its line.
  virtual void export_yade(YadeScript&) const {
    args.fail_line("export-yade: fix style '" + style + "' is not translated to YADE");
  }

  // Restart state (write_restart / read_restart). A fix whose behaviour depends on
  // its history (insertion counters, random streams) appends that state to `out`
  // and returns true; after read_restart, a fix defined again with the same ID and
  // style gets the same bytes in read_state() (pack them with core/io/restart.h).
  virtual bool write_state(std::string& /*out*/) const { return false; }
  virtual void read_state(const std::string& /*in*/) {}

  // ---- Per-atom tasks: what a hook does, declared; the step plan runs it.
  // A hook whose work treats every atom on its own is named in `atom_tasks`
  // and written as range(): core calls begin(hook) serially, range() on each
  // thread's atoms and end(hook) serially. The step plan (core/engine/step_plan.h)
  // composes these: an integrator's INITIAL_INTEGRATE task is its first half
  // kick and drift, its FINAL_INTEGRATE task the second half kick, and the
  // plan may run them in one pass with other tasks (the force clear, a folded
  // gravity, the rebuild check's scan) or inside the force pass. Each atom sees
  // the operations of the plain plan in the same order: the same bits for any
  // thread count and any rewrite. A fix writes no threading: a sum over its
  // atoms is core's AtomSum (core/engine/block_sum.h), the same bits for any split.
  unsigned atom_tasks = 0;  // FixHook bits
  // Tasks (of atom_tasks) in two phases: range() runs with phase 0 on every
  // thread's range, then, once all have finished, with phase 1. For work that
  // first gathers over atoms of other ranges (rigid bodies: each body summed and
  // advanced by one thread, then every member placed from its body; fix aveforce:
  // the group's force summed, then every member set from the total). Phase 0 of
  // the second half kick must leave the bodies ready for the first half: the plan
  // may skip its phase 1 (placing the members) when the first half follows.
  unsigned two_phase_tasks = 0;  // FixHook bits
  struct AtomRange {
    int thread = 0;
    std::size_t lo = 0, hi = 0;
    int phase = 0;  // two_phase_tasks: 0, then 1
  };
  virtual void begin(FixHook) {}
  virtual void range(FixHook, const AtomRange&) {}
  virtual void end(FixHook) {}
  // Runs the task declared for hook h (if any) over all atoms: begin, the ranges, end.
  void run_task(FixHook h);

  // The fixes defined after this one whose post_force may add force out of the
  // plane (not keeps_plane): their force comes after this fix has acted.
  std::vector<const Fix*> later_force_fixes() const;

  // Fastest speed this fix imposes (moving walls), for the time-step check: a
  // function, as it may change during a run (a wiggle, a mover's farthest grain).
  virtual double max_speed() const { return 0.0; }
};

}  // namespace sable
