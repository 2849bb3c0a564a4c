// compute ID group wall/gran/slices WALLFIX N dim x|y|z lo LO hi HI [outside clamp|drop]
// (sable addition; LIGGGHTS and LAMMPS have no such style.)
// The force the grains of the group put on a primitive plane wall (fix WALLFIX
// wall/gran ... primitive xplane|yplane|zplane), split into N equal slices of
// [LO, HI] along `dim` by the contact point's coordinate (the grain's
// projection on the plane). kneib2017 Sec. IV splits the right wall's height
// into ten slices this way (slice 1 at the bottom). LO and HI are numbers or
// equal-style variables (v_name), evaluated at each invocation, so HI can
// follow the current bed height.
//   c_ID[i], i = 1..N: the component along the plane's normal axis of the force
//   on the wall, the sign of f_WALLFIX[axis] (the right wall of the cavity:
//   > 0). Contacts outside [LO, HI]: `outside clamp` (default) counts them in
//   slice 1 (below LO) or N (above HI), so the slices sum to the whole wall's
//   force; `outside drop` leaves them out.
//   Local rows (dump local c_ID[k]), one per contact of the group's grains with
//   this wall, every contact (no slicing): id x y z fx fy fz, the grain's id,
//   the contact point on the wall, the force ON THE WALL (minus the force on
//   the grain; compute wall/gran/local gives the force on the grain).
// Both read the wall's last force pass, the one f_WALLFIX reports, so the
// slices sum to f_WALLFIX[axis] to rounding. (Re-evaluating the contacts at
// output, as wall/gran/local does, would let the dashpots see final_integrate's
// half kick: 0.8 % per sample in the cavity.) If grains were deleted or
// created since that pass, the contacts are re-evaluated now instead.
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "computes/bound_arg.h"
#include "core/engine/atoms.h"
#include "core/engine/compute.h"
#include "core/engine/contact_source.h"
#include "core/engine/simulation.h"
#include "core/input/style_registry.h"
#include "core/input/variable.h"
#include "core/io/yade_script.h"

namespace sable {

namespace {

int slice_axis_of(const std::string& w) { return w == "x" ? 0 : w == "y" ? 1 : w == "z" ? 2 : -1; }

}  // namespace

class ComputeWallGranSlices : public Compute {
 public:
  ComputeWallGranSlices(Simulation& s, const Args& a) : Compute(s, a) {
    const std::string usage = "compute ID group wall/gran/slices WALLFIX N dim x|y|z lo LO hi HI [outside clamp|drop]";
    a.need(12, usage);
    wall_id_ = a.word(4, "the ID of a fix wall/gran ... primitive plane");
    const long n = a.integer(5, "the number of slices N");
    if (n < 1 || n > 100000) a.fail(5, "a number of slices in 1..100000");
    vector_size = static_cast<int>(n);
    expect(a, 6, "dim");
    dim_ = slice_axis_of(a.word(7, "x, y or z"));
    if (dim_ < 0) a.fail(7, "x, y or z");
    expect(a, 8, "lo");
    lo_ = BoundArg::parse(s, a, 9, "a lower bound (a number or v_name)");
    expect(a, 10, "hi");
    hi_ = BoundArg::parse(s, a, 11, "an upper bound (a number or v_name)");
    for (std::size_t i = 12; i < a.size(); i += 2) {
      if (a[i] != "outside") a.fail(i, "the keyword 'outside' (or the end of the line)");
      clamp_ = a.choice(i + 1, {"clamp", "drop"}) == 0;
    }
    local_flag = true;
    local_names = {"id", "x", "y", "z", "fx", "fy", "fz"};
    local_cols = static_cast<int>(local_names.size());
    init();
  }

  void init() override {
    wall_ = contact_source_of_fix(sim, wall_id_);
    if (!wall_) args.fail(4, "the ID of a fix wall/gran ... primitive plane defined before this compute");
    axis_ = wall_->plane_axis();
    if (axis_ < 0) args.fail(4, "a fix wall/gran with a primitive xplane, yplane or zplane (fix " + wall_id_ + " is not one)");
  }

  double compute_vector(int i) override {
    if (invoked_step != sim.step) {  // once per step: every c_ID[i] of a step reads the same contacts
      fill();
      invoked_step = sim.step;
    }
    return slices_[static_cast<std::size_t>(i - 1)];
  }

 private:
  static void expect(const Args& a, std::size_t i, const std::string& key) {
    if (a.word(i, "'" + key + "'") != key) a.fail(i, "'" + key + "'");
  }

  // The slice (0-based) of coordinate y, or -1 when it is dropped.
  long slice_of(double y, double lo, double hi) const {
    const long n = vector_size;
    if (y < lo) return clamp_ ? 0 : -1;
    if (y > hi) return clamp_ ? n - 1 : -1;
    const long k = static_cast<long>(std::floor((y - lo) / (hi - lo) * static_cast<double>(n)));
    return std::clamp(k, 0L, n - 1);  // y == hi belongs to the top slice
  }

  // Calls fn(atom index, wall point, force on the grain) for each contact of the
  // group's grains with the wall at its last force pass.
  template <class Fn>
  void contacts(Fn&& fn) {
    init();  // the wall may have been redefined since
    const Atoms& at = sim.atoms;
    if (wall_->last_pass([&](int i, const double* p, const double* f) {
          if (at.mask[i] & groupbit) fn(i, p, f);
        }))
      return;
    wall_->records(groupbit, rec_);  // atoms changed since the pass: its indices no longer hold
    for (const ContactRecord& c : rec_.rows) fn(c.i, wall_->wall_point(c.shift), c.f);
  }

  void fill() {
    const double lo = lo_.eval(sim, args), hi = hi_.eval(sim, args);
    if (!(hi > lo) || !std::isfinite(lo) || !std::isfinite(hi))
      args.fail_line("compute " + id + ": at step " + std::to_string(sim.step) + " hi = " + std::to_string(hi) +
                     " is not above lo = " + std::to_string(lo));
    slices_.assign(static_cast<std::size_t>(vector_size), 0.0);
    contacts([&](int, const double* p, const double* f) {
      const long k = slice_of(p[dim_], lo, hi);
      if (k >= 0) slices_[static_cast<std::size_t>(k)] -= f[axis_];  // the wall receives minus the grain's force
    });
  }

 public:
  void compute_local() override {
    local.clear();
    contacts([&](int i, const double* p, const double* f) {
      const double row[7] = {static_cast<double>(sim.atoms.id[i]), p[0], p[1], p[2], 0.0 - f[0], 0.0 - f[1], 0.0 - f[2]};
      local.insert(local.end(), row, row + 7);
    });
  }
  std::string export_yade_term(const YadeScript& s, long k, const Args& at, const std::string& k_expr) const override;
  std::string export_yade_rows(const YadeScript& s) const override;

 private:
  std::string wall_id_;
  ContactSource* wall_ = nullptr;
  int axis_ = 0, dim_ = 1;
  BoundArg lo_, hi_;
  bool clamp_ = true;
  ContactRecords rec_;
  std::vector<double> slices_;
};

// --export-yade: c_ID[k] from YADE's interactions with the wall's body after the
// step's force pass (the pass O.forces.f of the wall reports, as sable's slices
// read the wall's last pass): minus the normal + shear force on the grain,
// sliced by the grain's coordinate (its projection on the plane); _slice in the
// script's head.
std::string ComputeWallGranSlices::export_yade_term(const YadeScript& s, long k, const Args& at,
                                                    const std::string& k_expr) const {
  const long n = vector_size;
  if (k < 1 || k > n)
    at.fail_line("export-yade: c_" + id + "[" + std::to_string(k) + "]: slices 1.." + std::to_string(n));
  const int w = s.wall_index(wall_id_);
  if (w < 0) args.fail(4, "a primitive wall export-yade translated (fix " + wall_id_ + " is not one of its walls)");
  auto bound = [&](std::size_t i) {
    return "lambda: " + (args[i].rfind("v_", 0) == 0 ? s.translate(args[i], args) : yade_num(args.num(i, "a bound")));
  };
  return "_slice(" + yade_quoted(id) + ", " + (k_expr.empty() ? std::to_string(k - 1) : k_expr) + ", " +
         std::to_string(w) + ", " + std::to_string(s.wall_axis(w)) + ", " + yade_num(s.wall_pos(w)) + ", " +
         s.ids_of(groupbit) + ", " + std::to_string(n) + ", " + std::to_string(dim_) + ", " + bound(9) + ", " +
         bound(11) + ", " + (clamp_ ? "True" : "False") + ")";
}

// The local rows (dump local): the grain, the contact point on the plane, the force on the wall.
std::string ComputeWallGranSlices::export_yade_rows(const YadeScript& s) const {
  const int w = s.wall_index(wall_id_);
  if (w < 0) args.fail(4, "a primitive wall export-yade translated");
  return "_wall_rows(" + yade_quoted(id) + ", " + std::to_string(w) + ", " + std::to_string(s.wall_axis(w)) + ", " +
         yade_num(s.wall_pos(w)) + ", " + s.ids_of(groupbit) + ")";
}

SABLE_COMPUTE("wall/gran/slices", ComputeWallGranSlices);

}  // namespace sable
