#pragma once
// pair_style gran model M [tangential T] [cohesion off] [rolling_friction R]
//            [surface default] [keyword on|off ...]      + pair_coeff * *
// LIGGGHTS 3.8's granular pair style: the models pick a precompiled kernel
// (contact_models/registry.h); coefficients come from fix property/global.
//
// Contact history when two grains separate: sable zeroes it at once (default).
// LIGGGHTS 3.8 does not: its pair loop calls surfacesClose() only within the
// cohesion distance (contactDistanceFactor > 1), so without cohesion the
// tangential spring of a separated pair survives until the next neighbour
// rebuild, where only pairs overlapping at that moment keep their history
// (neigh_gran.cpp). A pair that separates and touches again before the next
// rebuild thus restarts with its old spring, which makes results depend on
// skin and rebuild timing. `historyResetAtRebuild on` (sable addition)
// reproduces that behaviour exactly, for bit-level comparisons with LIGGGHTS.
// Walls reset at separation in both codes.
#include <cstdint>
#include <memory>
#include <vector>

#include "contact_models/kernel.h"
#include "core/engine/contact_source.h"
#include "core/engine/neighbor.h"
#include "core/engine/pair.h"

namespace sable {

class PairGran : public Pair, public ContactSource {
 public:
  PairGran(Simulation& sim, const Args& args);
  void coeff(const Args& args) override;
  void export_yade(YadeScript& s) const override;  // contact_models/pair_gran_yade.cpp
  void init() override;
  void compute() override { compute_then(RangeTail{}); }
  void compute_then(const RangeTail& tail) override;
  ContactStore* history() override { return kernel_->history_slots().empty() ? nullptr : &store_; }
  double contact_time(std::size_t i, std::size_t j, double v) const override;
  double rayleigh_time(std::size_t i) const override;
  std::string describe() const override;

  ContactKernel& kernel() { return *kernel_; }
  // ContactSource: both grains of a record in `groupbit`.
  Kind contact_kind() const override { return Kind::Pairs; }
  std::string law_name() const override { return kernel_->name(); }
  const std::vector<HistorySlot>& history_slots() const override { return kernel_->history_slots(); }
  void records(std::uint32_t groupbit, ContactRecords& out) override;
  void ids_renumbered(const std::vector<long>& o, const std::vector<long>& n) override { store_.ids_renumbered(o, n); }

 private:
  std::unique_ptr<ContactKernel> kernel_;
  bool connected_ = false;  // the law has its per-type coefficients (init ran)
  ContactStore store_;
  bool coeff_set_ = false;
  bool setup_pass_ = true;  // the first force pass after init() is LIGGGHTS' setup: history not advanced
  bool keep_history_until_rebuild_ = false;
  long last_builds_ = -1;
  std::uint32_t freeze_bit_ = 0;
  std::vector<double> shear_modulus_, poisson_;  // per type, for the Rayleigh time (empty: no Y/nu given)
  PairBatch batch();
};

// FixFreeze-style groups that count as infinitely heavy in m*: the groupbits of every `fix freeze`.
std::uint32_t frozen_groupbits(const Simulation& sim);

}  // namespace sable
