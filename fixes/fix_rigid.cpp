// fix ID group rigid bodystyle args [force M xf yf zf] [torque M xf yf zf]
// fix ID group rigid/small (molecule | custom v_name)
// LAMMPS' fix rigid (NVE, Richardson iteration for the orientation) for granular spheres.
//
// Bodies: `single` (the fix group), `group N g1 .. gN`, `custom v_name` (an
// atom-style variable whose integer value is each grain's body ID; 0 = in no
// body), evaluated once, at the first run. Granular atoms carry no molecule
// ID, so `molecule` is refused with that advice. Each body has at least two grains.
// Mass and inertia: the sum of the member spheres (2/5 m r^2 each, plus the
// parallel-axis term), overlaps counted twice, as LAMMPS and LIGGGHTS do.
// Contacts see the body's mass as each member's mass (LIGGGHTS' m_eff for rigid
// members: a flat dumbbell bouncing on a floor at e = 0.5 comes back at 0.366).
// Grains of one body never pair (LIGGGHTS' fix multisphere; with LAMMPS' fix
// rigid a deck asks for it by neigh_modify exclude): their forces would cancel.
// fix damping/cundall damps a body as a whole (BodySet::damping), not its members.
// f_ID[i][j]: body i, columns x y z (centre of mass, in the box), vx vy vz,
// fx fy fz, tx ty tz (summed force and torque before the force/torque flags),
// ix iy iz (image counters), as LAMMPS' global array.
#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <string>
#include <vector>

#include "core/io/restart.h"
#include "core/engine/simulation.h"
#include "core/input/style_registry.h"
#include "core/input/variable.h"
#include "fixes/rigid_body_set.h"
#include "core/io/yade_script.h"

namespace sable {

// declarations, not `using namespace rigid`: in a unity batch a directive would reach the next files
using rigid::Body;
using rigid::BodySet;
using rigid::Q4;
using rigid::V3;

class FixRigid : public Fix {
 public:
  FixRigid(Simulation& s, const Args& a) : FixRigid(s, a, false) {}
  void export_yade(YadeScript& s) const override { s.add_clumps(*this, yade::rigid_clumps(sim, *this)); }
  FixRigid(Simulation& s, const Args& a, bool small) : Fix(s, a), small_(small) {
    hooks = INITIAL_INTEGRATE | FINAL_INTEGRATE | PRE_FORCE;
    atom_tasks = two_phase_tasks = INITIAL_INTEGRATE | FINAL_INTEGRATE;
    parse(a);
    const auto st = sim.restart.fix_states.find(id);
    if (st == sim.restart.fix_states.end() || st->second.style != style) define_bodies();  // else read_state
  }

  void init() override {
    check_integrators();
    // Grains appear mid-run only in post_integrate (insertion): only then must
    // their contact mass be set before the force pass. Without the hook the
    // step plan lets the integrator zero the forces (one parallel region fewer).
    bool inserts = false;
    for (auto& f : sim.fixes) inserts = inserts || (f->hooks & POST_INTEGRATE);
    hooks = inserts ? hooks | PRE_FORCE : hooks & ~PRE_FORCE;
    mass_col_ = sim.atoms.add_column("rigid:contact_mass", 1);
    sim.atoms.mass_override = mass_col_;
    pair_col_ = sim.atoms.add_column("rigid:pair_exclusion", 1);
    sim.atoms.pair_exclusion = pair_col_;
    refresh_state();
    set_.find_damping();
    set_.place_members(false);
    refresh_contact_mass(true);
    traits.turns_grains = set_.any_rotates();  // the bodies' torque flags and spin, known now
  }
  void pre_force() override { refresh_contact_mass(false); }

  void begin(FixHook) override { set_.begin_task(); }
  void range(FixHook h, const AtomRange& r) override {
    if (h == INITIAL_INTEGRATE)
      set_.initial_range(r, sim.dt);
    else
      set_.final_range(r, sim.dt);
  }

  void setup() override { set_.sum_forces(); }

  const RigidBodies* rigid_bodies() const override { return &set_; }

  double compute_array(int i, int j) override {
    if (i < 1 || i > static_cast<int>(bodies_.size()) || j < 1 || j > 15)
      args.fail_line("f_" + id + "[" + std::to_string(i) + "][" + std::to_string(j) + "]: index out of range [1.." +
                     std::to_string(bodies_.size()) + "][1..15]");
    const Body& b = set_.by_number(i - 1);
    double x[3] = {b.xcm[0], b.xcm[1], b.xcm[2]};
    int image[3] = {0, 0, 0};
    sim.domain.remap(x, image);
    const int k = (j - 1) % 3;
    switch ((j - 1) / 3) {
      case 0: return x[k];
      case 1: return b.vcm[k];
      case 2: return b.force[k];
      case 3: return b.torque[k];
      default: return image[k];
    }
  }

  bool write_state(std::string& out) const override {
    restart::Packer p;
    p.put<std::uint8_t>(defined_);
    p.put_vector(bodies_);
    p.put_vector(set_.number);
    out = p.bytes;
    return true;
  }
  void read_state(const std::string& in) override {
    restart::Unpacker u(in, "the restart state of fix " + id);
    defined_ = u.get<std::uint8_t>();
    bodies_ = u.get_vector<Body>();
    set_.number = u.get_vector<int>();
    set_.numbers_read();
    for (Body& b : bodies_) b.fflag = b.tflag = {true, true, true};
    apply_flags();  // the deck's force/torque flags, as written again
    col_ = sim.atoms.find_column("rigid:" + id);
    if (col_ < 0) args.fail_line("the restart file holds fix " + id + " but not its per-grain body data");
    array_rows = static_cast<int>(bodies_.size());
    array_cols = 15;
  }

 private:
  enum class Style { Single, Group, Custom };
  Style bodystyle_ = Style::Single;
  bool small_ = false, defined_ = false;
  std::vector<int> groups_;  // bodystyle group
  std::string var_;          // bodystyle custom
  struct FlagSpec {
    bool torque;
    std::string range;
    std::array<bool, 3> on;
    std::size_t at;
  };
  std::vector<FlagSpec> flag_specs_;
  BodySet set_{sim};  // the bodies and their per-atom column (fixes/rigid_body_set.h)
  std::vector<Body>& bodies_ = set_.bodies;
  int& col_ = set_.col;
  int mass_col_ = -1;  // per atom: the mass contacts see
  int pair_col_ = -1;  // per atom: a key shared by the grains of one body, which never pair
  std::size_t last_n_ = 0;
  static constexpr int kStride = BodySet::kStride;

  // A member also moved by a per-atom integrator (nve/sphere) would be integrated twice.
  void check_integrators() const {
    const Atoms& at = sim.atoms;
    const auto& c = at.column(col_);
    for (auto& f : sim.fixes) {
      if (f.get() == this) continue;
      const RigidBodies* rb = f->rigid_bodies();
      for (std::size_t i = 0; i < at.n && rb; ++i)
        if (c[kStride * i] != 0 && rb->body_of(i) >= 0)
          args.fail_line("atom " + std::to_string(at.id[i]) + " belongs to a body of fix " + f->id +
                         " too: a grain is in one rigid body at most");
      if (f->role(INITIAL_INTEGRATE) != FixRole::Integrator) continue;
      for (std::size_t i = 0; i < at.n; ++i)
        if (c[kStride * i] != 0 && (at.mask[i] & f->groupbit))
          args.fail_line("atom " + std::to_string(at.id[i]) + " of a rigid body is also integrated by fix " + f->id +
                         " (" + f->style + "): give that fix a group without the body grains (LAMMPS would move "
                         "them twice)");
    }
  }

  void parse(const Args& a) {
    const std::string& bs = a.word(4, "a body style (single, group, custom; molecule)");
    std::size_t i = 5;
    if (bs == "molecule") {
      a.fail(4, "'custom v_name' (an atom-style variable giving each grain's body ID) or 'group N ...': sable's "
                "granular atoms carry no molecule ID");
    } else if (bs == "single" && !small_) {
      bodystyle_ = Style::Single;
    } else if (bs == "group" && !small_) {
      bodystyle_ = Style::Group;
      const long n = a.integer(5, "the number of groups");
      if (n < 1) a.fail(5, "a number of groups >= 1");
      for (long g = 0; g < n; ++g) {
        const std::string& name = a.word(6 + g, "group " + std::to_string(g + 1) + " of " + std::to_string(n));
        const int gi = sim.groups.find(name);
        if (gi < 0) a.fail(6 + g, "an existing group ID");
        groups_.push_back(gi);
      }
      i = 6 + n;
    } else if (bs == "custom") {
      bodystyle_ = Style::Custom;
      const std::string& v = a.word(5, "v_name (an atom-style variable with each grain's body ID)");
      if (v.rfind("v_", 0) != 0) a.fail(5, "v_name (an atom-style variable; sable has no i_name properties)");
      var_ = v.substr(2);
      if (!sim.variables->is_atom_style(var_)) a.fail(5, "an atom-style variable");
      i = 6;
    } else {
      a.fail(4, small_ ? "a rigid/small body style: custom (molecule needs molecule IDs)"
                       : "a body style: single, group N ..., custom v_name");
    }
    while (i < a.size()) {
      const std::string& k = a[i];
      if ((k == "force" || k == "torque") && !small_) {
        a.need(i + 5, k + " M xflag yflag zflag");
        FlagSpec f{k == "torque", a[i + 1], {}, i + 1};
        for (int c = 0; c < 3; ++c) f.on[c] = a.yes_no(i + 2 + c, "on or off");
        flag_specs_.push_back(f);
        i += 5;
      } else {
        a.fail(i, small_ ? "nothing (fix rigid/small takes no keywords in sable)"
                         : "a keyword sable supports: force or torque (langevin, temp, iso, infile ... are not)");
      }
    }
  }

  // Which atoms are in which body, then mass, centre, inertia and momentum of each.
  void define_bodies() {
    Atoms& at = sim.atoms;
    std::vector<long> key(at.n, 0);  // 0: in no body
    if (bodystyle_ == Style::Single) {
      for (std::size_t i = 0; i < at.n; ++i) key[i] = (at.mask[i] & groupbit) ? 1 : 0;
    } else if (bodystyle_ == Style::Group) {
      for (std::size_t i = 0; i < at.n; ++i) {
        if (!(at.mask[i] & groupbit)) continue;
        for (std::size_t g = 0; g < groups_.size(); ++g)
          if (at.mask[i] & (1u << groups_[g])) {
            if (key[i]) args.fail_line("atom " + std::to_string(at.id[i]) + " is in two of the listed groups: a grain "
                                       "belongs to one rigid body at most");
            key[i] = static_cast<long>(g) + 1;
          }
      }
    } else {
      std::vector<double> val;
      sim.variables->atom_values(var_, val);
      for (std::size_t i = 0; i < at.n; ++i) {
        if (!(at.mask[i] & groupbit)) continue;
        if (val[i] != std::floor(val[i]) || val[i] < 0)
          args.fail_line("variable " + var_ + " gives atom " + std::to_string(at.id[i]) + " the body ID " +
                         std::to_string(val[i]) + ": body IDs are integers >= 0 (0: in no body)");
        key[i] = static_cast<long>(val[i]);
      }
    }
    // Bodies numbered in ascending key order (LAMMPS: by molecule ID; group order for group).
    std::map<long, int> index;
    for (long k : key)
      if (k) index.emplace(k, 0);
    if (bodystyle_ == Style::Group)
      for (std::size_t g = 0; g < groups_.size(); ++g) index.emplace(static_cast<long>(g) + 1, 0);
    int nb = 0;
    for (auto& [k, v] : index) v = nb++;
    if (nb == 0) args.fail_line("no rigid bodies: no grain of group '" + sim.groups.name(group) + "' has a body (" +
                                (bodystyle_ == Style::Custom ? "every body ID is 0" : "the group is empty") + ")");
    bodies_.assign(nb, Body{});
    col_ = at.add_column("rigid:" + id, kStride);
    auto& c = at.column(col_);
    for (std::size_t i = 0; i < at.n; ++i) c[kStride * i] = key[i] ? index[key[i]] + 1 : 0;
    for (std::size_t i = 0; i < at.n; ++i)
      if (key[i]) bodies_[index[key[i]]].members++;
    for (std::size_t b = 0; b < bodies_.size(); ++b)
      if (bodies_[b].members < 2)
        args.fail_line("rigid body " + std::to_string(b + 1) + " has " + std::to_string(bodies_[b].members) +
                       " grain" + (bodies_[b].members == 1 ? "" : "s") + ": each body needs two or more");
    apply_flags();
    measure_static(std::vector<char>(bodies_.size(), 1));
    measure_dynamic();
    defined_ = true;
    last_n_ = at.n;
    array_rows = nb;
    array_cols = 15;
    sim.print(std::to_string(nb) + " rigid bodies with " + std::to_string(std::count_if(
        key.begin(), key.end(), [](long k) { return k != 0; })) + " atoms");
  }

  void apply_flags() {
    const long nb = static_cast<long>(bodies_.size());
    for (const FlagSpec& f : flag_specs_) {
      long lo = 1, hi = nb;
      const std::string& r = f.range;
      const auto star = r.find('*');
      auto num = [&](const std::string& s) {
        long v;
        if (!parse_long(s, v)) args.fail(f.at, "a body number M, or a range *, *n, n*, m*n");
        return v;
      };
      if (star == std::string::npos) {
        lo = hi = num(r);
      } else {
        if (star > 0) lo = num(r.substr(0, star));
        if (star + 1 < r.size()) hi = num(r.substr(star + 1));
      }
      if (lo < 1 || hi > nb || lo > hi)
        args.fail(f.at, "bodies within 1.." + std::to_string(nb) + " (this fix has " + std::to_string(nb) + ")");
      for (long b = lo; b <= hi; ++b) {
        Body& body = bodies_[set_.slot(static_cast<int>(b - 1))];
        (f.torque ? body.tflag : body.fflag) = f.on;
      }
    }
  }

  // Mass, centre of mass, principal moments and axes, and each member's offset in
  // the body frame, of the bodies marked in `which`: three passes over the atoms.
  void measure_static(const std::vector<char>& which) {
    Atoms& at = sim.atoms;
    auto& c = at.column(col_);
    auto body_of_atom = [&](std::size_t i) {
      const int k = static_cast<int>(c[kStride * i]) - 1;
      return k >= 0 && which[k] ? k : -1;
    };
    std::vector<V3> s(bodies_.size(), V3{0, 0, 0});
    for (std::size_t b = 0; b < bodies_.size(); ++b)
      if (which[b]) bodies_[b].mass = 0;
    for (std::size_t i = 0; i < at.n; ++i) {
      const int k = body_of_atom(i);
      if (k < 0) continue;
      double u[3];
      sim.domain.unmap(&at.x[3 * i], &at.image[3 * i], u);
      for (int e = 0; e < 3; ++e) s[k][e] += at.rmass[i] * u[e];
      bodies_[k].mass += at.rmass[i];
    }
    for (std::size_t b = 0; b < bodies_.size(); ++b)
      if (which[b]) {
        for (int e = 0; e < 3; ++e) bodies_[b].xcm[e] = s[b][e] / bodies_[b].mass;
        bodies_[b].inv_mass = 1.0 / bodies_[b].mass;
      }
    std::vector<Eigen::Matrix3d> inertia(bodies_.size(), Eigen::Matrix3d::Zero());
    for (std::size_t i = 0; i < at.n; ++i) {
      const int k = body_of_atom(i);
      if (k < 0) continue;
      const V3 d = offset(i, bodies_[k]);
      const double m = at.rmass[i];
      const Eigen::Vector3d e(d[0], d[1], d[2]);
      inertia[k] += (at.inertia(i) + m * e.squaredNorm()) * Eigen::Matrix3d::Identity() - m * e * e.transpose();
    }
    for (std::size_t b = 0; b < bodies_.size(); ++b)
      if (which[b]) rigid::principal_axes(bodies_[b], inertia[b]);
    for (std::size_t i = 0; i < at.n; ++i) {
      const int k = body_of_atom(i);
      if (k < 0) continue;
      const Body& b = bodies_[k];
      const V3 d = offset(i, b);
      double* o = &c[kStride * i];
      o[1] = rigid::dot(d, b.ex), o[2] = rigid::dot(d, b.ey), o[3] = rigid::dot(d, b.ez);
      o[4] = d[0], o[5] = d[1], o[6] = d[2];
    }
  }

  V3 offset(std::size_t i, const Body& b) const {
    double u[3];
    sim.domain.unmap(&sim.atoms.x[3 * i], &sim.atoms.image[3 * i], u);
    return {u[0] - b.xcm[0], u[1] - b.xcm[1], u[2] - b.xcm[2]};
  }

  // Centre-of-mass velocity and angular momentum (orbital plus the members' own spin) from the grains.
  void measure_dynamic() {
    Atoms& at = sim.atoms;
    auto& c = at.column(col_);
    for (Body& b : bodies_) b.vcm = b.angmom = V3{0, 0, 0};
    for (std::size_t i = 0; i < at.n; ++i) {
      const int k = static_cast<int>(c[kStride * i]) - 1;
      if (k < 0) continue;
      Body& b = bodies_[k];
      const double m = at.rmass[i];
      const V3 v{at.v[3 * i], at.v[3 * i + 1], at.v[3 * i + 2]};
      const V3 d{c[kStride * i + 4], c[kStride * i + 5], c[kStride * i + 6]};
      const V3 l = rigid::cross(d, v);
      for (int e = 0; e < 3; ++e) {
        b.vcm[e] += m * v[e];
        b.angmom[e] += m * l[e] + at.inertia(i) * at.omega[3 * i + e];
      }
    }
    for (Body& b : bodies_) {
      for (double& v : b.vcm) v /= b.mass;
      b.omega = rigid::omega_of(b.angmom, b.ex, b.ey, b.ez, b.inv_moments);
    }
  }

  // Before a later run: a body whose grains were moved or given velocities since
  // the last step (velocity, set, displace_atoms) is measured again; one left
  // alone keeps its state bit for bit (restarts and split runs continue exactly).
  void refresh_state() {
    Atoms& at = sim.atoms;
    auto& c = at.column(col_);
    std::vector<char> moved(bodies_.size(), 0), count_ok(bodies_.size(), 0);
    std::vector<int> count(bodies_.size(), 0);
    for (std::size_t i = 0; i < at.n; ++i) {
      const int k = static_cast<int>(c[kStride * i]) - 1;
      if (k < 0) continue;
      ++count[k];
      double x[3], v[3];
      set_.expected(i, k, x, v);
      for (int e = 0; e < 3; ++e)
        if (x[e] != at.x[3 * i + e] || v[e] != at.v[3 * i + e] || bodies_[k].omega[e] != at.omega[3 * i + e])
          moved[k] = 1;
    }
    for (std::size_t b = 0; b < bodies_.size(); ++b)
      if (count[b] != bodies_[b].members)
        args.fail_line("rigid body " + std::to_string(set_.number_of(static_cast<int>(b)) + 1) + " had " +
                       std::to_string(bodies_[b].members) + " grains and has " + std::to_string(count[b]) + " now (grains of a body were deleted)");
    if (std::find(moved.begin(), moved.end(), 1) == moved.end()) return;
    measure_static(moved);
    measure_dynamic();
  }

  // The mass contacts see: the body's for members, the grain's own otherwise
  // (grains inserted since the last look get theirs here, before the force pass).
  void refresh_contact_mass(bool all) {
    Atoms& at = sim.atoms;
    if (!all && at.n == last_n_) return;
    auto& m = at.column(mass_col_);
    auto& pairs = at.column(pair_col_);
    const auto& c = at.column(col_);
    const int ordinal = rigid_ordinal();
    for (std::size_t i = 0; i < at.n; ++i) {
      const int k = static_cast<int>(c[kStride * i]) - 1;
      if (k >= 0) {
        m[i] = bodies_[k].mass;
        pairs[i] = std::ldexp(ordinal, 32) + k + 1;  // unique over all rigid fixes
      } else if (ordinal == 0 && (all || m[i] == 0.0)) {
        m[i] = at.rmass[i];
      }
    }
    last_n_ = at.n;
  }
  int rigid_ordinal() const {  // 0 for the first rigid fix defined
    int k = 0;
    for (auto& f : sim.fixes) {
      if (f.get() == this) return k;
      k += dynamic_cast<const FixRigid*>(f.get()) != nullptr;
    }
    return k;
  }
};

// fix rigid/small: the same integrator, bodies from a custom per-atom ID only.
struct FixRigidSmall : FixRigid {
  FixRigidSmall(Simulation& s, const Args& a) : FixRigid(s, a, true) {}
};

SABLE_FIX("rigid", FixRigid);
SABLE_FIX("rigid/small", FixRigidSmall);

}  // namespace sable
