#pragma once
// fix ID group wall/gran model M [tangential T] [rolling_friction R] primitive type T
//     xplane|yplane|zplane POS | xcylinder|ycylinder|zcylinder R C1 C2
//     [shear x|y|z V] [wiggle amplitude A period P] [keyword on|off ...]
// LIGGGHTS 3.8 primitive granular walls. The wall is a partner of infinite
// radius and mass (R* = r_i, m* = m_i) of material type T, and uses the same
// compiled kernel as `pair_style gran` with the same model names. Planes act on
// grains on either side; cylinders on grains inside or outside.
//   shear: planes move tangentially at V; a cylinder moves along its axis at V
//          (dim = axis) or spins about it with wall velocity V e_axis x r_radial
//          (dim != axis: LIGGGHTS' code treats V as an angular velocity, rad/s).
//   wiggle (sable addition, LIGGGHTS-PUBLIC has none for primitives): a plane
//          moves along its normal as POS + A sin(2 pi t / P), t from the fix's creation.
// Outputs (sable addition): f_ID[1..3] = total force exerted by the grains ON the
// wall at the last force evaluation. The contacts' history (tangential spring,
// rolling spring) is kept by grain id (core's HistoryStore), and in restart files.
#include <memory>
#include <vector>

#include "contact_models/kernel.h"
#include "core/engine/block_sum.h"
#include "core/engine/contact_source.h"
#include "core/engine/fix.h"
#include "core/engine/threads.h"
#include "core/engine/history_store.h"

namespace sable {

class FixWallGran : public Fix, public ContactSource {
 public:
  FixWallGran(Simulation& sim, const Args& args);
  void export_yade(YadeScript& s) const override;  // fixes/fix_wall_gran_yade.cpp
  void init() override;
  void begin(FixHook) override;
  void range(FixHook, const AtomRange& r) override;
  void end(FixHook) override;
  double compute_vector(int i) override;  // 1..3: force on the wall
  bool write_state(std::string& out) const override;  // the contacts' history
  void read_state(const std::string& in) override;
  const HistoryStore& history() const {  // the last pass's contacts, by grain id
    keep_places();
    return hist_;
  }
  double max_speed() const override;

  ContactKernel& kernel() { return *kernel_; }
  int wall_type() const { return type_; }
  // ContactSource. last_pass: the contacts of the last force pass (the one f_ID
  // reports), in its order, while the atoms are not sorted or deleted since.
  Kind contact_kind() const override { return Kind::Wall; }
  std::string law_name() const override { return kernel_->name(); }
  const std::vector<HistorySlot>& history_slots() const override { return kernel_->history_slots(); }
  void records(std::uint32_t groupbit, ContactRecords& out) override;
  const double* wall_point(int k) const override { return &records_.point[3 * k]; }
  const double* wall_velocity(int k) const override { return &records_.vwall[3 * k]; }
  bool last_pass(const PassFn& fn) const override;
  void ids_renumbered(const std::vector<long>& o, const std::vector<long>& n) override;
  std::vector<HistoryStore*> histories_by_grain() override {
    keep_places();
    near_builds_ = -1;  // the places reload from hist_ at the next pass
    return {&hist_};
  }
  void history_moved() override { hist_.sort(); }
  int plane_axis() const override { return shape_ == Shape::Plane ? axis_ : -1; }

 private:
  std::unique_ptr<ContactKernel> kernel_;
  enum class Shape { Plane, Cylinder } shape_ = Shape::Plane;
  int axis_ = 2;                 // plane normal / cylinder axis
  double pos0_ = 0, radius_ = 0, c1_ = 0, c2_ = 0;
  int shear_dim_ = -1;
  double vshear_ = 0;
  double wiggle_amp_ = 0, wiggle_period_ = 0;
  long wiggle_step0_ = 0;
  int type_ = 1;
  int hist_size_ = 0;
  // The history lives by near-list place between neighbour rebuilds (atom
  // indices hold: O(1) per contact), and by grain id in hist_ across them, in
  // restart files and renumberings: keep_places() brings hist_ up to date,
  // load_places() fills the places from it after the near list is refreshed.
  mutable HistoryStore hist_;
  std::vector<double> place_hist_;  // per near place: its row
  std::vector<long> place_pass_;    // per near place: the last pass that touched it
  std::vector<long> near_id_;       // per near place: the grain's id at the refresh
  long last_pass_ = 0, pass_no_ = 0;
  mutable bool store_behind_ = false;  // a pass changed the places since hist_ was kept
  void keep_places() const;
  void load_places();
  bool setup_pass_ = true;
  std::uint32_t freeze_bit_ = 0;
  double force_[3] = {0, 0, 0};
  // Overlapping grains found by one search: atom index, its place in the near
  // list, overlap, unit normal, wall velocity, wall point and (force pass)
  // force per contact; records() copies the history into hist (row per
  // contact, index in row). Own cache lines: each thread grows its own.
  struct alignas(64) Staged {
    std::vector<int> atom, place, row;
    std::vector<double> deltan, en, vwall, point, force, hist;
    void clear();
  };
  // Wall position along its normal and normal velocity at this step (wiggle).
  struct Now {
    double pos, vnormal;
  };
  // The force pass: each thread's contacts (Atoms::split ranges, in order),
  // the wall's state and whether history is updated (begin).
  ThreadParts<Staged> parts_;
  Now pass_now_{0.0, 0.0};
  bool pass_update_ = true;
  std::size_t pass_atoms_ = 0;
  Staged records_;  // the contacts of the last records() call

  // Grains that can reach the wall before the next neighbour rebuild (indices
  // hold until then): the per-step search looks at these only.
  std::vector<int> near_;
  long near_builds_ = -1;
  std::size_t near_n_ = 0;
  void refresh_near();

  Now now() const;
  bool geometry(std::size_t i, const Now& w, double n[3], double vw[3], double& dist) const;
  // Appends the overlapping grains of near_[c0, c1) in the fix group that also match `also`.
  void collect(std::size_t c0, std::size_t c1, std::uint32_t also, const Now& w, Staged& out) const;
  WallBatch batch(Staged& s);
  // The force pass's contacts take their rows in place_hist_; a contact the
  // last pass did not have starts at zero.
  void pass_history(const Staged& s, WallBatch& b);
  // A copy of the last pass's history of the staged contacts (records()).
  void copy_history(Staged& s, WallBatch& b) const;
  BlockSum<3> sum_;  // the total force on the grains, in fixed blocks of the near list
};

}  // namespace sable
