#pragma once
// compute ID group stress/cg kernel lucy|gauss W grid xlo xhi nx ylo yhi ny zlo zhi nz
//         [frame mesh MESHFIXID]                                  (sable addition)
// Coarse-grained density, volume fraction, mean velocity and stress of the
// group's grains on a regular grid (Goldhirsch 2010; Weinhart et al. 2012):
//   rho = sum m_i W(x - x_i),  phi = sum V_i W(x - x_i),  u = sum m_i v_i W / rho,
//   stress_contact = sum_contacts sym(f_ij (x) b_ij) int_0^1 W(x - x_i + s b_ij) ds,
//   stress_kinetic = sum m_i (v_i - u(x)) (x) (v_i - u(x)) W(x - x_i),
//   stress = contact + kinetic, compression positive.
// Contacts: every pair contact with both grains in the group (b = x_i - x_j,
// f the force on i; each pair once) and every wall contact of fix wall/gran
// (primitive and mesh) with its grain in the group (b from the contact point
// to the grain centre). Kernel, node positions and field order: computes/cg_field.h.
// Periodic boxes: grains and branches count with every image within reach of the grid.
// frame mesh ID (a fix mesh/surface or mesh/surface/stress): grid coordinates
// are the mesh's body coordinates (node world position R x + T of its current
// pose), and u and the stresses are given in the body axes (R^T u, R^T s R);
// u is the grains' velocity (not relative to the moving frame) in those axes.
// Output: a global vector of nodes * 23 values, node-major (c_ID[23 n + f + 1]);
// fix ave/cg averages and writes the whole grid. Evaluated only when asked,
// at most once a step.
#include <memory>
#include <vector>

#include "computes/cg_field.h"
#include "core/engine/compute.h"

namespace sable {

class FixMeshSurface;

class ComputeStressCG : public Compute {
 public:
  ComputeStressCG(Simulation& sim, const Args& args);
  void init() override;
  double compute_vector(int i) override;
  // The fields now (kFields per node), evaluated at most once a step.
  const std::vector<double>& fields();
  const CgField& field() const { return *field_; }
  const double* lo() const { return lo_; }
  const double* hi() const { return hi_; }
  std::string frame() const { return frame_id_.empty() ? "world" : "mesh " + frame_id_; }

 private:
  std::unique_ptr<CgField> field_;
  std::vector<double> out_;
  double lo_[3], hi_[3];
  std::string frame_id_;
  std::size_t frame_at_ = 0;  // the word naming the mesh fix (errors)
  FixMeshSurface* frame_ = nullptr;

  void parse(const Args& a);
  void evaluate();
  // Calls put(x) with each periodic image of the box [a, b] (world) that comes within reach of the grid.
  template <class Put>
  void images(const double a[3], const double b[3], Put&& put) const;
  double reach_lo_[3], reach_hi_[3];  // world box of the grid plus the kernel's support
  void reach_box();
  void to_grid(const double xw[3], double out[3]) const;  // world point -> grid coordinates
  void dir_to_grid(const double vw[3], double out[3]) const;
};

}  // namespace sable
