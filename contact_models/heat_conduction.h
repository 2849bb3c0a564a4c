#pragma once
// Heat conduction through grain-grain contacts, as LIGGGHTS 3.8's fix
// heat/gran/conduction (after Chaudhuri et al., Chem. Eng. Sci. 61, 6348, 2006):
//   heat flow into i:  Q = h_c (T_j - T_i),   h_c = 4 k_i k_j / (k_i + k_j) sqrt(A)
// with k the thermalConductivity of each grain's type (h_c = 0 when either is
// below 1e-5) and A the contact area: `overlap` (default) the disc where the
// two spheres intersect, -pi/4 (r-ri-rj)(r+ri-rj)(r-ri+rj)(r+ri+rj) / r^2 at
// centre distance r; `projection` pi max(ri, rj)^2; `constant` a given area.
//
// A law of the contact loop (core/engine/contact_loop.h) like the force laws: the
// loop finds the touching pairs of the half list (r < ri + rj, the force
// pass's own test), gathers them into columns and scatters in list order with
// its threads; this law writes each contact's heat flow into i in force
// column 0, and the scatter adds it to i and subtracts it from j, so heat is
// conserved to round-off and the sums are the same for any thread count.
#include <cstdint>
#include <memory>
#include <vector>

#include "core/engine/contact_loop.h"

namespace sable {

class Atoms;

class HeatConduction final : public ColumnLaw<0> {
 public:
  enum class Area { Overlap, Projection, Constant };
  HeatConduction();

  // Per-contact formulas (also what the unit tests check).
  static double contact_area(double r, double ri, double rj, Area mode, double constant_area);
  static double conductance(double ki, double kj, double area);

  Area area_mode = Area::Overlap;
  double constant_area = 0.0;

  // Adds each touching pair's heat flow to flow[i] (and -flow to flow[j]);
  // flow has one double per atom and must cover the list's atoms. A contact
  // conducts when i or j is in `groupbit` (LIGGGHTS: grains outside the group
  // still exchange heat with it). `k` is indexed by atom type (1..ntypes),
  // `temp` by atom. The list must describe the current atoms.
  void flows(Atoms& atoms, const NeighborList& list, long list_version, const double* temp, const double* k,
             std::uint32_t groupbit, std::vector<double>& flow);

  void evaluate(PairChunk<0>& ch, double dt, bool update, Simd simd, Kinematics kin) const override;
  void evaluate(WallChunk<0>& ch, double dt, bool update, Simd simd, Kinematics kin) const override;

 private:
  std::unique_ptr<ContactLoop> loop_;
  // 3 per atom: the loop scatters vectors (component 0 is the flow) and, on
  // threads, adds (zero) torques too.
  std::vector<double> scatter_, torque_;
  // Bound for one flows() call (read by evaluate on every thread).
  const double* temp_ = nullptr;
  const double* k_ = nullptr;
  const std::uint32_t* mask_ = nullptr;
  std::uint32_t groupbit_ = 0;
};

}  // namespace sable
