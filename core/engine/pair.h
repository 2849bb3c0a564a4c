#pragma once
// Base of pair styles (`pair_style gran model ... tangential ...`).
#include <string>

#include "core/input/args.h"
#include "core/engine/threads.h"

namespace sable {

class Simulation;
class ContactStore;
class YadeScript;  // core/io/yade_script.h

class Pair {
 public:
  Pair(Simulation& sim, const Args& args) : sim(sim), args(args) {}
  virtual ~Pair() = default;
  Simulation& sim;
  Args args;
  virtual void coeff(const Args& args) = 0;   // pair_coeff
  virtual void init() = 0;                    // derive per-type tables, check properties
  virtual void compute() = 0;                 // add contact forces and torques
  // compute(), then tail(t, lo, hi) on each thread range of Atoms::split, run
  // by the thread that computed the range's forces as soon as they are final:
  // per-atom work that follows the force pass stays on the core whose cache
  // holds those atoms, with no wait for the other threads in between. The
  // default runs compute() and then the ranges.
  virtual void compute_then(const RangeTail& tail);
  virtual ContactStore* history() { return nullptr; }
  // Shortest contact duration for the time-step check, for atoms i and j touching at speed v.
  virtual double contact_time(std::size_t i, std::size_t j, double v) const = 0;
  // Same for atom i against a wall of type wall_type.
  virtual double rayleigh_time(std::size_t i) const = 0;
  virtual std::string describe() const = 0;
  // sable --export-yade: the contact law as YADE materials and laws (core/io/yade_script.h).
  virtual void export_yade(YadeScript&) const { args.fail(1, "gran model ... (export-yade)"); }
};

}  // namespace sable
