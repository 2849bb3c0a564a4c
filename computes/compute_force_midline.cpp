// compute ID group force/midline x X0 [ylo YLO yhi YHI]
// compute ID group force/midline y Y0 [xlo XLO xhi XHI]
// (sable addition; LIGGGHTS has no such style.) 2D (dimension 2): the normal
// stress across a line, as petit2017 (Petit et al. 2017, Sec. III) gets
// sigma_xx: the force that the grains on one side of the vertical line x = X0
// exert on those on the other side, per length of the line. Over the
// grain-grain contacts with both grains in the group whose branch vector (centre
// to centre, periodic image included) crosses the line (one centre below X0,
// the other at or above; on a periodic axis, the image of the line nearest the
// contact), the x component of the whole contact force (normal + tangential)
// on the grain at or above X0, minus for one below: compression positive. Line
// y = Y0 likewise gives sigma_yy with x and y exchanged. X0, and the bounds, are
// numbers or v_name (equal-style variables, read at each invocation).
//   height  given ylo, yhi (e.g. the piston faces): yhi - ylo, and only
//           contacts whose branch vector meets the line within [ylo, yhi]
//           count. Without them: the group's height, from its lowest grain
//           bottom (y - r) to its highest grain top (y + r): about the piston
//           faces when the group is the grains between the pistons (within a
//           grain diameter at each piston of grains, whose surface is rough;
//           the contacts with the piston grains then do not count: put them in
//           the group and give ylo, yhi to count those). A deck that wants the
//           height between piston centres gives ylo, yhi so. On a periodic y
//           axis the crossing point is wrapped into the box first (ylo, yhi =
//           the box's y bounds: every contact once); give ylo, yhi there.
// Global scalar c_ID = sigma = sum F / height (N/m). Vector c_ID[k]: 1 sigma,
// 2 sum F (N), 3 height, 4 crossing contacts counted, 5 lo, 6 hi used. An empty
// group without bounds: all 0.
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "computes/bound_arg.h"
#include "core/engine/contact_source.h"
#include "core/engine/simulation.h"
#include "core/input/style_registry.h"

namespace sable {

class ComputeForceMidline : public Compute {
 public:
  ComputeForceMidline(Simulation& s, const Args& a) : Compute(s, a) {
    parse(a);
    scalar_flag = true;
    vector_size = 6;
    init();
  }
  void init() override {
    if (sim.domain.dimension != 2) args.fail_line("compute force/midline is 2D: it needs 'dimension 2'");
    pair_ = pair_contacts(sim);
    if (!pair_) args.fail_line("compute force/midline needs 'pair_style gran' defined before it");
  }
  double compute_scalar() override { return compute_vector(1); }
  double compute_vector(int i) override {
    if (invoked_step != sim.step) {
      evaluate();
      invoked_step = sim.step;
    }
    return out_[i - 1];
  }

 private:
  int ax_ = 0;  // the line is x[ax_] = X0; the span runs along the other axis
  BoundArg line_, lo_, hi_;
  bool bounded_ = false;
  ContactSource* pair_ = nullptr;
  ContactRecords rec_;
  double out_[6] = {0, 0, 0, 0, 0, 0};

  void parse(const Args& a) {
    const std::string usage = "compute ID group force/midline x X0 [ylo YLO yhi YHI] (or y Y0 [xlo XLO xhi XHI])";
    a.need(6, usage);
    ax_ = a.choice(4, {"x", "y"}, " (the line x = X0 or y = Y0)");
    line_ = BoundArg::parse(sim, a, 5, "the line's position (a number or v_name)");
    if (a.size() == 6) return;
    const std::string o = ax_ == 0 ? "y" : "x";
    if (a.size() != 10 || a[6] != o + "lo" || a[8] != o + "hi") a.fail(6, "'" + o + "lo LO " + o + "hi HI' or nothing");
    lo_ = BoundArg::parse(sim, a, 7, "a lower bound (a number or v_name)");
    hi_ = BoundArg::parse(sim, a, 9, "an upper bound (a number or v_name)");
    bounded_ = true;
  }

  // The image of the line x = X nearest c on a periodic axis.
  double line_near(double x, double c) const {
    if (!sim.domain.wraps(ax_)) return x;
    const double l = sim.domain.length(ax_);
    return x + l * std::round((c - x) / l);
  }

  // y wrapped into the box on a periodic axis (each contact then meets the line once in a period).
  double in_box(int k, double y) const {
    if (!sim.domain.wraps(k)) return y;
    const double l = sim.domain.length(k);
    return y - l * std::floor((y - sim.domain.lo[k]) / l);
  }

  // The lowest grain bottom and highest grain top of the group along axis k (0, 0: no grain).
  void group_span(int k, double& lo, double& hi) const {
    const Atoms& at = sim.atoms;
    lo = std::numeric_limits<double>::infinity(), hi = -lo;
    for (std::size_t i = 0; i < at.n; ++i)
      if (at.mask[i] & groupbit) {
        lo = std::min(lo, at.x[3 * i + k] - at.radius[i]);
        hi = std::max(hi, at.x[3 * i + k] + at.radius[i]);
      }
    if (lo > hi) lo = hi = 0;
  }

  void evaluate() {
    init();
    const int ay = 1 - ax_;
    const double x0 = line_.eval(sim, args);
    double lo = 0, hi = 0;
    if (bounded_) lo = lo_.eval(sim, args), hi = hi_.eval(sim, args);
    else group_span(ay, lo, hi);
    if (bounded_ && !(hi > lo))
      args.fail_line("compute " + id + ": at step " + std::to_string(sim.step) + " the upper bound " +
                     std::to_string(hi) + " is not above the lower " + std::to_string(lo));
    pair_->records(groupbit, rec_);
    const Atoms& at = sim.atoms;
    double sum = 0;
    long n = 0;
    for (const ContactRecord& c : rec_.rows) {
      const double len = at.radius[c.i] + at.radius[c.j] - c.delta;
      const double* xi = &at.x[3 * c.i];
      const double xj[2] = {xi[0] - c.en[0] * len, xi[1] - c.en[1] * len};  // j's image: x_i - l
      const double x = line_near(x0, 0.5 * (xi[ax_] + xj[ax_]));
      const bool iup = xi[ax_] >= x;
      if (iup == (xj[ax_] >= x)) continue;
      const double t = (x - xi[ax_]) / (xj[ax_] - xi[ax_]), y = in_box(ay, xi[ay] + t * (xj[ay] - xi[ay]));
      if (bounded_ && (y < lo || y > hi)) continue;
      sum += iup ? c.f[ax_] : -c.f[ax_];
      ++n;
    }
    const double h = hi - lo;
    out_[0] = h > 0 ? sum / h : 0.0;
    out_[1] = sum, out_[2] = h, out_[3] = static_cast<double>(n), out_[4] = lo, out_[5] = hi;
  }
};

SABLE_COMPUTE("force/midline", ComputeForceMidline);

}  // namespace sable
