#pragma once
// Base of computes (LIGGGHTS `compute ID group style args`). Evaluated lazily:
// only when a thermo column, dump, variable or fix asks, and once per step.
#include <string>
#include <vector>

#include "core/engine/global_output.h"
#include "core/input/args.h"

namespace sable {

class Simulation;
class YadeScript;  // core/io/yade_script.h

class Compute : public GlobalOutput {
 public:
  Compute(Simulation& sim, const Args& args);
  virtual ~Compute() = default;
  Compute(const Compute&) = delete;
  Compute& operator=(const Compute&) = delete;

  Simulation& sim;
  Args args;
  std::string id, style;
  int group = 0;
  std::uint32_t groupbit = 1;

  virtual void init() {}

  // Global scalar c_ID and vector c_ID[i]: GlobalOutput's scalar_flag,
  // vector_size, compute_scalar() and compute_vector(i) (computes have no arrays).
  double global(int index, int /*col*/ = 0) override { return index ? vector(index) : scalar(); }
  // per-atom: ncols == 0 for a vector (one value per atom), else columns
  bool peratom_flag = false;
  int peratom_cols = 0;
  virtual void compute_peratom() {}
  std::vector<double> peratom;  // n * max(1, peratom_cols)
  // local (per contact): rows x local_cols
  bool local_flag = false;
  int local_cols = 0;
  std::vector<std::string> local_names;
  virtual void compute_local() {}
  std::vector<double> local;  // rows * local_cols
  std::size_t local_rows() const { return local_cols ? local.size() / local_cols : 0; }

  // sable --export-yade: c_ID[k] as a Python expression in the YADE script (k_expr,
  // when given, is the Python for k - 1), and the local rows as one (dump local);
  // "" where the style has no translation (the caller refuses, naming the reference).
  virtual std::string export_yade_term(const YadeScript&, long /*k*/, const Args& /*at*/,
                                             const std::string& /*k_expr*/ = "") const {
    return "";
  }
  virtual std::string export_yade_rows(const YadeScript&) const { return ""; }

  long invoked_step = -1;  // callers use these to avoid recomputing within a step
  // Forget cached values (atoms may have changed between runs at the same step).
  void reset_cache() { invoked_step = scalar_step_ = peratom_step_ = local_step_ = -1; }
  // init() now (a run's setup); the helpers below re-init when fixes or the pair
  // style changed since (a compute evaluated in a variable between runs).
  void init_now();
  // Helpers that recompute only once per step.
  double scalar();
  double vector(int i);
  void peratom_now();
  void local_now();

 private:
  long scalar_step_ = -1, peratom_step_ = -1, local_step_ = -1;
  long init_epoch_ = -1;  // Simulation::config_epoch at the last init()
  void ready();
  double scalar_cache_ = 0.0;
};

}  // namespace sable
