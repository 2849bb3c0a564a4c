// fix ID group check/timestep/gran N fraction_r fraction_h [warn yes|no] [error yes|no] [vmax V]
// LIGGGHTS 3.8's periodic time-step report, its estimates and its warnings: every N steps
// (at end of step) a WARNING for each limit the step exceeds, the run going on; with
// `error yes` the run stops there instead. It stops nothing by itself: sable's own guard
// (Simulation::stability_check, at setup) is what refuses an unsafe step.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>

#include "core/engine/error.h"
#include "core/engine/global_property.h"
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
      else if (a[i] == "vmax") vmax_user_ = a.num(i + 1, "a speed");
      else a.fail(i, "warn, error or vmax");
    }
    vector_size = 3;  // f_ID[1..3]: dt / Rayleigh time, dt / Hertz time, v_rel dt / skin (LIGGGHTS' order)
  }

  void init() override {
    Y_ = GlobalProperty::find(sim, "youngsModulus");
    nu_ = GlobalProperty::find(sim, "poissonsRatio");
    if (!sim.pair || !Y_ || !nu_)
      args.fail_line("fix check/timestep/gran only works with pair_style gran and the properties youngsModulus and "
                     "poissonsRatio (LIGGGHTS requires them too)");
  }

  void end_of_step() override {
    estimate();
    const double dt = sim.dt, skin = sim.neighbor.skin;
    rf_ = dt / rayleigh_;
    hf_ = dt / hertz_;
    sf_ = vrel_ * dt / skin;
    if (!warn_ && !error_) return;
    char buf[256];
    // LIGGGHTS' four tests and texts, in its order.
    if (rf_ > fr_) {
      std::snprintf(buf, sizeof buf, "time-step is %f %% of rayleigh time", 100 * rf_);
      report(buf);
    }
    if (hf_ > fh_) {
      std::snprintf(buf, sizeof buf, "time-step is %f %% of hertz time", 100 * hf_);
      report(buf);
    }
    if (sf_ > 1) {
      std::snprintf(buf, sizeof buf,
                    "time step too large or skin too small - particles may relatively travel a distance of %f per "
                    "time-step, but skin is %f",
                    vrel_ * dt, skin);
      report(buf);
    }
    if (vrel_ * dt > rmin_)
      report("time step way too large - particles relatively move further than the minimum radius in one step");
  }
  double compute_vector(int i) override { return i == 1 ? rf_ : i == 2 ? hf_ : sf_; }

 private:
  // LIGGGHTS' estimates over the group: the smallest Rayleigh time; the relative speed
  // max(2 v_max, v_max + v_wall); the Hertz time of each grain hitting itself at that speed,
  // with LIGGGHTS' m_eff = m (the grain's whole mass), r_eff = r/2 and Y_eff of its type pair.
  void estimate() {
    const Atoms& a = sim.atoms;
    rayleigh_ = 1e6;
    rmin_ = 1e6;
    double v2 = 0.0;
    for (std::size_t i = 0; i < a.n; ++i) {
      if (!(a.mask[i] & groupbit)) continue;
      rayleigh_ = std::min(rayleigh_, sim.pair->rayleigh_time(i));
      rmin_ = std::min(rmin_, a.radius[i]);
      const double* v = &a.v[3 * i];
      v2 = std::max(v2, v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    }
    const double vmax = std::max(std::sqrt(v2), vmax_user_);
    double vwall = 0.0;  // LIGGGHTS counts moving meshes; sable every moving wall or mesh
    for (auto& f : sim.fixes) vwall = std::max(vwall, f->max_speed());
    vrel_ = std::max(2.0 * vmax, vmax + vwall);
    hertz_ = 1e6;  // LIGGGHTS' value when nothing moves
    if (vrel_ == 0.0) return;
    for (std::size_t i = 0; i < a.n; ++i) {
      if (!(a.mask[i] & groupbit)) continue;
      const int t = a.type[i] - 1;
      const double Y = Y_->values.at(t), nu = nu_->values.at(t);
      const double yeff = Y / (2.0 * (1.0 - nu * nu));
      const double m = a.rmass[i], reff = a.radius[i] / 2.0;
      hertz_ = std::min(hertz_, 2.87 * std::pow(m * m / (reff * yeff * yeff * vrel_), 0.2));
    }
  }

  // LIGGGHTS: error->warning (each check, the run goes on) or, with `error yes`, the fix's error.
  void report(const std::string& what) {
    const std::string where = " (fix " + id + " check/timestep/gran, step " + std::to_string(sim.step) + ")";
    if (error_) args.fail_line(what + "; stopped because of 'error yes'" + where);
    sim.warn(what + where);
  }

  const GlobalProperty *Y_ = nullptr, *nu_ = nullptr;
  double fr_ = 0.1, fh_ = 0.1, vmax_user_ = 0.0;
  double rayleigh_ = 0, hertz_ = 0, rmin_ = 0, vrel_ = 0;
  double rf_ = 0, hf_ = 0, sf_ = 0;
  bool warn_ = true, error_ = false;
};

SABLE_FIX("check/timestep/gran", FixCheckTimestepGran);

}  // namespace sable
