// fix ID group check/timestep/gran N fraction_r fraction_h [warn yes|no] [error yes|no] [vmax V]
// LIGGGHTS' periodic time-step report. sable already checks once at setup;
// this fix repeats the check every N steps and warns (or stops) like LIGGGHTS.
#include <cstdio>

#include "core/engine/error.h"
#include "core/engine/simulation.h"
#include "core/input/style_registry.h"

namespace sable {

class FixCheckTimestepGran : public Fix {
 public:
  void export_yade(YadeScript&) const override {}  // --export-yade: a check of sable's step only
  FixCheckTimestepGran(Simulation& s, const Args& a) : Fix(s, a) {
    hooks = END_OF_STEP;
    nevery = static_cast<int>(a.integer(4, "the check period N"));
    if (nevery < 1) a.fail(4, "a period >= 1");
    fr_ = a.num(5, "the Rayleigh fraction");
    fh_ = a.num(6, "the Hertz fraction");
    for (std::size_t i = 7; i < a.size(); i += 2) {
      if (a[i] == "warn") warn_ = a.yes_no(i + 1, "yes or no");
      else if (a[i] == "error") error_ = a.yes_no(i + 1, "yes or no");
      else if (a[i] == "vmax") vmax_ = a.num(i + 1, "a speed");
      else a.fail(i, "warn, error or vmax");
    }
    vector_size = 2;
  }
  void end_of_step() override {
    const auto b = sim.step_bounds(vmax_);
    if (!b.valid) return;
    rf_ = sim.dt / b.rayleigh;
    hf_ = sim.dt / b.hertz;
    if (rf_ <= fr_ && hf_ <= fh_ && b.skin_ratio >= 1.0) return;
    char buf[256];
    std::snprintf(buf, sizeof buf, "step %ld: time step is %.3g of the Rayleigh time and %.3g of the Hertz time, skin ratio %.3g (fix %s)",
                  sim.step, rf_, hf_, b.skin_ratio, id.c_str());
    if (error_) fail(buf);
    if (warn_) sim.warn(buf);
  }
  double compute_vector(int i) override { return i == 1 ? rf_ : hf_; }

 private:
  double fr_ = 0.1, fh_ = 0.1, vmax_ = 0.0, rf_ = 0, hf_ = 0;
  bool warn_ = true, error_ = false;
};

SABLE_FIX("check/timestep/gran", FixCheckTimestepGran);

}  // namespace sable
