#pragma once
// Base of all fixes (LIGGGHTS `fix ID group style args`). A fix overrides the
// hooks it needs and says so in `hooks`, so the step loop calls only those.
#include <string>

#include "core/args.h"

namespace sable {

class Simulation;

enum FixHook : unsigned {
  INITIAL_INTEGRATE = 1u << 0,
  POST_INTEGRATE = 1u << 1,
  PRE_FORCE = 1u << 2,
  POST_FORCE = 1u << 3,
  FINAL_INTEGRATE = 1u << 4,
  END_OF_STEP = 1u << 5,
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
  virtual void initial_integrate() {}
  virtual void post_integrate() {}
  virtual void pre_force() {}
  virtual void post_force();    // ranged fixes (below): prepare, every thread range, finish
  virtual void final_integrate() {}
  virtual void end_of_step() {}
  virtual void post_run() {}
  // `fix_modify` keywords this fix understands; return false to reject.
  virtual bool modify_param(const Args&, std::size_t&) { return false; }

  // Global outputs referenced as f_ID and f_ID[i] (1-based).
  int scalar_flag = 0, vector_size = 0;
  virtual double compute_scalar() { return 0.0; }
  virtual double compute_vector(int /*i*/) { return 0.0; }

  // Restart state (write_restart / read_restart). A fix whose behaviour depends on
  // its history (insertion counters, random streams) appends that state to `out`
  // and returns true; after read_restart, a fix defined again with the same ID and
  // style gets the same bytes in read_state() (pack them with core/restart.h).
  virtual bool write_state(std::string& /*out*/) const { return false; }
  virtual void read_state(const std::string& /*in*/) {}

  // Step fusion (Simulation::run). An integrator that can_fuse() is told, step
  // by step, to run last step's deferred final half at the start of its initial
  // pass (fuse.final: nothing looked at the atoms in between) and to zero forces
  // and torques at its end (fuse.clear: nothing reads them before the force
  // pass). Either way the results are those of the separate passes, bit for bit.
  virtual bool can_fuse() const { return false; }
  struct Fusion {
    bool final = false, clear = false;
    // With final: last step's gravity pass was skipped; add rmass * accel to
    // each force before using it (what that pass would have stored).
    const double* accel = nullptr;
  } fuse;
  // A post_force that does nothing but add m a to the force of every atom
  // (gravity on group all) gives a here. As the last post_force fix, on
  // steps whose final half kick is deferred, its pass goes into the
  // integrator's (Fusion::accel): one pass over the grains fewer.
  virtual bool uniform_acceleration(double /*a*/[3]) const { return false; }

  // Pipelining (Simulation::run): a post_force that treats every atom on its
  // own says post_force_ranged(); the run may then call post_force_prepare()
  // serially, post_force_range(t, lo, hi) inside the force pass on each
  // thread's atoms as soon as their pair forces are final
  // (Pair::compute_then), and post_force_finish() serially after it: the same
  // additions to each atom, in the same order, as post_force().
  virtual bool post_force_ranged() const { return false; }
  virtual void post_force_prepare() {}
  virtual void post_force_range(int /*t*/, std::size_t /*lo*/, std::size_t /*hi*/) {}
  virtual void post_force_finish() {}
  // A fusing integrator's initial pass (with the `fuse` settings) on the atoms
  // [lo, hi) only, run there too on steps whose final half kick is deferred.
  virtual void initial_integrate_range(int /*t*/, std::size_t /*lo*/, std::size_t /*hi*/) {}

  // Fastest speed this fix imposes (moving walls), for the time-step check.
  virtual double max_speed() const { return 0.0; }
  // Acceleration this fix imposes on free grains (gravity), for the speed estimate.
  virtual double acceleration() const { return 0.0; }
};

}  // namespace sable
