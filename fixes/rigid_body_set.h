#pragma once
// Rigid bodies of member grains, shared by fix rigid / rigid/small (bodies
// from groups or IDs, mass and inertia from the member spheres) and fix
// multisphere (LIGGGHTS clumps inserted from templates, mass and inertia from
// the template): the body state, LAMMPS' NVE integration with Richardson
// iteration for the orientation, placing the members from their body, and
// summing member forces into body force and torque.
//
// The integration runs serially (initial_integrate, sum_forces, final_integrate)
// or as the step plan's per-atom tasks in two phases (Fix::two_phase_tasks):
// in phase 0 each thread advances the bodies whose first member lies in its atom
// range, summing each body over its members in atom order (the same bits for any
// split); in phase 1 each thread places the members in its range.
//
// Per atom, one extra column of kStride doubles: body index + 1 (0: in no
// body), the offset from the centre of mass in the body frame (3) and in the
// world frame (3).
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "core/engine/fix.h"
#include "core/engine/rigid_bodies.h"

namespace sable {

class Simulation;

namespace rigid {

using V3 = std::array<double, 3>;
using Q4 = std::array<double, 4>;  // w, x, y, z

inline V3 cross(const V3& a, const V3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
inline double dot(const V3& a, const V3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

// Columns of the rotation matrix of unit quaternion q: the body axes in the world frame.
void axes(const Q4& q, V3& ex, V3& ey, V3& ez);
void normalize(Q4& q);
// Angular velocity from angular momentum m, body axes and inverse principal moments
// (0 for a zero moment: no spin about that axis).
V3 omega_of(const V3& m, const V3& ex, const V3& ey, const V3& ez, const V3& inv);

// The fields the per-atom passes read come first, in as few cache lines as they fit
// (place_members: xcm .. ez; sum_forces: force, torque).
struct alignas(64) Body {
  V3 xcm{}, vcm{}, omega{};                  // xcm unwrapped
  V3 ex{1, 0, 0}, ey{0, 1, 0}, ez{0, 0, 1};  // the body axes, axes(q), kept with q
  V3 force{}, torque{};                      // sums over the members, before the flags
  double mass = 0, inv_mass = 0;
  V3 angmom{}, moments{}, inv_moments{};
  Q4 q{1, 0, 0, 0};
  std::array<bool, 3> fflag{true, true, true}, tflag{true, true, true};
  int members = 0;
  // What fix damping/cundall adds to force and torque (BodySet::damping), set
  // with each sum and applied by both half kicks; not in the sums above.
  V3 fdamp{}, tdamp{};
};

// Principal moments (one below 1e-7 of the largest set to zero: no spin about
// that axis, as LAMMPS) and the orientation quaternion of the right-handed principal axes.
void principal_axes(Body& b, const Eigen::Matrix3d& inertia);

// The owning fix's rigid_bodies(): bodies by the deck's numbers.
class BodySet : public RigidBodies {
 public:
  static constexpr int kStride = 7;
  // Bodies are kept in the order the (bin-sorted) atoms first meet them,
  // renumbered after each neighbour build, so that the per-atom passes walk the
  // bodies forwards. number[k] is body k's number as the deck counts them (f_ID
  // rows, flags, messages; from 0: a body appended later gets the next one).
  std::vector<Body> bodies;
  std::vector<int> number;
  int col = -1;  // the per-atom column
  // Cundall's local damping of whole bodies, one entry per fix damping/cundall
  // (in fix order): a body with a member in the group gets its summed force
  // and torque damped against its own vcm and omega (not each member's).
  struct Damping {
    std::uint32_t groupbit;
    double alpha;
  };
  std::vector<Damping> damping;
  void find_damping();  // from the simulation's fixes; each run's init
  void damp_again();     // after the owner changed the sums (multisphere's gravity)

  explicit BodySet(Simulation& s) : sim_(s) {}
  // RigidBodies: the deck's number of atom i's body, a body's force, and (members
  // that carry the body's mass: fix multisphere) the bodies' 1/2 M vcm^2.
  int body_of(std::size_t i) const override { return number_of_atom(i); }
  const double* body_force(int n) const override { return by_number(n).force.data(); }
  bool body_kinetic_energy(double& ke) const override;
  bool members_carry_mass = false;
  double translational_energy() const;  // 1/2 M vcm^2 over all bodies

  int body_of_atom(std::size_t i) const;  // its slot in `bodies`; -1: in no body
  int number_of_atom(std::size_t i) const {  // the deck's number of its body; -1: in no body
    const int k = body_of_atom(i);
    return k < 0 ? -1 : number_of(k);
  }
  static bool rotates(const Body& b) {
    return b.tflag[0] || b.tflag[1] || b.tflag[2] || b.angmom[0] != 0 || b.angmom[1] != 0 || b.angmom[2] != 0;
  }
  bool any_rotates() const;

  // First half of the NVE step (half kick, drift, orientation), then the members placed.
  void initial_integrate(double dt);
  // Second half kick from the summed force and torque, then the members' velocities.
  void final_integrate(double dt);
  // Members from their body: the offset turned to the body's orientation (kept
  // as it is when the body cannot turn), the position wrapped into the box,
  // v = vcm + w x d, and each sphere's spin the body's.
  void place_members(bool positions);
  // Force and torque on each body about its centre: the members' forces, their
  // moments d x f, and the members' own torques (serial, in atom order: the
  // same bits for any thread count).
  void sum_forces();
  // The same steps as the plan's two-phase tasks (see the top of this file):
  // begin_task serially before each, then the phases on every atom range:
  // phase 0 advances the bodies a thread owns, phase 1 places its members. The
  // final task's phase 0 leaves each body ready for the next first half (omega
  // included), so that the plan may skip its phase 1 when that half follows.
  void begin_task();
  void initial_range(const Fix::AtomRange& r, double dt);
  void final_range(const Fix::AtomRange& r, double dt);
  // Where place_members would put grain i of body k, and its velocity.
  void expected(std::size_t i, int k, double* x, double* v) const;
  // The body the deck numbers n (from 0), and the deck's number of body k.
  // (Bodies appended since the last renumbering keep their place: slot == number.)
  int slot(int n) const { return n < static_cast<int>(slot_.size()) ? slot_[n] : n; }
  const Body& by_number(int n) const { return bodies[slot(n)]; }
  int number_of(int k) const { return k < static_cast<int>(number.size()) ? number[k] : k; }
  // number[] given (restart): slot() follows it.
  void numbers_read();
  // Renumbers the bodies in the atoms' order if the atoms were sorted, added or
  // removed since the last look, and lists each body's members in atom order.
  void follow_atom_order();

 private:
  Simulation& sim_;
  std::vector<char> turning_;  // rotates(body), taken once per placing pass
  long builds_seen_ = -1;      // neighbour builds (each sorts the atoms) at the last renumbering
  std::size_t atoms_seen_ = 0, bodies_seen_ = 0;
  std::vector<int> slot_, new_index_;
  std::vector<Body> scratch_;
  // Body k's members: member_[start_[k] .. start_[k + 1]) in atom order; first_[k]
  // its first member (the atom count for a body without members): ascending in k.
  std::vector<int> start_, member_;
  std::vector<std::size_t> first_;
  void number_new_bodies();
  void list_members();
  void owned(const Fix::AtomRange& r, int& k0, int& k1) const;  // the bodies of r's thread
  void sum_body(int k);
  void damp(Body& b, std::uint32_t mask) const;
  void advance(int k0, int k1, double dt);
  void turn(int k0, int k1, double dt);
  void place_range(std::size_t lo, std::size_t hi, bool positions);
};

}  // namespace rigid
}  // namespace sable
