#pragma once
// Base of pair styles (`pair_style gran model ... tangential ...`).
#include <string>

#include "core/args.h"

namespace sable {

class Simulation;
class ContactStore;

class Pair {
 public:
  Pair(Simulation& sim, const Args& args) : sim(sim), args(args) {}
  virtual ~Pair() = default;
  Simulation& sim;
  Args args;
  virtual void coeff(const Args& args) = 0;   // pair_coeff
  virtual void init() = 0;                    // derive per-type tables, check properties
  virtual void compute() = 0;                 // add contact forces and torques
  virtual ContactStore* history() { return nullptr; }
  // Shortest contact duration for the time-step check, for atoms i and j touching at speed v.
  virtual double contact_time(std::size_t i, std::size_t j, double v) const = 0;
  // Same for atom i against a wall of type wall_type.
  virtual double rayleigh_time(std::size_t i) const = 0;
  virtual std::string describe() const = 0;
};

}  // namespace sable
