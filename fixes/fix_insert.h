#pragma once
// Shared part of LIGGGHTS' region insertion fixes (insert/pack,
// insert/rate/region): the general keywords (seed, distributiontemplate,
// insert_every, start, maxattempt, overlapcheck, all_in, vel, omega, ...) and
// the region ones (region, ntry_mc, check_dist_from_subdomain_border); the
// region's sampling box, all_in distance and volume; overlap-free random
// placement; adding the grains; the INFO lines; f_ID[1] (grains inserted) and
// f_ID[2] (their mass); and the restart state. A style says how many grains
// each insertion step wants and when it is done; a style that inserts
// elsewhere than in a region (insert/stream) says where instead.
#include <array>
#include <limits>
#include <string>
#include <vector>

#include "core/engine/fix.h"
#include "fixes/fix_particledistribution_discrete.h"

namespace sable {

class Region;

class FixInsert : public Fix {
 public:
  FixInsert(Simulation& s, const Args& a);
  void init() override;
  void post_integrate() override;
  void post_run() override;
  double compute_vector(int i) override;
  bool write_state(std::string& out) const override;
  void read_state(const std::string& in) override;

 protected:
  // Parses words 6..: the shared keywords here, a style's own through
  // own_keyword(); then the checks common to all styles (call from the
  // style's constructor, where its overrides are in place).
  void parse(const Args& a);
  // Consumes a style keyword at a[i] (advancing i); false if a[i] is none.
  virtual bool own_keyword(const Args& a, std::size_t& i) = 0;
  // After parsing: the style's own required keywords and their consistency.
  virtual void check_own(const Args& a) = 0;
  // The keywords of this style, for the error on an unknown one.
  virtual std::string keyword_list() const = 0;
  // How many grains this insertion step wants; `filled` (0..1) is the part of
  // the target already there, which widens the try budget as LIGGGHTS does.
  virtual long wanted(double& filled) = 0;
  // The step after an insertion at next_step_, or -1 when the fix is done.
  virtual long following_step() const { return insert_every_ > 0 ? next_step_ + insert_every_ : -1; }
  // INFO line(s) at the first run.
  virtual void announce();
  // Styles that insert in a volume of their own (not a `region`) say false and
  // override random_position(), setting slo_/shi_ (the box of the volume).
  virtual bool uses_region() const { return true; }
  // A uniformly random position of a grain of radius r in the insertion volume.
  virtual void random_position(double r, double* x);
  // Without overlapcheck too, positions within r of a box face are drawn again
  // within the try budget (LIGGGHTS insert/stream; the region styles keep the first).
  virtual bool keeps_off_faces_always() const { return false; }
  // The velocity and spin a new grain starts with (default: `vel`, `omega`).
  virtual void start_motion(double* v, double* w);
  // The `vel` keyword's velocity, its fluctuation drawn from rng_.
  void draw_velocity(double* v);
  // The grains just added are atoms first..n-1 (in placement order).
  virtual void inserted(std::size_t /*first*/) {}
  // The step counter jumped by delta between runs (reset_timestep): move
  // whatever the style keeps in steps (next_step_ is moved already).
  virtual void shift_steps(long /*delta*/) {}

  int dim() const;
  double grain_volume(double r) const;
  long drawable(long want) const;  // at most what could ever fit (see fix_insert.cpp)
  // Grains (count, volume, mass) whose centre is in the region, any group; a
  // multisphere clump counts once, by its centre of mass (LIGGGHTS).
  void region_content(long& np, double& vol, double& mass) const;

  long seed_ = 0, insert_every_ = -1, next_step_ = -1, maxattempt_ = 50, ntry_mc_ = 100000;
  bool every_given_ = false, once_allowed_ = true;  // insert/rate/region forbids insert_every once
  FixParticledistributionDiscrete* dist_ = nullptr;
  Region* region_ = nullptr;
  double region_volume_ = 0;
  Rng rng_, pos_rng_;
  long ninserted_ = 0;
  double mass_inserted_ = 0;
  bool overlap_ = true, all_in_ = false;
  int vstyle_ = 0;  // vel constant, uniform, gaussian
  double v_[3] = {0, 0, 0}, dv_[3] = {0, 0, 0}, w_[3] = {0, 0, 0};
  double slo_[3], shi_[3];  // where positions are drawn: region bounds within the box

 private:
  bool exact_ = true, verbose_ = true, announced_ = false, border_gap_ = true;
  // sim.step when this fix last saw it (construction, end of a run, restart):
  // a different step at the next init is a reset_timestep, which moves the
  // insertion schedule with it (LIGGGHTS 3.8).
  long step_seen_ = -1;
  enum class Orient { Template, Random, Constant } orient_ = Orient::Template;  // LIGGGHTS' default: template
  std::array<double, 4> quat_{1, 0, 0, 0};  // orientation constant
  std::vector<std::array<double, 4>> q_;    // per placed grain: its rotation (clumps)
  std::string dist_id_, region_id_;
  bool warned_all_in_ = false;

  bool shared_keyword(const Args& a, std::size_t& i);
  void setup_geometry();
  bool in_region(const double* x, double r);
  bool near_box_face(const double* x, double r) const;
  std::array<double, 4> orientation();
  std::size_t place(const std::vector<FixParticledistributionDiscrete::Grain>& grains, double filled,
                    std::vector<double>& pos);
  void insert();
  void insert_clump(const FixParticledistributionDiscrete::Grain& G, const double* x, const std::array<double, 4>& q,
                    const double* v);
};

// The styles driven by a rate (insert/rate/region, insert/stream): `nparticles
// N|INF` or `mass M|INF` (N = int(M / expected grain mass)), `particlerate R`
// or `massrate MR` (R = MR / expected grain mass). Every insert_every_ steps
// from the start step they ask for int(n + u) grains, n = R K dt, u uniform in
// [0, 1), never more than what remains of N, and stop once N are in (LIGGGHTS
// 3.8). Grains that found no place are not carried over.
class FixInsertRated : public FixInsert {
 public:
  FixInsertRated(Simulation& s, const Args& a) : FixInsert(s, a) {}
  void init() override;  // the counts follow dt, which the deck may change between runs

 protected:
  static constexpr long kUnlimited = std::numeric_limits<long>::max();
  long ninsert_ = 0;  // grains to insert in all (kUnlimited for INF)
  double mass_total_ = 0, particle_rate_ = 0, mass_rate_ = 0, per_step_ = 0;

  // nparticles, mass, particlerate, massrate at a[i] (advancing i); false if none.
  bool rate_keyword(const Args& a, std::size_t& i);
  void check_rate(const Args& a) const;  // exactly one of each pair
  // At init, before the counts: a style that derives insert_every_ does so here.
  virtual void schedule() {}
  long wanted(double& filled) override;
  long following_step() const override { return ninserted_ >= ninsert_ ? -1 : next_step_ + insert_every_; }
  void announce() override;

 private:
  int totals_ = 0, rates_ = 0;
};

}  // namespace sable
