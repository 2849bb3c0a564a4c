// fix ID group move STYLE args [units box]   (LAMMPS / LIGGGHTS fix move)
//   linear Vx Vy Vz                  X = X0 + V t,            v = V
//   wiggle Ax Ay Az period           X = X0 + A sin(w t),     v = A w cos(w t),  w = 2 pi / period
//   rotate Px Py Pz Rx Ry Rz period  X0 turned by w t about the axis R through P (right hand),
//                                    v = w R x (X - axis), and each grain's spin set to w R
//   variable v_dx v_dy v_dz v_vx v_vy v_vz   X = X0 + d(t), v = v(t) (equal- or atom-style)
// X0 is each grain's unwrapped position when the fix is defined and t the time
// since (steps times the current dt, as LAMMPS counts it). A NULL component of
// linear, wiggle or variable (both d and v NULL) is integrated from the force
// as fix nve would; with only v_dx the velocity is left alone, with only v_vx
// the position follows the velocity (LAMMPS). Default and only units: box
// (LIGGGHTS' default; LAMMPS' is lattice). Grains of the group should not be in
// another integrator's group too: like LAMMPS, both then update them, in
// definition order (a warning says how many). X0 and the time origin are
// restart state: a restarted deck that defines the fix again continues it.
//
// Both halves are per-atom tasks; the first reads the step's time (begin()), so
// the fix prescribes motion (FixTraits): the plan never runs it ahead of its step.
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "core/io/restart.h"
#include "core/engine/simulation.h"
#include "core/input/style_registry.h"
#include "core/input/variable.h"
#include "core/io/yade_script.h"

namespace sable {

class FixMove : public Fix {
 public:
  FixMove(Simulation& s, const Args& a) : Fix(s, a) {
    hooks = atom_tasks = INITIAL_INTEGRATE | FINAL_INTEGRATE;
    traits.prescribes_motion = true;
    const std::string& st = a.word(4, "a move style: linear, wiggle, rotate or variable");
    std::size_t next = 0;
    if (st == "linear") {
      style_ = Linear, next = 8;
      for (int k = 0; k < 3; ++k) set_[k] = number_or_null(a, 5 + k, "a velocity component or NULL", vel_[k]);
    } else if (st == "wiggle") {
      style_ = Wiggle, next = 9;
      for (int k = 0; k < 3; ++k) set_[k] = number_or_null(a, 5 + k, "an amplitude component or NULL", amp_[k]);
      period(a, 8);
    } else if (st == "rotate") {
      style_ = Rotate, next = 12;
      parse_rotate(a);
    } else if (st == "variable") {
      style_ = Variable, next = 11;
      for (int k = 0; k < 6; ++k) parse_variable(a, 5 + k, k < 3 ? disp_[k] : vel_var_[k - 3]);
      for (int k = 0; k < 3; ++k) set_[k] = !disp_[k].name.empty() || !vel_var_[k].name.empty();
    } else {
      a.fail(4, "a move style: linear, wiggle, rotate or variable");
    }
    if (a.size() < next) a.fail(a.size(), "the arguments of move " + st);
    a.box_units_only(next, "units",
                     "box (sable's fix move takes box units only; give distances and velocities in box units)");
    check_2d(a);
    traits.turns_grains = style_ == Rotate;  // it sets each grain's spin
    col_ = s.atoms.add_column("move " + id, 3, kUnset);
    // After read_restart the column came back with the atoms: the state continues it.
    auto st_it = s.restart.fix_states.find(id);
    if (st_it == s.restart.fix_states.end() || st_it->second.style != style) record_origin();
  }

  void init() override {
    for (Var* v : {&disp_[0], &disp_[1], &disp_[2], &vel_var_[0], &vel_var_[1], &vel_var_[2]})
      if (!v->name.empty()) {
        if (!sim.variables->exists(v->name))
          args.fail(v->at, "a defined variable ('" + v->name + "' is not defined)");
        v->atom = sim.variables->is_atom_style(v->name);
      }
    backfill(delta_at(sim.step));
    warn_double_integration();
  }

  // First half: this step's time and variables, serially; then each grain from its X0.
  void begin(FixHook h) override {
    if (h != INITIAL_INTEGRATE) return;
    Atoms& at = sim.atoms;
    if (at.n != seen_n_ || at.max_id != seen_id_) backfill(delta_at(sim.step - 1));  // new grains
    t_ = delta_at(sim.step);
    if (style_ == Variable) evaluate_variables();
    cos_ = std::cos(omega_ * t_), sin_ = std::sin(omega_ * t_);
  }
  void range(FixHook h, const AtomRange& r) override {
    if (h == INITIAL_INTEGRATE) return first_half(r);
    if (style_ == Rotate || (set_[0] && set_[1] && set_[2])) return;
    Atoms& at = sim.atoms;  // second half: fix nve's kick of the free components
    const double half = 0.5 * sim.dt;
    for (std::size_t i = r.lo; i < r.hi; ++i) {
      if (!(at.mask[i] & groupbit)) continue;
      for (int k = 0; k < 3; ++k)
        if (!set_[k]) at.v[3 * i + k] += half / at.rmass[i] * at.f[3 * i + k];
    }
  }

  bool write_state(std::string& out) const override {
    restart::Packer p;
    p.put<std::int64_t>(origin_);
    out += p.bytes;
    return true;
  }
  void read_state(const std::string& in) override {
    restart::Unpacker u(in, "fix move " + id + " state");
    origin_ = u.get<std::int64_t>();
  }
  void export_yade(YadeScript& s) const override;
  double max_speed() const override {
    if (style_ == Linear) return std::sqrt(sq(set_[0] ? vel_[0] : 0) + sq(set_[1] ? vel_[1] : 0) + sq(set_[2] ? vel_[2] : 0));
    if (style_ == Wiggle)
      return omega_ * std::sqrt(sq(set_[0] ? amp_[0] : 0) + sq(set_[1] ? amp_[1] : 0) + sq(set_[2] ? amp_[2] : 0));
    if (style_ == Rotate) return omega_ * farthest_from_axis();
    return 0.0;  // variable: unknown
  }

 private:
  enum Style { Linear, Wiggle, Rotate, Variable };
  struct Var {
    std::string name;
    std::size_t at = 0;
    bool atom = false;
    double value = 0;
    std::vector<double> per_atom;
    bool given() const { return !name.empty(); }
    double get(std::size_t i) const { return atom ? per_atom[i] : value; }
  };
  static constexpr double kUnset = std::numeric_limits<double>::quiet_NaN();  // X0 not yet recorded
  static double sq(double v) { return v * v; }

  Style style_ = Linear;
  bool set_[3] = {false, false, false};  // component prescribed (else integrated from the force)
  double vel_[3] = {0, 0, 0}, amp_[3] = {0, 0, 0};
  double point_[3] = {0, 0, 0}, axis_[3] = {0, 0, 1}, period_ = 1, omega_ = 0;
  Var disp_[3], vel_var_[3];
  long origin_ = 0;
  int col_ = -1;
  std::size_t seen_n_ = 0;
  long seen_id_ = 0;
  bool warned_ = false;
  double t_ = 0, cos_ = 1, sin_ = 0;  // this step's time since the origin, cos and sin of omega t

  void first_half(const AtomRange& r) {
    Atoms& at = sim.atoms;
    const double* x0 = at.column(col_).data();
    for (std::size_t i = r.lo; i < r.hi; ++i) {
      if (!(at.mask[i] & groupbit)) continue;
      double shift[3];
      for (int k = 0; k < 3; ++k) shift[k] = at.image[3 * i + k] * sim.domain.length(k);
      if (style_ == Rotate)
        rotate(i, x0 + 3 * i, shift, cos_, sin_);
      else
        for (int k = 0; k < 3; ++k) move(i, k, x0[3 * i + k] - shift[k], t_, cos_, sin_);
    }
  }

  static bool number_or_null(const Args& a, std::size_t i, const std::string& what, double& out) {
    if (a.word(i, what) == "NULL") return false;
    out = a.num(i, what);
    return true;
  }
  void period(const Args& a, std::size_t i) {
    period_ = a.num(i, "the period (time units, > 0)");
    if (!(period_ > 0)) a.fail(i, "the period (time units, > 0)");
    omega_ = 2.0 * std::numbers::pi / period_;
  }
  void parse_rotate(const Args& a) {
    double r[3], len = 0;
    for (int k = 0; k < 3; ++k) point_[k] = a.num(5 + k, "a point on the rotation axis (Px Py Pz)");
    for (int k = 0; k < 3; ++k) {
      r[k] = a.num(8 + k, "the rotation axis vector (Rx Ry Rz)");
      len += r[k] * r[k];
    }
    if (len == 0) a.fail(8, "a non-zero rotation axis vector");
    for (int k = 0; k < 3; ++k) axis_[k] = r[k] / std::sqrt(len);
    period(a, 11);
    set_[0] = set_[1] = set_[2] = true;
  }
  static void parse_variable(const Args& a, std::size_t i, Var& v) {
    const std::string& w = a.word(i, "v_name or NULL");
    if (w == "NULL") return;
    if (w.rfind("v_", 0) != 0 || w.size() < 3) a.fail(i, "v_name or NULL");
    v.name = w.substr(2);
    v.at = i;
  }
  // LAMMPS' 2D checks: nothing may move along z.
  void check_2d(const Args& a) const {
    if (sim.domain.dimension != 2) return;
    if (style_ == Linear && set_[2] && vel_[2] != 0) a.fail(7, "0 or NULL (no z motion in 2D)");
    if (style_ == Wiggle && set_[2] && amp_[2] != 0) a.fail(7, "0 or NULL (no z motion in 2D)");
    if (style_ == Rotate && (axis_[0] != 0 || axis_[1] != 0)) a.fail(8, "an axis along z (2D rotates about z only)");
    if (style_ == Variable && (disp_[2].given() || vel_var_[2].given())) a.fail(7, "NULL for z and vz (2D)");
  }

  double delta_at(long step) const { return static_cast<double>(step - origin_) * sim.dt; }

  // X0 of every grain of the group now, unwrapped; the time origin is now.
  void record_origin() {
    Atoms& at = sim.atoms;
    std::vector<double>& x0 = at.column(col_);
    for (std::size_t i = 0; i < at.n; ++i) {
      if (at.mask[i] & groupbit)
        sim.domain.unmap(&at.x[3 * i], &at.image[3 * i], &x0[3 * i]);
      else
        x0[3 * i] = x0[3 * i + 1] = x0[3 * i + 2] = kUnset;
    }
    origin_ = sim.step;
    seen_n_ = at.n, seen_id_ = at.max_id;
  }

  // Grains of the group without X0 (inserted, or added to the group, since the
  // fix was defined) get the X0 that puts them where they are at time t (LAMMPS).
  void backfill(double t) {
    Atoms& at = sim.atoms;
    std::vector<double>& x0 = at.column(col_);
    seen_n_ = at.n, seen_id_ = at.max_id;
    for (std::size_t i = 0; i < at.n; ++i) {
      if (!(at.mask[i] & groupbit) || !std::isnan(x0[3 * i])) continue;
      if (style_ == Variable) args.fail_line("fix move variable cannot take grains added to its group after it was defined (as LAMMPS)");
      double* o = &x0[3 * i];
      sim.domain.unmap(&at.x[3 * i], &at.image[3 * i], o);
      if (style_ == Rotate) {
        const double d[3] = {o[0] - point_[0], o[1] - point_[1], o[2] - point_[2]};
        double along[3], disp[3];
        turn(d, std::cos(-omega_ * t), std::sin(-omega_ * t), along, disp);
        for (int k = 0; k < 3; ++k) o[k] = point_[k] + along[k] + disp[k];
      } else {
        for (int k = 0; k < 3; ++k)
          if (set_[k]) o[k] -= style_ == Linear ? vel_[k] * t : amp_[k] * std::sin(omega_ * t);
      }
    }
  }

  void evaluate_variables() {
    for (Var* v : {&disp_[0], &disp_[1], &disp_[2], &vel_var_[0], &vel_var_[1], &vel_var_[2]}) {
      if (!v->given()) continue;
      if (v->atom)
        sim.variables->atom_values(v->name, v->per_atom);
      else if (!sim.variables->numeric(v->name, v->value))
        args.fail(v->at, "a numeric variable (v_" + v->name + ")");
    }
  }

  // Component k of grain i; x0 is its X0 in the grain's current image.
  void move(std::size_t i, int k, double x0, double t, double c, double sn) {
    double& x = sim.atoms.x[3 * i + k];
    double& v = sim.atoms.v[3 * i + k];
    if (style_ == Linear && set_[k]) {
      v = vel_[k];
      x = x0 + vel_[k] * t;
    } else if (style_ == Wiggle && set_[k]) {
      v = amp_[k] * omega_ * c;
      x = x0 + amp_[k] * sn;
    } else if (style_ == Variable && disp_[k].given()) {
      if (vel_var_[k].given()) v = vel_var_[k].get(i);
      x = x0 + disp_[k].get(i);
    } else if (style_ == Variable && vel_var_[k].given()) {
      v = vel_var_[k].get(i);
      x += sim.dt * v;
    } else {  // free: fix nve's half kick and drift
      v += 0.5 * sim.dt / sim.atoms.rmass[i] * sim.atoms.f[3 * i + k];
      x += sim.dt * v;
    }
  }

  // d = X0 - P split into its part along the axis and the part across it,
  // turned by the angle whose cosine and sine are c, s (right hand; LAMMPS' form).
  void turn(const double d[3], double c, double s, double along[3], double disp[3]) const {
    const double* r = axis_;
    const double dr = d[0] * r[0] + d[1] * r[1] + d[2] * r[2];
    double a[3], b[3];
    for (int k = 0; k < 3; ++k) along[k] = dr * r[k], a[k] = d[k] - along[k];
    b[0] = r[1] * a[2] - r[2] * a[1];
    b[1] = r[2] * a[0] - r[0] * a[2];
    b[2] = r[0] * a[1] - r[1] * a[0];
    for (int k = 0; k < 3; ++k) disp[k] = a[k] * c + b[k] * s;
  }

  void rotate(std::size_t i, const double* x0, const double* shift, double c, double s) {
    Atoms& at = sim.atoms;
    const double d[3] = {x0[0] - point_[0], x0[1] - point_[1], x0[2] - point_[2]};
    double along[3], disp[3];
    turn(d, c, s, along, disp);
    const double* r = axis_;
    double* x = &at.x[3 * i];
    double* v = &at.v[3 * i];
    for (int k = 0; k < 3; ++k) x[k] = point_[k] + along[k] + disp[k] - shift[k];
    v[0] = omega_ * (r[1] * disp[2] - r[2] * disp[1]);
    v[1] = omega_ * (r[2] * disp[0] - r[0] * disp[2]);
    v[2] = omega_ * (r[0] * disp[1] - r[1] * disp[0]);
    for (int k = 0; k < 3; ++k) at.omega[3 * i + k] = omega_ * r[k];
  }

  double farthest_from_axis() const {
    const Atoms& at = sim.atoms;
    double r2 = 0;
    for (std::size_t i = 0; i < at.n; ++i) {
      if (!(at.mask[i] & groupbit)) continue;
      double d[3], dr = 0, d2 = 0;
      for (int k = 0; k < 3; ++k) d[k] = at.x[3 * i + k] - point_[k], dr += d[k] * axis_[k];
      for (int k = 0; k < 3; ++k) d2 += sq(d[k] - dr * axis_[k]);
      r2 = std::max(r2, d2);
    }
    return std::sqrt(r2);
  }

  // Once per fix (a label/jump loop of runs would repeat it).
  void warn_double_integration() {
    if (warned_) return;
    const Atoms& at = sim.atoms;
    for (auto& f : sim.fixes) {
      if (f.get() == this || !(f->hooks & INITIAL_INTEGRATE)) continue;
      long both = 0;
      for (std::size_t i = 0; i < at.n; ++i) both += (at.mask[i] & groupbit) && (at.mask[i] & f->groupbit);
      if (!both) continue;
      warned_ = true;
      sim.warn("fix move " + id + ": " + std::to_string(both) + " of its grains are also integrated by fix " +
               f->style + " '" + f->id + "': both update them, in definition order (as in LAMMPS and LIGGGHTS); "
               "leave them out of that fix's group");
    }
  }
};

// linear only: each grain's velocity set once, its set components and spin locked
// (YADE's blockedDOFs), a NULL component keeps the grain's velocity now.
void FixMove::export_yade(YadeScript& s) const {
  if (style_ != Linear) args.tail(1).fail(3, "linear (export-yade translates fix move linear)");
  const Atoms& at = sim.atoms;
  for (std::size_t i = 0; i < at.n; ++i) {
    if (!(at.mask[i] & groupbit)) continue;
    std::string vel = "Vector3(", dofs;
    for (int k = 0; k < 3; ++k) {
      if (set_[k]) dofs += "xyz"[k];
      vel += yade_num(set_[k] ? vel_[k] : at.v[3 * i + k]) + (k < 2 ? ", " : ")");
    }
    s.block(i, dofs + "XYZ");
    s.add_move("_b(" + std::to_string(at.id[i]) + ").state.vel = " + vel);
    s.add_move("_b(" + std::to_string(at.id[i]) + ").state.angVel = Vector3(0, 0, 0)");
  }
  s.integrate(groupbit);
}

SABLE_FIX("move", FixMove);

}  // namespace sable
