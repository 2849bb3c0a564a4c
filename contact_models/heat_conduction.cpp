#include "contact_models/heat_conduction.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "core/engine/atoms.h"

namespace sable {

namespace {
constexpr double kSmallConductivity = 1e-5;  // LIGGGHTS' SMALL: below it a grain does not conduct
}

HeatConduction::HeatConduction() { loop_ = make_contact_loop<0>(*this); }

double HeatConduction::contact_area(double r, double ri, double rj, Area mode, double constant_area) {
  switch (mode) {
    case Area::Constant: return constant_area;
    case Area::Projection: {
      const double rmax = std::max(ri, rj);
      return std::numbers::pi * rmax * rmax;
    }
    case Area::Overlap: break;
  }
  // Radius^2 of the circle where the spheres meet, times pi (Heron-like product of the four gaps).
  return -std::numbers::pi / 4.0 * ((r - ri - rj) * (r + ri - rj) * (r - ri + rj) * (r + ri + rj)) / (r * r);
}

double HeatConduction::conductance(double ki, double kj, double area) {
  if (ki < kSmallConductivity || kj < kSmallConductivity) return 0.0;
  return 4.0 * ki * kj / (ki + kj) * std::sqrt(area);
}

void HeatConduction::flows(Atoms& at, const NeighborList& list, long list_version, const double* temp,
                           const double* k, std::uint32_t groupbit, std::vector<double>& flow) {
  const std::size_t n = list.first.empty() ? 0 : list.first.size() - 1;
  if (n == 0) return;
  scatter_.assign(3 * n, 0.0);
  torque_.assign(3 * n, 0.0);
  PairBatch b;
  // The force pass's view of the atoms, but the loop's "forces" go to scatter_
  // and no spin is read or torque made (Kinematics::Frozen).
  b.a = atom_view(at, n, 0);
  b.a.f = scatter_.data();
  b.a.torque = torque_.data();
  b.a.rotation = false;
  b.a.plane_2d = false;
  b.first = list.first.data();
  b.jlist = list.j.data();
  b.shift = list.shift.data();
  b.shift_vec = list.shift_vec;
  b.span = list.span;
  b.list_version = list_version;
  b.split = nullptr;  // the per-atom passes keep following the force pass's ranges
  temp_ = temp;
  k_ = k;
  mask_ = at.mask.data();
  groupbit_ = groupbit;
  loop_->pair_forces(b);
  for (std::size_t i = 0; i < n; ++i) flow[i] += scatter_[3 * i];
}

void HeatConduction::evaluate(PairChunk<0>& ch, double, bool, Simd, Kinematics) const {
  const int n = ch.n;
  for (int m = 0; m < n; ++m) {
    const int i = ch.i[m], j = ch.j[m];
    const double r = std::sqrt(ch.dx[m] * ch.dx[m] + ch.dy[m] * ch.dy[m] + ch.dz[m] * ch.dz[m]);
    const double area = contact_area(r, ch.radi[m], ch.radj[m], area_mode, constant_area);
    const double hc = conductance(k_[ch.itype[m]], k_[ch.jtype[m]], area);
    const bool conducts = ((mask_[i] | mask_[j]) & groupbit_) != 0;
    ch.f[0][m] = conducts ? (temp_[j] - temp_[i]) * hc : 0.0;
    ch.f[1][m] = ch.f[2][m] = 0.0;
  }
}

// Walls carry no heat (LIGGGHTS' wall/gran `temperature` keyword is not supported).
void HeatConduction::evaluate(WallChunk<0>& ch, double, bool, Simd, Kinematics) const {
  for (int m = 0; m < ch.n; ++m) ch.f[0][m] = ch.f[1][m] = ch.f[2][m] = 0.0;
}

}  // namespace sable
