// The shared part of the region insertion fixes; see fixes/fix_insert.h.
// LIGGGHTS 3.8 semantics: at each insertion step the style says how many
// grains it wants; they are drawn from the distribution (largest first) and
// placed at random in the region (whole grain inside with all_in yes), without
// overlap (with each other and with every existing grain, periodic images
// included) when overlapcheck is yes, within a budget of M tries per grain.
// Like LIGGGHTS on one process, overlap-checked grains keep one radius away
// from the box faces (check_dist_from_subdomain_border yes). New atoms get the
// next free IDs and join "all", this fix's group and the groups of the
// distribution and template fixes. sable extension: in 2D it inserts discs at
// z = 0 (mass pi r^2 rho) and volumes are areas.
#include "fixes/fix_insert.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>

#include "core/io/restart.h"
#include "core/engine/simulation.h"
#include "fixes/fix_multisphere.h"

namespace sable {
namespace {

// Cell grid over the insertion zone for the overlap check: cells at least one
// contact distance wide, so a candidate is tested against 27 (9 in 2D) cells.
// Periodic axes span the whole box and wrap, with minimum-image distances.
class OverlapGrid {
 public:
  OverlapGrid(const Domain& d, const double* lo, const double* hi, double cut) : dim_(d.dimension) {
    double span[3];
    for (int k = 0; k < 3; ++k) {
      wrap_[k] = d.wraps(k);
      lo_[k] = wrap_[k] ? d.lo[k] : lo[k] - cut;
      span[k] = wrap_[k] ? d.length(k) : hi[k] - lo[k] + 2 * cut;
      L_[k] = d.length(k);
    }
    // Bound the cell count (a big box and a small region): wider cells stay correct.
    for (double c = cut;; c *= 1.26) {
      double cells = 1;
      for (int k = 0; k < 3; ++k) {
        n_[k] = k < dim_ ? std::max(1, static_cast<int>(std::min(span[k] / c, 1e6))) : 1;
        inv_[k] = n_[k] / span[k];
        cells *= n_[k];
      }
      if (cells <= 4e6) break;
    }
    head_.assign(static_cast<std::size_t>(n_[0]) * n_[1] * n_[2], -1);
  }
  bool covers(const double* x) const {
    for (int k = 0; k < dim_; ++k)
      if (!wrap_[k] && (x[k] < lo_[k] || x[k] > lo_[k] + n_[k] / inv_[k])) return false;
    return true;
  }
  void add(const double* x, double r) {
    const std::size_t c = index(x);
    for (int k = 0; k < 3; ++k) xs_.push_back(x[k]);
    rs_.push_back(r);
    next_.push_back(head_[c]);
    head_[c] = static_cast<int>(rs_.size()) - 1;
  }
  // True when a sphere (x, r) would overlap a stored one (distance < sum of radii).
  bool overlaps(const double* x, double r) const {
    int c[3], lo[3], hi[3];
    for (int k = 0; k < 3; ++k) {
      c[k] = cell(x, k);
      if (k >= dim_)
        lo[k] = hi[k] = 0;
      else if (wrap_[k])
        lo[k] = n_[k] >= 3 ? -1 : 0, hi[k] = n_[k] >= 3 ? 1 : n_[k] - 1;
      else
        lo[k] = -std::min(1, c[k]), hi[k] = std::min(1, n_[k] - 1 - c[k]);
    }
    for (int dz = lo[2]; dz <= hi[2]; ++dz)
      for (int dy = lo[1]; dy <= hi[1]; ++dy)
        for (int dx = lo[0]; dx <= hi[0]; ++dx) {
          const int q[3] = {dx, dy, dz};
          std::size_t cc = 0;
          for (int k = 2; k >= 0; --k) cc = cc * n_[k] + (c[k] + q[k] + n_[k]) % n_[k];
          for (int j = head_[cc]; j >= 0; j = next_[j]) {
            double d2 = 0;
            for (int k = 0; k < dim_; ++k) {
              double dk = x[k] - xs_[3 * j + k];
              if (wrap_[k]) dk -= L_[k] * std::round(dk / L_[k]);
              d2 += dk * dk;
            }
            const double s = r + rs_[j];
            if (d2 < s * s) return true;
          }
        }
    return false;
  }

 private:
  int dim_;
  bool wrap_[3];
  double lo_[3], inv_[3], L_[3];
  int n_[3];
  std::vector<int> head_, next_;
  std::vector<double> xs_, rs_;
  int cell(const double* x, int k) const {
    if (k >= dim_) return 0;
    int c = static_cast<int>(std::floor((x[k] - lo_[k]) * inv_[k]));
    if (wrap_[k]) return ((c % n_[k]) + n_[k]) % n_[k];
    return std::clamp(c, 0, n_[k] - 1);
  }
  std::size_t index(const double* x) const {
    return (static_cast<std::size_t>(cell(x, 2)) * n_[1] + cell(x, 1)) * n_[0] + cell(x, 0);
  }
};

// Does each sphere of a clump (centre of mass x, rotation q) stay clear of the
// grid's spheres? With add, the spheres are added instead.
bool clump_fits(const FixParticledistributionDiscrete::Grain& g, const double* x, const std::array<double, 4>& q,
                OverlapGrid& grid, bool add) {
  rigid::Q4 qb;
  const auto d = clump_offsets(*g.g.clump, q, qb);
  for (std::size_t j = 0; j < d.size(); ++j) {
    const double p[3] = {x[0] + d[j][0], x[1] + d[j][1], x[2] + d[j][2]};
    if (add)
      grid.add(p, g.g.clump->radius[j]);
    else if (grid.overlaps(p, g.g.clump->radius[j]))
      return false;
  }
  return true;
}

}  // namespace

FixInsert::FixInsert(Simulation& s, const Args& a) : Fix(s, a) {
  hooks = POST_INTEGRATE;  // LIGGGHTS inserts in pre_exchange: after the drift, before the list build
  vector_size = 2;         // f_ID[1] grains inserted so far, f_ID[2] their mass
  if (a.word(4, "'seed'") != "seed") a.fail(4, "'seed' (fix ID group " + style + " seed S ...)");
  seed_ = parse_prime_seed(a, 5);
  step_seen_ = s.step;
}

int FixInsert::dim() const { return sim.domain.dimension; }

double FixInsert::grain_volume(double r) const {
  return dim() == 2 ? std::numbers::pi * r * r : 4.0 / 3.0 * std::numbers::pi * r * r * r;
}

void FixInsert::parse(const Args& a) {
  for (std::size_t i = 6; i < a.size();)
    if (!shared_keyword(a, i) && !own_keyword(a, i)) a.fail(i, "an " + style + " keyword: " + keyword_list());
  if (!dist_) a.fail(a.size(), "'distributiontemplate ID' (which grains to insert)");
  if (uses_region() && !region_) a.fail(a.size(), "'region ID' (where to insert)");
  if (uses_region() && !every_given_)
    a.fail(a.size(), once_allowed_ ? "'insert_every N' or 'insert_every once'" : "'insert_every N'");
  check_own(a);
  traits.turns_grains = w_[0] != 0 || w_[1] != 0 || w_[2] != 0;  // `omega`: inserted grains spin
  if (!sim.domain.box_exists) a.fail(0, "a box first (create_box before fix " + style + ")");
  if (dist_->max_type > sim.atoms.ntypes)
    a.fail_line("template atom_type " + std::to_string(dist_->max_type) + " exceeds the " +
                std::to_string(sim.atoms.ntypes) + " atom types of create_box");
  // LIGGGHTS insists that all seeds of one insertion chain differ (correlated streams otherwise).
  std::vector<long> seeds{seed_, dist_->seed};
  for (auto* t : dist_->templates) seeds.push_back(t->seed);
  for (std::size_t p = 0; p < seeds.size(); ++p)
    for (std::size_t q = 0; q < p; ++q)
      if (seeds[p] == seeds[q])
        a.fail(5, "a seed different from those of distribution '" + dist_->id +
                      "' and of its templates (LIGGGHTS requires all of them to differ)");
  if (next_step_ < 0) next_step_ = sim.step + 1;
  rng_.reseed(seed_);
  pos_rng_.reseed(seed_ + 12);  // positions: their own stream (LIGGGHTS: region generator, seed + 12)
  if (uses_region()) setup_geometry();
}

// The general (fix insert) and region keywords; false when a[i] is none of them.
bool FixInsert::shared_keyword(const Args& a, std::size_t& i) {
  const std::string& k = a[i];
  if (!uses_region() && (k == "region" || k == "check_dist_from_subdomain_border")) return false;
  auto yes_no = [&](bool& flag) {
    flag = a.yes_no(i + 1, "yes or no");
    i += 2;
  };
  if (k == "distributiontemplate") {
    dist_id_ = a.word(i + 1, "a distribution fix ID");
    dist_ = dynamic_cast<FixParticledistributionDiscrete*>(sim.find_fix(dist_id_));
    if (!dist_) a.fail(i + 1, "the ID of a fix particledistribution/discrete defined earlier");
    i += 2;
  } else if (k == "insert_every" || k == "every") {
    insert_every_ = a.word(i + 1, "a period in steps or 'once'") == "once"
                        ? 0
                        : a.integer(i + 1, "a period in steps or 'once'");
    if (insert_every_ < 0 || (!once_allowed_ && insert_every_ == 0))
      a.fail(i + 1, once_allowed_ ? "a period >= 0 steps or 'once'" : "a period >= 1 steps (not 'once' for " + style + ")");
    every_given_ = true;
    i += 2;
  } else if (k == "maxattempt") {
    maxattempt_ = a.integer(i + 1, "the number of attempts per grain");
    if (maxattempt_ < 1) a.fail(i + 1, "maxattempt >= 1");
    i += 2;
  } else if (k == "start") {
    next_step_ = a.integer(i + 1, "the first insertion step");
    if (next_step_ < sim.step + 1) a.fail(i + 1, "a start step after the current step " + std::to_string(sim.step));
    i += 2;
  } else if (k == "overlapcheck") {
    yes_no(overlap_);
  } else if (k == "all_in") {
    yes_no(all_in_);
  } else if (k == "verbose") {
    yes_no(verbose_);
  } else if (k == "check_dist_from_subdomain_border") {
    yes_no(border_gap_);
  } else if (k == "compress_tags") {
    bool c;
    yes_no(c);
    if (c) a.fail(i - 1, "'no' (compress_tags yes is not supported)");
  } else if (k == "random_distribute") {
    exact_ = a.choice(i + 1, {"exact", "uncorrelated"}) == 0;
    i += 2;
  } else if (k == "vel") {
    vstyle_ = a.choice(i + 1, {"constant", "uniform", "gaussian"});
    for (int d = 0; d < 3; ++d) v_[d] = a.num(i + 2 + d, "a velocity component");
    for (int d = 0; d < 3 && vstyle_; ++d) dv_[d] = a.num(i + 5 + d, "a velocity fluctuation component");
    i += vstyle_ ? 8 : 5;
  } else if (k == "omega") {
    if (a.word(i + 1, "'constant'") != "constant") a.fail(i + 1, "'constant'");
    for (int d = 0; d < 3; ++d) w_[d] = a.num(i + 2 + d, "an angular velocity component");
    i += 5;
  } else if (k == "orientation") {  // of multisphere clumps (spheres have none)
    const std::string& o = a.word(i + 1, "random, template or constant q1 q2 q3 q4");
    if (o == "constant") {
      orient_ = Orient::Constant;
      double n = 0;
      for (int d = 0; d < 4; ++d) n += std::pow(quat_[d] = a.num(i + 2 + d, "a quaternion component"), 2);
      if (!(n > 0)) a.fail(i + 2, "a non-zero quaternion");
      for (double& c : quat_) c /= std::sqrt(n);
    } else if (o == "random" || o == "template") {
      orient_ = o == "random" ? Orient::Random : Orient::Template;
    } else {
      a.fail(i + 1, "random, template or constant q1 q2 q3 q4");
    }
    i += o == "constant" ? 6 : 2;
  } else if (k == "region") {
    region_id_ = a.word(i + 1, "a region ID");
    region_ = sim.find_region(region_id_);
    if (!region_) a.fail(i + 1, "an existing region ID (define it with 'region' first)");
    i += 2;
  } else if (k == "ntry_mc") {
    ntry_mc_ = a.integer(i + 1, "a number of Monte-Carlo points");
    if (ntry_mc_ < 1000) a.fail(i + 1, "ntry_mc >= 1000");
    i += 2;
  } else {
    return false;
  }
  return true;
}

// The region and fixes this fix points to must still be the ones it was given.
void FixInsert::init() {
  if (uses_region() && sim.find_region(region_id_) != region_)
    args.fail_line("region '" + region_id_ + "' was deleted or redefined");
  if (sim.find_fix(dist_id_) != dist_) args.fail_line("fix '" + dist_id_ + "' was removed or redefined");
  for (std::size_t t = 0; t < dist_->templates.size(); ++t)
    if (sim.find_fix(dist_->template_ids[t]) != dist_->templates[t])
      args.fail_line("template fix '" + dist_->template_ids[t] + "' was removed or redefined");
  if (const long delta = sim.step - step_seen_; delta != 0) {  // reset_timestep since
    if (next_step_ >= 0) next_step_ += delta;
    shift_steps(delta);
  }
  step_seen_ = sim.step;
  if (!announced_) {
    announce();
    if (dim() == 2) sim.print("INFO: 2D insertion of discs at z = 0 is a sable extension (LIGGGHTS 3.8 inserts in 3D only)");
    announced_ = true;
  }
}

void FixInsert::announce() {
  sim.print("INFO: Particle insertion " + id + ": inserting every " + std::to_string(insert_every_) + " steps");
}

void FixInsert::post_integrate() {
  if (sim.step != next_step_) return;
  insert();
  next_step_ = following_step();
}

void FixInsert::post_run() { step_seen_ = sim.step; }

double FixInsert::compute_vector(int i) {
  return i == 1 ? static_cast<double>(ninserted_) : i == 2 ? mass_inserted_ : 0.0;
}

// Restart state (LIGGGHTS fix insert stores the same): next insertion step,
// counters and this fix's random streams, so a restarted deck neither inserts
// again (insert_every once) nor repeats positions. The templates' and the
// distribution's own streams are theirs to store.
bool FixInsert::write_state(std::string& out) const {
  static_assert(std::is_trivially_copyable_v<Rng>);
  restart::Packer p;
  p.put<std::int64_t>(next_step_);
  p.put<std::int64_t>(ninserted_);
  p.put(mass_inserted_);
  p.put(rng_);
  p.put(pos_rng_);
  p.put<std::int64_t>(sim.step);  // the step the schedule above refers to
  out = p.bytes;
  return true;
}

void FixInsert::read_state(const std::string& in) {
  restart::Unpacker u(in, "the restart state of fix " + id);
  next_step_ = u.get<std::int64_t>();
  ninserted_ = u.get<std::int64_t>();
  mass_inserted_ = u.get<double>();
  rng_ = u.get<Rng>();
  pos_rng_ = u.get<Rng>();
  step_seen_ = u.left() ? u.get<std::int64_t>() : sim.step;  // files from before it was stored
}

// Sampling box, region shape (for all_in) and region volume (area in 2D).
void FixInsert::setup_geometry() {
  const Domain& d = sim.domain;
  const Region& R = *region_;
  bool clipped = false;
  for (int k = 0; k < 3; ++k) {
    slo_[k] = R.interior ? std::max(R.lo[k], d.lo[k]) : d.lo[k];
    shi_[k] = R.interior ? std::min(R.hi[k], d.hi[k]) : d.hi[k];
    if (k < dim() && R.interior && (R.lo[k] < d.lo[k] || R.hi[k] > d.hi[k])) {
      clipped = true;
      if (std::fabs(R.lo[k]) < 1e100 && std::fabs(R.hi[k]) < 1e100)
        sim.warn("fix " + style + " " + id + ": region '" + R.id + "' extends outside the box along " +
                 std::string(1, char('x' + k)) + "; only its part inside the box is filled");
    }
    if (k < dim() && !(shi_[k] > slo_[k]))
      args.fail_line("the insertion region '" + R.id + "' does not overlap the box");
  }
  // A grain wider than the region (all_in) or than the box can never be placed.
  for (int k = 0; k < dim(); ++k) {
    const double room = all_in_ ? shi_[k] - slo_[k] : d.hi[k] - d.lo[k], diam = 2 * dist_->max_radius;
    if (diam > room)
      args.fail_line("the largest template grain (diameter " + std::to_string(diam) + ") is wider than " +
                     (all_in_ ? "region '" + R.id + "'" : std::string("the box")) + " along " +
                     std::string(1, char('x' + k)) + " (" + std::to_string(room) + "): it can never be inserted");
  }
  if (dim() == 2 && (R.lo[2] > 0 || R.hi[2] < 0) && R.interior)
    args.fail_line("in 2D grains are inserted at z = 0, but region '" + R.id + "' does not contain z = 0");
  // Exact volume when the region lies in the box and knows it; else Monte-Carlo like LIGGGHTS.
  if (!clipped && R.interior && dim() == 3 && R.volume() > 0)
    region_volume_ = R.volume();
  else if (!clipped && R.interior && dim() == 2 && R.area() > 0)
    region_volume_ = R.area();
  else {
    Rng mc(seed_ + 12);
    long in = 0;
    for (long t = 0; t < ntry_mc_; ++t) {
      double x[3] = {0, 0, 0};
      for (int k = 0; k < dim(); ++k) x[k] = slo_[k] + mc.uniform() * (shi_[k] - slo_[k]);
      in += R.match(x);
    }
    double box = 1;
    for (int k = 0; k < dim(); ++k) box *= shi_[k] - slo_[k];
    region_volume_ = box * in / ntry_mc_;
  }
  if (!(region_volume_ > 0)) args.fail_line("the insertion region '" + R.id + "' has no volume inside the box");
}

// Is a grain (x, r) in the region: its centre, or with all_in yes all of it?
bool FixInsert::in_region(const double* x, double r) {
  if (!all_in_) return region_->match(x);
  const double dd = region_->depth(x, dim());
  if (!std::isnan(dd)) return region_->interior ? dd >= r : dd <= -r;
  // Region style without a distance: test the centre and 26 points of the surface.
  if (!warned_all_in_) {
    sim.warn("fix " + style + " " + id + ": all_in for region style '" + region_->style +
             "' is checked on 26 surface points only (approximate)");
    warned_all_in_ = true;
  }
  if (!region_->match(x)) return false;
  for (int i = -1; i <= 1; ++i)
    for (int j = -1; j <= 1; ++j)
      for (int k = -1; k <= 1; ++k) {
        if (!i && !j && !k) continue;
        const double n = std::sqrt(double(i * i + j * j + k * k));
        const double p[3] = {x[0] + r * i / n, x[1] + r * j / n, dim() == 2 ? 0.0 : x[2] + r * k / n};
        if (!region_->match(p)) return false;
      }
  return true;
}

// LIGGGHTS (one process) rejects overlap-checked positions closer than r to a
// box face, periodic or not: its sub-domain border test.
bool FixInsert::near_box_face(const double* x, double r) const {
  for (int k = 0; k < dim(); ++k)
    if (x[k] - sim.domain.lo[k] < r || sim.domain.hi[k] - x[k] < r) return true;
  return false;
}

// A uniformly random position of a grain of radius r in the region.
void FixInsert::random_position(double r, double* x) {
  double lo[3], hi[3];
  for (int k = 0; k < 3; ++k) {
    const double shrink = all_in_ && region_->interior && k < dim() ? r : 0.0;
    lo[k] = slo_[k] + shrink;
    hi[k] = shi_[k] - shrink;
    if (k < dim() && !(hi[k] >= lo[k]))
      args.fail_line("region '" + region_->id + "' is too small for grains of radius " + std::to_string(r) +
                     " with all_in yes");
  }
  for (long t = 0; t < 1000000; ++t) {
    for (int k = 0; k < 3; ++k) x[k] = k < dim() ? lo[k] + pos_rng_.uniform() * (hi[k] - lo[k]) : 0.0;
    if (in_region(x, r)) return;
  }
  args.fail_line("found no position inside region '" + region_->id + "' in 10^6 random draws for a grain of radius " +
                 std::to_string(r));
}


// Positions for the grains, in order, into pos; returns how many were placed
// (all of them without overlapcheck, else as many as the try budget allowed).
std::size_t FixInsert::place(const std::vector<FixParticledistributionDiscrete::Grain>& grains, double filled,
                             std::vector<double>& pos) {
  const Atoms& at = sim.atoms;
  pos.assign(3 * grains.size(), 0.0);
  q_.assign(grains.size(), {1, 0, 0, 0});
  std::size_t placed = 0;
  if (!overlap_ && !keeps_off_faces_always()) {
    for (; placed < grains.size(); ++placed) {
      random_position(grains[placed].g.radius, &pos[3 * placed]);
      if (grains[placed].g.clump) q_[placed] = orientation();
    }
    return placed;
  }
  if (!overlap_) {  // redraw near a face, one shared budget of M tries per grain (LIGGGHTS insert/stream)
    const long maxtry = static_cast<long>(grains.size()) * maxattempt_;
    long ntry = 0;
    for (; placed < grains.size(); ++placed) {
      const double r = grains[placed].g.radius;
      do {
        random_position(r, &pos[3 * placed]);
        ++ntry;
      } while (ntry < maxtry && near_box_face(&pos[3 * placed], r));
      if (ntry >= maxtry) break;  // as LIGGGHTS: the draw that used up the budget is not kept
      if (grains[placed].g.clump) q_[placed] = orientation();
    }
    return placed;
  }
  double rmax = 0;
  for (std::size_t i = 0; i < at.n; ++i) rmax = std::max(rmax, at.radius[i]);
  OverlapGrid grid(sim.domain, slo_, shi_, dist_->max_radius + std::max(sim.comm.highest(rmax), dist_->max_radius));
  if (sim.comm.distributed) {
    // Several ranks: every rank sees every grain near the region and places the same
    // grains with the same draws (each then keeps those in its subdomain: insert()).
    std::vector<double> mine, all;
    for (std::size_t i = 0; i < at.n; ++i)
      if (grid.covers(&at.x[3 * i])) mine.insert(mine.end(), {at.x[3 * i], at.x[3 * i + 1], at.x[3 * i + 2], at.radius[i]});
    sim.comm.all_gather(mine, all);
    for (std::size_t q = 0; q + 3 < all.size(); q += 4) grid.add(&all[q], all[q + 3]);
  } else {
    for (std::size_t i = 0; i < at.n; ++i)
      if (grid.covers(&at.x[3 * i])) grid.add(&at.x[3 * i], at.radius[i]);
  }
  // LIGGGHTS budget: M tries per grain, more when the region is already partly filled.
  const double budget = static_cast<double>(grains.size()) * maxattempt_;
  const long maxtry = static_cast<long>(filled < 1 ? budget / (1 - std::max(0.0, filled)) : budget);
  long ntry = 0;
  while (placed < grains.size() && ntry < maxtry) {
    const double r = grains[placed].g.radius;
    double* x = &pos[3 * placed];
    bool ok = false;
    while (!ok && ntry < maxtry) {
      do {
        random_position(r, x);
        ++ntry;
      } while (ntry < maxtry && border_gap_ && near_box_face(x, r));
      if (ntry == maxtry) break;  // as LIGGGHTS: the last draw is not tried
      if (grains[placed].g.clump) {
        q_[placed] = orientation();
        ok = clump_fits(grains[placed], x, q_[placed], grid, false);
      } else {
        ok = !grid.overlaps(x, r);
      }
    }
    if (ok) {
      if (grains[placed].g.clump)
        clump_fits(grains[placed], x, q_[placed], grid, true);
      else
        grid.add(x, r);
      ++placed;
    }
  }
  return placed;
}

// A clump's orientation: the template's, a constant rotation, or a uniformly
// random one (Shoemake's method).
std::array<double, 4> FixInsert::orientation() {
  if (orient_ == Orient::Template) return {1, 0, 0, 0};
  if (orient_ == Orient::Constant) return quat_;
  const double u1 = rng_.uniform(), u2 = 2 * std::numbers::pi * rng_.uniform(), u3 = 2 * std::numbers::pi * rng_.uniform();
  const double s1 = std::sqrt(1 - u1), s2 = std::sqrt(u1);
  return {s2 * std::cos(u3), s1 * std::sin(u2), s1 * std::cos(u2), s2 * std::sin(u3)};
}

void FixInsert::region_content(long& np, double& vol, double& mass) const {
  const Atoms& at = sim.atoms;
  np = 0, vol = 0, mass = 0;
  const FixMultisphere* ms = sim.find_fix_style<FixMultisphere>();
  std::vector<double> rho(ms ? ms->bodies().size() : 0, 0.0);  // a clump's density, from its spheres
  for (std::size_t i = 0; i < at.n; ++i) {
    if (const int k = ms ? ms->rigid_bodies()->body_of(i) : -1; k >= 0) {
      rho[k] = at.density[i];
    } else if (region_->match(&at.x[3 * i])) {
      ++np;
      vol += grain_volume(at.radius[i]);
      mass += at.rmass[i];
    }
  }
  if (sim.comm.distributed) {  // every rank's grains (clumps do not run on several ranks)
    np = sim.comm.total(np);
    vol = sim.comm.total(vol);
    mass = sim.comm.total(mass);
  }
  for (std::size_t k = 0; k < rho.size(); ++k) {
    const auto& b = ms->body(static_cast<int>(k));
    double x[3] = {b.xcm[0], b.xcm[1], b.xcm[2]};
    int image[3] = {0, 0, 0};
    sim.domain.remap(x, image);
    if (!region_->match(x)) continue;
    ++np;
    vol += b.mass / rho[k];
    mass += b.mass;
  }
}

void FixInsert::insert() {
  double filled = 0;
  const long want = wanted(filled);
  if (want <= 0) return;
  const auto grains = dist_->draw(drawable(want), exact_);
  std::vector<double> pos;
  const std::size_t placed = place(grains, filled, pos);
  Atoms& at = sim.atoms;
  const std::size_t first = at.n;
  double mass_now = 0;
  long next_id = static_cast<long>(sim.comm.highest(static_cast<double>(at.max_id))) + 1;  // all ranks' ids
  for (std::size_t p = 0; p < placed; ++p, ++next_id) {
    const auto& G = grains[p];
    double v[3], w[3];
    start_motion(v, w);  // every rank draws for every grain: the same streams
    mass_now += G.g.mass;
    if (sim.comm.distributed && sim.comm.owner_of(&pos[3 * p], sim.domain) != sim.comm.rank()) continue;
    if (G.g.clump) {
      insert_clump(G, &pos[3 * p], q_[p], v);
    } else {
      const long aid = sim.comm.distributed ? next_id : at.max_id + 1;  // (one rank: after a clump's spheres too)
      const std::size_t i = at.add(aid, G.g.type, &pos[3 * p], G.g.radius, G.g.density);
      at.rmass[i] = G.g.mass;  // disc mass in 2D
      at.mask[i] |= groupbit | G.groupbits;
      for (int k = 0; k < 3; ++k) {
        at.v[3 * i + k] = v[k];
        at.omega[3 * i + k] = w[k];
      }
    }
  }
  inserted(first);
  ninserted_ += static_cast<long>(placed);
  mass_inserted_ += mass_now;
  char buf[320];
  if (verbose_) {
    std::snprintf(buf, sizeof buf,
                  "INFO: Particle insertion %s: inserted %zu particle templates (mass %e) at step %ld\n"
                  " - a total of %ld particle templates (mass %e) inserted so far.",
                  id.c_str(), placed, mass_now, sim.step, ninserted_, mass_inserted_);
    sim.print(buf);
  }
  if (static_cast<long>(placed) < want) {
    std::snprintf(buf, sizeof buf,
                  "Particle insertion: Less insertions than requested: fix %s %s placed %zu of %ld grains "
                  "at step %ld (%ld tries per grain); lower the target, enlarge the region or raise maxattempt",
                  style.c_str(), id.c_str(), placed, want, sim.step, maxattempt_);
    sim.warn(buf);
  }
}

// The most grains worth drawing: twice what grains of the smallest template would
// fill packed solid in the insertion volume (grown by a grain on every side: only
// centres must be inside it). A target beyond that (a fuzzed count of 2^31) would
// otherwise draw and try millions of grains in vain; the shortfall is warned about.
long FixInsert::drawable(long want) const {
  double space = 1, smallest = INFINITY;
  for (int k = 0; k < dim(); ++k) space *= shi_[k] - slo_[k] + 2 * dist_->max_radius;
  for (const auto* t : dist_->templates) smallest = std::min(smallest, t->volume_expect());
  if (!(smallest > 0) || !(space > 0)) return want;
  const double most = std::ceil(2.0 * space / smallest);
  return most < static_cast<double>(want) ? static_cast<long>(most) : want;
}

void FixInsert::draw_velocity(double* v) {
  for (int k = 0; k < 3; ++k) {
    v[k] = v_[k];
    if (vstyle_ == 1) v[k] += dv_[k] * (2 * rng_.uniform() - 1);
    if (vstyle_ == 2) v[k] += dv_[k] * rng_.gaussian();
  }
}

void FixInsert::start_motion(double* v, double* w) {
  draw_velocity(v);
  for (int k = 0; k < 3; ++k) w[k] = w_[k];
}

// A clump's spheres as atoms carrying the body's mass (LIGGGHTS), handed to fix multisphere.
void FixInsert::insert_clump(const FixParticledistributionDiscrete::Grain& G, const double* x,
                             const std::array<double, 4>& q, const double* v) {
  auto* ms = sim.find_fix_style<FixMultisphere>();
  if (!ms) args.fail_line("fix " + id + " inserts multisphere clumps: define a fix multisphere (LIGGGHTS: exactly one)");
  Atoms& at = sim.atoms;
  const ClumpShape& c = *G.g.clump;
  rigid::Q4 qb;
  const auto d = clump_offsets(c, q, qb);
  const std::size_t first = at.n;
  for (std::size_t j = 0; j < d.size(); ++j) {
    const double p[3] = {x[0] + d[j][0], x[1] + d[j][1], x[2] + d[j][2]};
    const std::size_t i = at.add(at.max_id + 1, G.g.type, p, c.radius[j], c.density);
    at.rmass[i] = c.mass;
    at.mask[i] |= groupbit | G.groupbits;
  }
  ms->add_body(c, x, q, v, w_, first);
}

}  // namespace sable
