// compute ID group contact/fabric [bins N] [area A] [rattler M] [contacts both|any]
// (sable addition; LIGGGHTS has no such style.) 2D (dimension 2) contact
// fabric of the grain-grain contacts with both grains in the group, for
// petit2017 (Petit et al. 2017: Z, Eq. 10's contact-angle entropy, App. A's
// overlaps). Which grains count (e.g. frozen piston grains or not) is the
// group's choice; `contacts any` also counts the contacts of the group's grains
// with grains outside it (e.g. with the pistons: they then count as walls, never
// as grains or rattlers). The contacts are re-evaluated by the pair's kernel
// when the compute is invoked, as compute pair/gran/local does.
//   phi     the angle of the branch vector from the vertical, atan2(lx, ly),
//           of the contact line, so folded by pi into [-pi/2, pi/2): 0 = one
//           grain on top of the other, -pi/2 = side by side (+pi/2 folds there).
//   bins    N equal bins of width pi/N over the orientations (default 36, 5
//           deg), c_ID[4+k] centred on phi_k = -pi/2 + k pi/N, k = 0..N-1,
//           periodic: k = 0 takes the horizontal from both sides. Lattice directions
//           that are multiples of 180/N deg thus lie mid-bin, never on an edge.
//           Each contact counts once; P_k = n_k / N_c sums to 1.
//   S       Eq. 10, -sum_k P_k ln P_k (0 ln 0 = 0). A triangular lattice gives
//           ln 3 = 1.099 (three equally frequent lines) and a square one ln 2,
//           for any N that separates the directions. The paper's S_tri = ln 4
//           = 1.386 is no binning of the contacts: it is each grain's
//           neighbours in its closed upper half-plane counted, on a lattice
//           with horizontal rows (-90, -30, 30, 90 deg: a horizontal contact
//           twice, once from each grain). That counting equals this one
//           wherever no contact is exactly horizontal (any random packing).
//   Z       the mean number of contacts of the non-rattler grains of the group
//           (2 N_c / N_g with `contacts both`): a rattler is a grain with
//           fewer than M contacts (default 2, the fewest that can balance a
//           force in 2D without gravity; petit2017 does not say), removed
//           repeatedly until every grain left has M (its contacts go with it).
//   sigma   Love-Weber, sigma_ab = (1/A) sum_c f_a l_b, f the force on grain
//           i, l = x_i - x_j the branch vector to i (periodic image of j),
//           over every contact counted (rattlers' included): compression
//           positive, in N/m (force per length: 2D). A = `area` (a number or
//           v_name, equal-style, read at each invocation), default the box's
//           x by y area.
//   delta   the overlap over the sum of radii, delta / (R_i + R_j) (App. A).
// Global vector (c_ID[k]): 1 Z, 2 rattler fraction (rattlers / grains of the
// group), 3 S, 4..3+N P_k, then sigma_xx, sigma_yy, sigma_xy, sigma_yx, mean
// and max delta/(R_i+R_j), N_c (contacts counted), non-rattler grains. No
// contact: Z, S, P, sigma and the deltas are 0.
// Local rows (dump local c_ID[k]): id_i id_j phi delta/(R_i+R_j) fn, fn = f.n
// the normal force on i (n = l/|l|: > 0 in compression).
#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "computes/bound_arg.h"
#include "core/engine/contact_source.h"
#include "core/engine/simulation.h"
#include "core/input/style_registry.h"

namespace sable {

namespace {

constexpr double kPiFabric = std::numbers::pi;

// atan2(lx, ly) folded by pi into [-pi/2, pi/2).
double fold_phi(double lx, double ly) {
  double phi = std::atan2(lx, ly);
  if (phi >= kPiFabric / 2) phi -= kPiFabric;
  if (phi < -kPiFabric / 2) phi += kPiFabric;
  return phi;
}

// The bin of phi among n centred on -pi/2 + k pi/n (periodic).
int phi_bin(double phi, int n) {
  if (!std::isfinite(phi)) return 0;  // coincident centres: no direction (the force is not finite either)
  const long k = std::lround(std::floor((phi + kPiFabric / 2) / (kPiFabric / n) + 0.5));
  return static_cast<int>(((k % n) + n) % n);
}

}  // namespace

class ComputeContactFabric : public Compute {
 public:
  ComputeContactFabric(Simulation& s, const Args& a) : Compute(s, a) {
    parse(a);
    vector_size = 3 + bins_ + 8;
    local_flag = true;
    local_names = {"id_i", "id_j", "phi", "delta_rel", "fn"};
    local_cols = static_cast<int>(local_names.size());
    init();
  }
  void init() override {
    if (sim.domain.dimension != 2) args.fail_line("compute contact/fabric is 2D: it needs 'dimension 2'");
    pair_ = pair_contacts(sim);
    if (!pair_) args.fail_line("compute contact/fabric needs 'pair_style gran' defined before it");
  }
  double compute_vector(int i) override {
    if (invoked_step != sim.step) {
      evaluate();
      invoked_step = sim.step;
    }
    return out_[static_cast<std::size_t>(i - 1)];
  }
  void compute_local() override {
    contacts();
    local.clear();
    for (const Contact& c : con_) {
      const double row[5] = {static_cast<double>(sim.atoms.id[c.i]), static_cast<double>(sim.atoms.id[c.j]), c.phi,
                             c.rel, c.fn};
      local.insert(local.end(), row, row + 5);
    }
  }

 private:
  struct Contact {
    int i, j;
    double phi, rel, fn, f[2], l[2];
  };
  int bins_ = 36, min_contacts_ = 2;
  bool has_area_ = false, any_ = false;
  BoundArg area_;
  ContactSource* pair_ = nullptr;
  ContactRecords rec_;
  std::vector<Contact> con_;
  std::vector<double> out_;

  void parse(const Args& a) {
    for (std::size_t i = 4; i < a.size(); i += 2) {
      if (a[i] == "bins") {
        const long n = a.integer(i + 1, "a number of bins");
        if (n < 1 || n > 100000) a.fail(i + 1, "a number of bins in 1..100000");
        bins_ = static_cast<int>(n);
      } else if (a[i] == "area") {
        area_ = BoundArg::parse(sim, a, i + 1, "an area (a number or v_name)");
        has_area_ = true;
      } else if (a[i] == "rattler") {
        const long m = a.integer(i + 1, "the fewest contacts of a non-rattler");
        if (m < 0 || m > 100) a.fail(i + 1, "a number of contacts in 0..100");
        min_contacts_ = static_cast<int>(m);
      } else if (a[i] == "contacts") {
        any_ = a.choice(i + 1, {"both", "any"}) == 1;
      } else {
        a.fail(i, "bins, area, rattler or contacts (or the end of the line)");
      }
    }
  }

  // The group's contacts now, with their branch vectors and angles.
  void contacts() {
    init();
    pair_->records(any_ ? 1u : groupbit, rec_);  // 1u: group all
    con_.clear();
    const Atoms& at = sim.atoms;
    for (const ContactRecord& r : rec_.rows) {
      if (!(at.mask[r.i] & groupbit) && !(at.mask[r.j] & groupbit)) continue;
      const double sum = at.radius[r.i] + at.radius[r.j], len = sum - r.delta;
      Contact c{r.i, r.j, 0, r.delta / sum, r.f[0] * r.en[0] + r.f[1] * r.en[1], {r.f[0], r.f[1]},
                {r.en[0] * len, r.en[1] * len}};
      c.phi = fold_phi(c.l[0], c.l[1]);
      con_.push_back(c);
    }
  }

  void evaluate() {
    contacts();
    out_.assign(static_cast<std::size_t>(vector_size), 0.0);
    coordination();
    entropy();
    love_weber();
    overlaps();
  }

  // Z and the rattler fraction: grains of the group with fewer than M contacts removed until
  // none is left; grains outside the group (contacts any) stay.
  void coordination() {
    const Atoms& at = sim.atoms;
    std::vector<char> alive(at.n, 1);
    long ng = 0;
    for (std::size_t i = 0; i < at.n; ++i) ng += (at.mask[i] & groupbit) ? 1 : 0;
    std::vector<int> deg(at.n);
    long ends = 0, left = ng;
    for (bool changed = true; changed;) {
      std::fill(deg.begin(), deg.end(), 0);
      for (const Contact& c : con_)
        if (alive[c.i] && alive[c.j]) ++deg[c.i], ++deg[c.j];
      changed = false;
      ends = 0;
      for (std::size_t i = 0; i < at.n; ++i) {
        if (!(at.mask[i] & groupbit) || !alive[i]) continue;
        if (deg[i] < min_contacts_) alive[i] = 0, --left, changed = true;
        else ends += deg[i];
      }
    }
    out_[0] = left ? static_cast<double>(ends) / static_cast<double>(left) : 0.0;
    out_[1] = ng ? static_cast<double>(ng - left) / static_cast<double>(ng) : 0.0;
    out_[static_cast<std::size_t>(3 + bins_ + 6)] = static_cast<double>(con_.size());
    out_[static_cast<std::size_t>(3 + bins_ + 7)] = static_cast<double>(left);
  }

  // Eq. 10 over the bins (P_k into c_ID[4..3+N]).
  void entropy() {
    if (con_.empty()) return;
    double* p = &out_[3];
    for (const Contact& c : con_) p[phi_bin(c.phi, bins_)] += 1.0;
    double s = 0;
    for (int k = 0; k < bins_; ++k) {
      p[k] /= static_cast<double>(con_.size());
      if (p[k] > 0) s -= p[k] * std::log(p[k]);
    }
    out_[2] = s;
  }

  double area() {
    if (has_area_) {
      const double a = area_.eval(sim, args);
      if (!(a > 0) || !std::isfinite(a))
        args.fail_line("compute " + id + ": area " + std::to_string(a) + " at step " + std::to_string(sim.step) +
                       " is not positive");
      return a;
    }
    return sim.domain.length(0) * sim.domain.length(1);
  }

  // sigma_ab = (1/A) sum f_a l_b: xx, yy, xy, yx.
  void love_weber() {
    double s[2][2] = {{0, 0}, {0, 0}};
    for (const Contact& c : con_)
      for (int a = 0; a < 2; ++a)
        for (int b = 0; b < 2; ++b) s[a][b] += c.f[a] * c.l[b];
    const double inv = 1.0 / area();
    double* o = &out_[static_cast<std::size_t>(3 + bins_)];
    o[0] = s[0][0] * inv, o[1] = s[1][1] * inv, o[2] = s[0][1] * inv, o[3] = s[1][0] * inv;
  }

  void overlaps() {
    double sum = 0, mx = 0;
    for (const Contact& c : con_) sum += c.rel, mx = std::max(mx, c.rel);
    double* o = &out_[static_cast<std::size_t>(3 + bins_ + 4)];
    o[0] = con_.empty() ? 0.0 : sum / static_cast<double>(con_.size());
    o[1] = mx;
  }
};

SABLE_COMPUTE("contact/fabric", ComputeContactFabric);

}  // namespace sable
