#pragma once
// The whole engine state (LAMMPS' `LAMMPS` object): atoms, box, neighbour
// list, styles, variables, output. Every style holds a reference to it.
#include <array>
#include <chrono>
#include <cstdio>
#include <map>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include "core/engine/atoms.h"
#include "core/engine/comm.h"
#include "core/engine/compute.h"
#include "core/engine/domain.h"
#include "core/io/dump.h"
#include "core/engine/fix.h"
#include "core/engine/group.h"
#include "core/engine/neighbor.h"
#include "core/engine/pair.h"
#include "core/geometry/region.h"
#include "core/engine/step_plan.h"

namespace sable {

class Input;
class Variables;
class Thermo;

// What the time-step check does when dt exceeds a bound.
enum class StepPolicy { Stop, Accept };

struct Lattice {
  std::string style = "none";
  double a[3] = {1, 1, 1};  // spacings
  std::vector<std::array<double, 3>> basis;  // fractional
};

class Simulation {
 public:
  Simulation();
  ~Simulation();

  Comm comm;  // this process among the run's ranks, the processor grid (core/engine/comm.h)
  Atoms atoms;
  Domain domain;
  Neighbor neighbor;
  Groups groups;
  Lattice lattice;
  std::unique_ptr<Pair> pair;
  std::vector<std::unique_ptr<Fix>> fixes;
  std::vector<std::unique_ptr<Compute>> computes;
  std::vector<std::unique_ptr<Dump>> dumps;
  std::map<std::string, std::unique_ptr<Region>> regions;
  std::unique_ptr<Variables> variables;
  std::unique_ptr<Thermo> thermo;
  Input* input = nullptr;

  double dt = 1e-5;
  bool dt_set = false;
  DeckLocation dt_where;  // the `timestep` line, for stability messages
  std::string dt_line = "(default time step)";
  StepPolicy step_policy = StepPolicy::Stop;
  long step = 0;          // current time step
  // Bumped when a fix or the pair style is added, replaced or removed: computes
  // evaluated between runs re-init first (Compute::ready), never reading a gone fix.
  long config_epoch = 0;
  double time = 0.0;      // simulated time
  long run_first = 0, run_last = 0;  // bounds of the current/last run
  bool newton = false;
  std::string units = "si";
  bool soft_particles = false;  // `soft_particles yes`: youngsModulus below LIGGGHTS' 5e6 allowed
  bool lost_ignore = false;
  double progress_every_s = 10.0;  // wall seconds between progress lines
  bool progress = true;            // -progress on|off: those lines (screen only, never the log)

  // What read_restart holds until the deck declares the styles that own it again
  // (core/io/restart.h): pair history, injected into the pair's ContactStore at the
  // next setup, and fix states, handed to a fix defined with the same ID and style.
  struct RestartPending {
    std::string file;                   // for messages
    std::string pair_model;             // PairGran::describe() of the writer
    std::vector<HistorySlot> slots;     // history slots of the stored contacts
    HistoryStore contacts;
    struct FixState {
      std::string style, bytes;
    };
    std::map<std::string, FixState> fix_states;  // by fix ID
  } restart;

  // Output to screen and log (print_to: to either or both).
  void print(const std::string& line);
  void print_to(const std::string& line, bool to_screen, bool to_log);
  void warn(const std::string& line);
  // The first time only (a note that each style using it would repeat).
  void print_once(const std::string& line);
  std::set<std::string> printed_once;
  FILE* screen = stdout;
  FILE* logfile = nullptr;
  void open_log(const std::string& path);  // "none" closes

  // Lookups whose errors say what was expected.
  Fix* find_fix(const std::string& id) const;
  Compute* find_compute(const std::string& id) const;
  Region* find_region(const std::string& id) const;
  template <class T>
  T* find_fix_style() const {
    for (auto& f : fixes)
      if (auto* p = dynamic_cast<T*>(f.get())) return p;
    return nullptr;
  }
  // The rigid body atom i belongs to, over every fix with bodies: its set and its
  // number there; {nullptr, -1} for a free grain.
  std::pair<const RigidBodies*, int> body_of(std::size_t i) const;
  void add_fix(std::unique_ptr<Fix> f);
  void remove_fix(const std::string& id);
  void add_compute(std::unique_ptr<Compute> c);
  void remove_compute(const std::string& id);

  // Run N steps (the `run` command).
  void run(long nsteps);
  // Ends the current run after this step, with its thermo line (fix halt). Only
  // from end_of_step: its steps keep no half kick deferred. `why` non-empty:
  // the deck's later runs are skipped too, saying why (LAMMPS' error soft).
  void request_stop(const std::string& why = "");
  // Set up for a run without stepping (forces, lists); used by write_dump etc.
  void setup();
  // Flush every output (before an error stops the run).
  void flush_outputs();
  double wall_seconds() const;

  // Time-step bounds now (what LIGGGHTS' fix check/timestep/gran reports).
  struct StepBounds {
    double rayleigh = 0, hertz = 0, speed = 0, skin_ratio = 0;
    bool valid = false;
  };
  StepBounds step_bounds(double vmin = 0.0) const;

  // The rewrites the step plan may take (core/engine/step_plan.h; tests turn each off);
  // `info plan` prints each run's plan.
  unsigned plan_rewrites = kAllRewrites;
  bool print_plan = false;
  // Let contacts run the 2D and no-rotation kernels where the scene allows
  // (setup: Atoms::plane_2d, Atoms::rotation); off (`contact_kernels full`):
  // always the full 3D kernel, the same physics (benchmarks, checks).
  bool reduced_kernels = true;
  long fused_steps = 0;     // steps whose final half kick ran in the next initial pass (run())
  long folded_steps = 0;    // ... and whose gravity pass went into it too
  long cleared_steps = 0;   // steps whose forces the fused initial pass zeroed (run())
  // Time split of the last run (seconds).
  struct Timers {
    double pair = 0, neigh = 0, integrate = 0, fixes = 0, output = 0, total = 0;
    double comm = 0;  // several ranks: messages (exchange, borders, forward), out of neigh and pair
  } timers;

 private:
  // The time-step guard (at setup; in a run that starts without grains, at
  // the first step that has some: insertion). mid_run: the summary line goes
  // to the screen only, the log's thermo table stays unbroken.
  void stability_check(bool mid_run = false);
  bool stability_pending_ = false;
  void check_atoms(bool positions);  // NaN velocities (and positions): stop with step, atom, cause
  void force_and_history();
  void rebuild_if_due();
  // Several ranks: exchange, ghosts and the list at a rebuild every rank takes at once.
  void rebuild_decomposed();
  void forward_ghosts();
  std::string rank_balance() const;
  void choose_kinematics();  // Atoms::plane_2d and Atoms::rotation for this run
  // Says once per fix which fix keeps the step off the fused, pipelined plan and what that costs.
  void explain_slow_path(const StepPlan& plan);
  bool quiet(long s) const;  // nobody looks at the grains after step s (core/engine/step_plan.h)
  void run_stage(const Stage& s);
  void force_pass(const Stage& s);
  std::set<std::string> slow_path_noted_;
  void claim_restart_leftovers();
  bool stop_ = false;
  std::string skip_runs_;  // why later runs are skipped (request_stop)
  std::chrono::steady_clock::time_point t0_;
};

}  // namespace sable
