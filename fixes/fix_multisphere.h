#pragma once
// fix ID group multisphere [allow_group_and_set yes|no] [allow_heatsource yes|no]
// LIGGGHTS 3.8's integrator of clumps: every body that an insertion fix makes
// from a fix particletemplate/multisphere joins this fix (one per deck) and
// moves as one rigid body, as fix rigid does (fixes/rigid_body_set.h).
// LIGGGHTS' conventions: each member sphere carries the body's mass (so
// contacts and per-atom outputs see it), gravity acts on the body (M g at its
// centre of mass) and not on the members, spheres of one body never pair,
// fflag/tflag come from the template. No f_ID outputs (LIGGGHTS defines none);
// compute ke/multisphere and erotate/multisphere read the bodies.
#include <cstddef>
#include <vector>

#include "core/engine/fix.h"
#include "fixes/fix_particletemplate_multisphere.h"
#include "fixes/rigid_body_set.h"

namespace sable {

// The orientation of a clump inserted with rotation q_ins: the template's body
// axes turned by q_ins (q_body), and the spheres' offsets from the centre of mass in the world frame.
std::vector<rigid::V3> clump_offsets(const ClumpShape& shape, const rigid::Q4& q_ins, rigid::Q4& q_body);

class FixMultisphere : public Fix {
 public:
  FixMultisphere(Simulation& s, const Args& a);
  void export_yade(YadeScript& s) const override;  // fixes/fix_multisphere_yade.cpp
  void init() override;
  void setup() override;
  void initial_integrate() override;
  void final_integrate() override;
  const RigidBodies* rigid_bodies() const override { return &set_; }
  bool write_state(std::string& out) const override;
  void read_state(const std::string& in) override;

  // A clump from an insertion: atoms first .. first + shape.displace.size() - 1
  // are its spheres (added by the caller, with the body's mass); this places
  // them and makes the body (centre xcm, rotation q_ins, velocity v, spin w).
  void add_body(const ClumpShape& shape, const double xcm[3], const rigid::Q4& q_ins, const double v[3],
                const double w[3], std::size_t first);
  const std::vector<rigid::Body>& bodies() const { return set_.bodies; }  // in the set's order (rigid_body_set.h)
  const rigid::Body& body(int n) const { return set_.by_number(n); }     // the n-th inserted (body_of's numbers)
  // 1/2 M vcm^2 and 1/2 sum I_k w_k^2 (body frame) over all bodies.
  double kinetic_energy() const;
  double rotational_energy() const;

 private:
  rigid::BodySet set_;
  int pair_col_ = -1;
  void sum_forces();
  void check_integrators(std::size_t first, std::size_t n) const;
};

}  // namespace sable
