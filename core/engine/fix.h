#pragma once
// Base of all fixes (LIGGGHTS `fix ID group style args`). A fix overrides the
// hooks it needs and says so in `hooks`, so the step loop calls only those.
#include <cstddef>
#include <string>

#include "core/input/args.h"
#include "core/engine/threads.h"

namespace sable {

class Simulation;
class YadeScript;  // tools/yade_script.h

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

class Fix {
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

  // Global outputs referenced as f_ID and f_ID[i] (1-based).
  int scalar_flag = 0, vector_size = 0;
  virtual double compute_scalar() { return 0.0; }
  virtual double compute_vector(int /*i*/) { return 0.0; }
  // A global array, f_ID[i][j] (1-based; LAMMPS' fix rigid: one row per body).
  int array_rows = 0, array_cols = 0;
  virtual double compute_array(int /*i*/, int /*j*/) { return 0.0; }

  // sable --export-yade: this fix's part of the YADE script, from its parsed
  // members (tools/yade_script.h). A style with no translation refuses at its line.
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
  // thread count and any rewrite. A fix writes no threading.
  unsigned atom_tasks = 0;  // FixHook bits
  // Tasks (of atom_tasks) in two phases: range() runs with phase 0 on every
  // thread's range, then, once all have finished, with phase 1. For work that
  // first gathers over atoms of other ranges (rigid bodies: each body summed and
  // advanced by one thread, then every member placed from its body). Phase 0 of
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
  // A POST_FORCE task that only adds m a to every grain (gravity on all) gives
  // a here: the plan may fold it into the integrator's pass (fold_gravity).
  virtual bool fold_acceleration(double /*a*/[3]) const { return false; }

  // Rigid bodies: the body of atom i (-1: in none of this fix's bodies) and a
  // body's summed force (as the last step applied it), for per-body statistics.
  // Bodies by the deck's numbers (from 0; f_ID row - 1), stable over the run.
  virtual int body_of(std::size_t /*i*/) const { return -1; }
  // An integrator of rigid bodies: its group's grains move only as members of its bodies.
  virtual bool body_integrator() const { return false; }
  virtual const double* body_force(int /*body*/) const { return nullptr; }
  // Bodies whose member grains carry the body's mass (fix multisphere): true and
  // their 1/2 M vcm^2, which thermo ke counts once per body in place of the members'.
  virtual bool body_kinetic_energy(double& /*ke*/) const { return false; }

  // Grains of this fix's group count as infinitely heavy in contacts (LIGGGHTS fix freeze).
  virtual bool freezes_group() const { return false; }
  // A post_force that never puts force or spin out of a 2D plane (may follow enforce2d).
  virtual bool keeps_plane() const { return false; }
  // May this fix make a grain turn (integrate or set omega)? If no fix does and
  // every omega is 0 at setup, contacts skip rotation (Atoms::rotation). Any
  // integrator is assumed to, unless it says otherwise.
  virtual bool turns_grains() const { return (hooks & (INITIAL_INTEGRATE | FINAL_INTEGRATE)) != 0; }

  // Runs the task declared for hook h (if any) over all atoms: begin, the ranges, end.
  void run_task(FixHook h);

  // Fastest speed this fix imposes (moving walls), for the time-step check.
  virtual double max_speed() const { return 0.0; }
  // Acceleration this fix imposes on free grains (gravity), for the speed estimate.
  virtual double acceleration() const { return 0.0; }
};

}  // namespace sable
