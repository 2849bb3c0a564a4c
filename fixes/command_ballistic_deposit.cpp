// ballistic_deposit N|fill TEMPLATE seed S [floor Y]
// sable's own setup command (no LIGGGHTS/LAMMPS namesake), for petit2017's
// packings: in a 2D box periodic in x, disks of fix particletemplate/sphere
// TEMPLATE are added one at a time. Each falls from above at a uniformly
// random x (stream of seed S; radii and densities from the template's own
// stream, as insertion draws them), stops at its first contact, and then rolls
// without friction (geometrically, no dynamics) over the deposit: around the
// grain it touches, downhill, until it touches a second grain on the far side
// of its centre (it rests on two supports), reaches the floor (y = floor, by
// default the box's ylo), or rolls past the grain's equator and falls again.
// N: that many grains (an error if one would stick out of the box top);
// fill: until the next grain would stick out (that one is not added). Grains
// already in the box are obstacles too. Velocities zero; type, density and
// group from the template. Lives in fixes/ because it reads a fix (core knows
// no concrete fix). Clumps (petit2017's 3-disk grains) are not handled yet.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <vector>

#include "core/random.h"
#include "core/simulation.h"
#include "core/style_registry.h"
#include "fixes/fix_particletemplate_sphere.h"

namespace sable {
namespace {

struct Disk {
  double x, y, r;
};

// The deposit: disks binned in square cells of side h >= the largest contact
// distance between two disks, columns wrapping with the period, so a falling
// disk meets only its own and the neighbouring columns, and a rolling one the
// cells within two of its pivot's.
class Deposit {
 public:
  Deposit(double xlo, double period, double floor, double rmax)
      : xlo_(xlo), w_(period), floor_(floor),
        ncol_(std::max(1, static_cast<int>(std::floor(period / (2 * rmax))))), h_(period / ncol_), rmax_(rmax),
        cells_(static_cast<std::size_t>(ncol_)), top_(static_cast<std::size_t>(ncol_), -1) {}

  std::vector<Disk> disks;

  void add(const Disk& d) {
    const int c = col(d.x), r = row(d.y);
    auto& column = cells_[static_cast<std::size_t>(c)];
    if (static_cast<int>(column.size()) <= r) column.resize(static_cast<std::size_t>(r) + 1);
    column[static_cast<std::size_t>(r)].push_back(static_cast<int>(disks.size()));
    top_[static_cast<std::size_t>(c)] = std::max(top_[static_cast<std::size_t>(c)], r);
    disks.push_back(d);
  }

  // Where a disk of radius r dropped at x from height y0 (at most) first
  // touches: the largest contact height; `hit` the disk touched (-1 the floor),
  // `hx` its x image nearest the falling disk. `skip` is not considered.
  double drop(double x, double y0, double r, int skip, int& hit, double& hx) const {
    double best = floor_ + r;
    hit = -1;
    const int c0 = col(x);
    int start = -1;
    for (int dc = -1; dc <= 1; ++dc) start = std::max(start, top_[static_cast<std::size_t>(wrap_col(c0 + dc))]);
    start = std::min(start, row(y0));
    for (int rw = start; rw >= 0; --rw) {
      // Disks in row rw and below have centres below its top: no contact higher than top + 2 rmax.
      if (best >= floor_ + (rw + 1) * h_ + 2 * rmax_) break;
      for (int c : columns(c0, 1))
        for (int j : cell(c, rw)) {
          if (j == skip) continue;
          const Disk& d = disks[static_cast<std::size_t>(j)];
          const double R = r + d.r, jx = nearest_image(d.x, x), dx = x - jx;
          if (std::abs(dx) >= R) continue;
          const double yc = d.y + std::sqrt(R * R - dx * dx);
          // Round-off can put a disk the faller touches a hair above it: still a contact, at y0.
          if (yc > y0 + 1e-9 * R || yc <= best) continue;
          best = std::min(yc, y0), hit = j, hx = jx;
        }
    }
    return best;
  }

  // Disks whose cells lie within two of the cell of (x, y): all that a disk
  // rolling around a pivot at (x, y) can touch.
  std::vector<int> near(double x, double y) const {
    std::vector<int> out;
    const int r0 = row(y);
    for (int c : columns(col(x), 2))
      for (int rw = std::max(0, r0 - 2); rw <= r0 + 2; ++rw)
        for (int j : cell(c, rw)) out.push_back(j);
    return out;
  }

  double period() const { return w_; }
  double floor() const { return floor_; }
  // The image of x0 nearest x.
  double nearest_image(double x0, double x) const { return x0 + w_ * std::round((x - x0) / w_); }

 private:
  double xlo_, w_, floor_;
  int ncol_;
  double h_, rmax_;
  std::vector<std::vector<std::vector<int>>> cells_;  // [column][row] -> disk indices
  std::vector<int> top_;                              // highest occupied row per column
  static inline const std::vector<int> empty_;

  int wrap_col(int c) const { return ((c % ncol_) + ncol_) % ncol_; }
  int col(double x) const { return wrap_col(static_cast<int>(std::floor((x - xlo_) / h_))); }
  // Clamped in double first: a drop starts from y = 1e300.
  int row(double y) const { return static_cast<int>(std::clamp(std::floor((y - floor_) / h_), 0.0, 1e9)); }
  const std::vector<int>& cell(int c, int rw) const {
    const auto& column = cells_[static_cast<std::size_t>(c)];
    return rw < static_cast<int>(column.size()) ? column[static_cast<std::size_t>(rw)] : empty_;
  }
  // Columns c0-k..c0+k, each once (a narrow box wraps them onto each other).
  std::vector<int> columns(int c0, int k) const {
    std::vector<int> out;
    for (int dc = -k; dc <= k; ++dc) {
      const int c = wrap_col(c0 + dc);
      if (std::find(out.begin(), out.end(), c) == out.end()) out.push_back(c);
    }
    return out;
  }
};

// One disk's path: drop, roll, drop ... until it rests. Positions unwrapped.
class Faller {
 public:
  Faller(const Deposit& dep, double r) : dep_(dep), r_(r) {}

  // Final centre of a disk dropped at x from above everything. Every move
  // lowers it, so the bound on moves only guards against a bug (false).
  bool settle(double x, double& fx, double& fy) {
    double y = 1e300;
    int skip = -1;
    for (int step = 0; step < 100000; ++step) {
      int j;
      double jx;
      y = dep_.drop(x, y, r_, skip, j, jx);
      if (j < 0) {  // on the floor
        fx = x, fy = y;
        return true;
      }
      const Disk& p = dep_.disks[static_cast<std::size_t>(j)];
      double px = jx, py = p.y;
      int pivot = j;
      // Roll around successive pivots until at rest (true) or past an equator (false).
      if (roll(x, y, pivot, px, py)) {
        fx = x, fy = y;
        return true;
      }
      skip = pivot;  // falls off the pivot's side, away from it
    }
    return false;
  }

 private:
  const Deposit& dep_;
  double r_;

  // Rolls the disk at (x, y) around disk `pivot` (centre px, py) downhill. At a
  // second contact on the far side of the centre it rests; on the near side
  // that disk becomes the pivot (rolling on separates from the old one).
  // Returns true at rest (two supports or the floor), false past the equator
  // (x, y then on it, `pivot` the disk left behind).
  bool roll(double& x, double& y, int& pivot, double& px, double& py) {
    for (int guard = 0; guard < 100000; ++guard) {
      const double s = x >= px ? 1.0 : -1.0;  // rolling direction: away from the pivot
      const double R = r_ + dep_.disks[static_cast<std::size_t>(pivot)].r;
      if (y <= dep_.floor() + r_ * (1 + 1e-12)) return true;
      switch (touching(x, y, s, px, py, R, pivot)) {
        case Touch::Rest: return true;
        case Touch::NewPivot: continue;
        case Touch::None: break;
      }
      const double psi0 = std::atan2(s * (x - px), y - py);
      // Earliest event along psi in (psi0, pi/2]: the equator, the floor, a disk.
      double psi_end = std::numbers::pi / 2, ex = px + s * R, ey = py;
      int kind = 0, next = -1;  // 0 equator, 1 floor, 2 disk
      double nx = 0;
      const double fy = dep_.floor() + r_ - py;  // floor height seen from the pivot
      if (std::abs(fy) <= R) {
        const double psi_f = std::acos(fy / R);
        if (psi_f > psi0 && psi_f <= psi_end)
          psi_end = psi_f, ex = px + s * std::sqrt(std::max(0.0, R * R - fy * fy)), ey = dep_.floor() + r_,
          kind = 1;
      }
      for (int k : dep_.near(px, py)) {
        if (k == pivot) continue;
        const Disk& d = dep_.disks[static_cast<std::size_t>(k)];
        const double Rk = r_ + d.r;
        for (int m = -1; m <= 1; ++m) {
          const double kx = dep_.nearest_image(d.x, px) + m * dep_.period();
          double hx = 0, hy = 0, psi = 0;
          if (!first_touch(px, py, R, kx, d.y, Rk, s, psi0, hx, hy, psi)) continue;
          // A disk at the floor's or the equator's point comes first: the faller meets it there.
          if (psi < psi_end || (kind != 2 && psi < psi_end + 1e-9))
            psi_end = psi, ex = hx, ey = hy, kind = 2, next = k, nx = kx;
        }
      }
      x = ex, y = ey;
      if (kind == 0) return false;
      if (kind == 1) return true;
      if (s * (nx - x) > 0) return true;  // supports on both sides of the centre: stable
      pivot = next, px = nx, py = dep_.disks[static_cast<std::size_t>(next)].y;
    }
    return false;  // no rest within the bound: settle() tries further and reports
  }

  enum class Touch { None, Rest, NewPivot };

  // Disks other than the pivot that the faller at (x, y) touches already
  // (within 1e-9 of the contact distance): exact ties are common, e.g. a
  // monodisperse disk dropped midway between two touching disks lands on both.
  // One beyond the centre (direction s): at rest. One this side that rolling
  // would push into becomes the pivot (rolling on it separates from the old).
  Touch touching(double x, double y, double s, double& px, double& py, double R, int& pivot) const {
    const double tx = s * (y - py) / R, ty = -s * (x - px) / R;  // rolling direction
    for (int k : dep_.near(px, py)) {
      if (k == pivot) continue;
      const Disk& d = dep_.disks[static_cast<std::size_t>(k)];
      const double Rk = r_ + d.r;
      for (int m = -1; m <= 1; ++m) {
        const double kx = dep_.nearest_image(d.x, x) + m * dep_.period();
        if (std::abs(std::hypot(x - kx, y - d.y) - Rk) > 1e-9 * Rk) continue;
        if (s * (kx - x) > 0) return Touch::Rest;
        if (tx * (kx - x) + ty * (d.y - y) > 0) {
          pivot = k, px = kx, py = d.y;
          return Touch::NewPivot;
        }
      }
    }
    return Touch::None;
  }

  // The first point, rolling in direction s with psi in (psi0, pi/2] on the
  // circle (p, R), at distance Rk from c: a circle-circle intersection.
  static bool first_touch(double px, double py, double R, double cx, double cy, double Rk, double s, double psi0,
                          double& hx, double& hy, double& psi) {
    const double dx = cx - px, dy = cy - py, D2 = dx * dx + dy * dy, D = std::sqrt(D2);
    if (D >= R + Rk || D <= std::abs(R - Rk) || D == 0) return false;
    const double a = (R * R - Rk * Rk + D2) / (2 * D), hh = std::sqrt(std::max(0.0, R * R - a * a));
    bool found = false;
    for (double sg : {-1.0, 1.0}) {
      const double qx = px + (a * dx - sg * hh * dy) / D, qy = py + (a * dy + sg * hh * dx) / D;
      const double q = std::atan2(s * (qx - px), qy - py);
      // 1e-9 rad: the contact the disk is leaving (its start point) is not a new one.
      if (q > psi0 + 1e-9 && q <= std::numbers::pi / 2 + 1e-9 && (!found || q < psi)) psi = q, hx = qx, hy = qy, found = true;
    }
    return found;
  }
};

void cmd_ballistic_deposit(Simulation& sim, const Args& a) {
  const Domain& dom = sim.domain;
  if (!dom.box_exists) a.fail(0, "a box first (create_box before ballistic_deposit)");
  if (dom.dimension != 2) a.fail(0, "a 2D box ('dimension 2' before create_box): ballistic_deposit deposits disks");
  if (!dom.periodic[0]) a.fail(0, "a box periodic in x ('boundary p f p' or 'p f f')");
  long n = -1;
  if (a.word(1, "a number of grains N or 'fill'") != "fill") {
    n = a.integer(1, "a number of grains N > 0 or 'fill'");
    if (n <= 0) a.fail(1, "a number of grains N > 0 or 'fill'");
  }
  auto* tmpl = dynamic_cast<FixParticletemplateSphere*>(sim.find_fix(a.word(2, "a particle template fix ID")));
  if (!tmpl) a.fail(2, "the ID of a fix particletemplate/sphere defined earlier");
  if (tmpl->style != "particletemplate/sphere")
    a.fail(2, "a fix particletemplate/sphere (clumps are not deposited yet)");
  long seed = 0;
  double floor = dom.lo[1];
  for (std::size_t i = 3; i < a.size(); i += 2) {
    if (a[i] == "seed") {
      seed = parse_prime_seed(a, i + 1);
    } else if (a[i] == "floor") {
      floor = a.num(i + 1, "the floor height y");
      if (!(floor >= dom.lo[1] && floor < dom.hi[1])) a.fail(i + 1, "a floor height inside the box's y range");
    } else {
      a.fail(i, "a ballistic_deposit keyword: seed, floor");
    }
  }
  if (seed == 0) a.fail(a.size(), "'seed S' (a prime > 10000)");
  Atoms& at = sim.atoms;
  double rmax = tmpl->radius.max();
  for (std::size_t i = 0; i < at.n; ++i) rmax = std::max(rmax, at.radius[i]);
  const double W = dom.length(0);
  // A narrower period lets a disk touch two images of one grain (or itself).
  if (!(W > 4 * rmax))
    a.fail(0, "a box wider than 4 largest radii (" + std::to_string(4 * rmax) + ") in x: it is " + std::to_string(W));
  if (floor + 2 * tmpl->radius.max() > dom.hi[1])
    a.fail(0, "a box taller than one grain diameter above the floor");
  // Disks cover at most ~0.91 of the area: a bound that stops a runaway 'fill' before it starts.
  constexpr double kMaxGrains = 1e7;
  const double rmin = tmpl->radius.min();
  const double fits = W * (dom.hi[1] - floor) / (std::numbers::pi * rmin * rmin);
  if ((n < 0 && fits > kMaxGrains) || n > kMaxGrains)
    a.fail(1, "at most 1e7 grains (" + (n < 0 ? "the box holds up to " + std::to_string(fits) + " of the smallest"
                                               : std::to_string(n) + " asked") + "): a smaller box or a smaller N");

  const auto t0 = std::chrono::steady_clock::now();
  Deposit dep(dom.lo[0], W, floor, rmax);
  for (std::size_t i = 0; i < at.n; ++i) dep.add({at.x[3 * i], at.x[3 * i + 1], at.radius[i]});
  const std::size_t first = dep.disks.size();
  std::vector<FixParticletemplateSphere::Grain> grains;
  Rng rng(static_cast<std::uint64_t>(seed));
  long added = 0;
  double area = 0, ymax = floor;
  while (n < 0 || added < n) {
    const auto g = tmpl->draw();
    const double x0 = dom.lo[0] + rng.uniform() * W;
    double x, y;
    if (!Faller(dep, g.radius).settle(x0, x, y))
      a.fail_line("grain " + std::to_string(added + 1) + " found no rest after 100000 moves (a bug: please report it)");
    if (y + g.radius > dom.hi[1]) {
      if (n < 0) break;
      a.fail_line("grain " + std::to_string(added + 1) + " of " + std::to_string(n) + " would rest with its top at y = " +
                  std::to_string(y + g.radius) + ", above the box top " + std::to_string(dom.hi[1]) +
                  ": a taller box, fewer grains, or 'fill'");
    }
    x -= W * std::floor((x - dom.lo[0]) / W);
    if (x >= dom.hi[0]) x = dom.lo[0];
    dep.add({x, y, g.radius});
    grains.push_back(g);
    ++added;
    area += std::numbers::pi * g.radius * g.radius;
    ymax = std::max(ymax, y + g.radius);
  }
  // Atoms only once every grain found its place: a failed command adds none.
  for (std::size_t k = 0; k < grains.size(); ++k) {
    const Disk& p = dep.disks[first + k];
    const double pos[3] = {p.x, p.y, 0.0};
    const std::size_t i = at.add(at.max_id + 1, grains[k].type, pos, p.r, grains[k].density);
    at.rmass[i] = grains[k].mass;  // disc mass in 2D, as the template computed it
    at.mask[i] |= tmpl->groupbit;
  }
  const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  char buf[256];
  std::snprintf(buf, sizeof buf,
                "ballistic_deposit: %ld disks, deposit top %.6g, area fraction below it %.4f, %.3f s", added, ymax,
                area / (W * (ymax - floor)), secs);
  sim.print(buf);
}

}  // namespace

SABLE_COMMAND("ballistic_deposit", cmd_ballistic_deposit);

}  // namespace sable
