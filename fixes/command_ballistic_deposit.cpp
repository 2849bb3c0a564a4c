// ballistic_deposit N|fill TEMPLATE seed S [floor Y] [clump beta B [body ID]]
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
// no concrete fix).
//
// clump beta B (0 < B <= 1): each body is petit2017's rigid 3-disk clump
// (Appendix B, Fig. 15), N counts clumps. Read: one disk at the origin, two
// more at distance r from it at +-30 deg about a common axis (60 deg apart),
// so the three centres make an equilateral triangle of side r = 2 beta R (the
// paper's "triangular arrangement"; beta = 1: touching disks, beta -> 0 one
// disk); one R per clump from the template (its polydispersity applies to R).
// A clump's own disks overlap whenever beta < 1. Each clump falls vertically,
// centroid at a uniformly random x and orientation uniform in [0, 2 pi) (both
// from seed S's stream), and stops at its first contact (any of its disks
// against a deposited disk or the floor). Then, the disk rule generalised, it
// turns rigidly (geometrically, no dynamics, no friction model) about the
// centre of the deposited disk it touches (on the floor: about its own disk
// that touches it), the way that lowers its centre of mass, until
//  - a new contact lies on the far side (in x) of its centre of mass from the
//    pivot's contact: at rest on two contacts either side of it;
//  - a new contact on the same side: that one becomes the pivot (if it lies at
//    or below its disk's equator it bears no weight: the clump stays there,
//    "wedged"; so also when two contacts each block turning about the other);
//  - its touching disk reaches the pivot disk's equator: it falls again;
//  - its centre of mass comes straight below the pivot's centre ("hanging").
// Every clump so ends touching the floor or an earlier grain without overlap;
// the count of each ending is printed (200 clumps at beta 0.62: 192 at rest on
// both sides, 8 wedged). Not a dynamic or frictional rest: a deck settles the
// clumps as rigid bodies afterwards. Atoms: 3 per clump, consecutive IDs (the
// clump number is (id - first id) / 3), image counters that unwrap each clump
// next to its centroid (fix rigid/small reads them); body ID: a scalar fix
// property/atom that receives each clump's number (continuing after the
// largest value already there), for `variable b atom f_ID` and `fix ...
// rigid/small custom v_b`. Box wider than 16 largest radii.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <vector>

#include "core/engine/random.h"
#include "core/engine/simulation.h"
#include "core/input/style_registry.h"
#include "fixes/fix_particletemplate_multisphere.h"
#include "fixes/fix_property_atom.h"
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

  // Disks whose cells lie within ceil(L / h) + 1 of the cell of (x, y): all
  // within L of (x, y) (a clump turning about a point reaches farther than a disk).
  std::vector<int> within(double x, double y, double L) const {
    std::vector<int> out;
    const int k = static_cast<int>(std::ceil(L / h_)) + 1, r0 = row(y);
    for (int c : columns(col(x), k))
      for (int rw = std::max(0, r0 - k); rw <= r0 + k; ++rw)
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

// A rigid clump (petit2017 Appendix B, Fig. 15): three disks of one radius R
// whose centres make an equilateral triangle of side r = 2 beta R. Pose: the
// centroid (= centre of mass: equal disks) and the angle th; disk m's centre is
// the centroid + a (cos(th + 2 pi m / 3), sin(th + 2 pi m / 3)), a = r / sqrt 3.
struct ClumpPose {
  double X, Y, th;
};

// One clump's path: drop, turn, drop ... (see the header). Positions unwrapped.
class ClumpFaller {
 public:
  enum class End { Rest, Wedged, Hanging, Stuck };

  ClumpFaller(const Deposit& dep, double R, double a, double rmax) : dep_(dep), R_(R), a_(a), rmax_(rmax) {}

  End settle(double x0, double th0, ClumpPose& p) {
    p = {x0, 1e300, th0};
    int skip_m = -1, skip_i = -1;
    int still = 0;  // consecutive turns blocked at once
    for (int step = 0; step < 10000; ++step) {
      Contact piv = drop(p, skip_m, skip_i);
      skip_m = skip_i = -1;
      // Turn about successive pivots until at rest or off the pivot's equator.
      for (; step < 10000; ++step) {
        const Turn t = turn(p, piv);
        if (t.kind == Turn::Fall) {
          skip_m = piv.m, skip_i = piv.i;
          break;
        }
        if (t.kind == Turn::Rest) return End::Rest;
        if (t.kind == Turn::Hanging) return End::Hanging;
        still = t.phi > 0 ? 0 : still + 1;
        if (still >= 2) return End::Wedged;  // each contact blocks turning about the other
        piv = t.next;
        if (piv.i >= 0) {  // a contact at or below the new pivot's equator bears no weight
          double cx, cy;
          centre(p, piv.m, cx, cy);
          if (cy - dep_.disks[static_cast<std::size_t>(piv.i)].y <= 1e-12 * R_) return End::Wedged;
        }
      }
    }
    return End::Stuck;
  }

  void centre(const ClumpPose& p, int m, double& cx, double& cy) const {
    const double t = p.th + 2 * std::numbers::pi * m / 3;
    cx = p.X + a_ * std::cos(t), cy = p.Y + a_ * std::sin(t);
  }

 private:
  const Deposit& dep_;
  double R_, a_, rmax_;

  struct Contact {
    int m = -1;     // the clump's disk
    int i = -1;     // the deposit's disk, -1 the floor
    double ix = 0;  // that disk's x image
  };
  struct Turn {
    enum Kind { Rest, Fall, Hanging, Pivot } kind;
    double phi = 0;
    Contact next{};
  };

  // Drops the clump (Y = 1e300: from above everything) to its first contact.
  // Disk skip_m ignores deposit disk skip_i (the pivot it slid off).
  Contact drop(ClumpPose& p, int skip_m, int skip_i) const {
    double best = -1e300;
    Contact c;
    for (int m = 0; m < 3; ++m) {
      const double t = p.th + 2 * std::numbers::pi * m / 3, ox = a_ * std::cos(t), oy = a_ * std::sin(t);
      int hit;
      double hx = 0;
      const double yk = dep_.drop(p.X + ox, p.Y + oy, R_, m == skip_m ? skip_i : -1, hit, hx) - oy;
      if (yk > best) best = yk, c = {m, hit, hx};
    }
    p.Y = std::min(best, p.Y);
    return c;
  }

  // The point where contact c touches (clump at p).
  double contact_x(const ClumpPose& p, const Contact& c) const {
    double cx, cy;
    centre(p, c.m, cx, cy);
    if (c.i < 0) return cx;
    const Disk& d = dep_.disks[static_cast<std::size_t>(c.i)];
    return cx + R_ / (R_ + d.r) * (c.ix - cx);
  }

  static void rotate(ClumpPose& p, double qx, double qy, double ang) {
    const double c = std::cos(ang), s = std::sin(ang), dx = p.X - qx, dy = p.Y - qy;
    p.X = qx + c * dx - s * dy, p.Y = qy + s * dx + c * dy, p.th += ang;
  }

  // The clump turns rigidly about Q, the centre of the pivot disk it touches
  // (or, on the floor, of its own disk that touches it: both keep the contact),
  // the way that lowers its centre of mass, until (the first of) a new contact,
  // the touching disk reaching the pivot's equator (Fall), or the centre of
  // mass straight below Q (Hanging). At a new contact on the far side of the
  // centre of mass from the pivot's: Rest; else that contact is the next pivot.
  Turn turn(ClumpPose& p, const Contact& piv) const {
    constexpr double pi = std::numbers::pi;
    double qx, qy;
    if (piv.i >= 0) {
      qx = piv.ix, qy = dep_.disks[static_cast<std::size_t>(piv.i)].y;
    } else {
      centre(p, piv.m, qx, qy);
    }
    const double vx = p.X - qx, vy = p.Y - qy;
    if (vx == 0 && vy <= 0) return {Turn::Hanging};
    const double w = vx >= 0 ? -1.0 : 1.0;  // clockwise when the centre of mass is right of Q
    const double ac = std::atan2(vy, vx);
    double phi_max = w < 0 ? ac + pi / 2 : 3 * pi / 2 - (ac < 0 ? ac + 2 * pi : ac);
    Turn::Kind end = Turn::Hanging;
    if (piv.i >= 0) {
      double kx, ky;
      centre(p, piv.m, kx, ky);
      const double ak = std::atan2(ky - qy, kx - qx);  // in (0, pi): above the equator
      const double phi_eq = w < 0 ? ak : pi - ak;
      if (phi_eq <= phi_max) phi_max = phi_eq, end = Turn::Fall;
    }
    phi_max = std::max(0.0, phi_max);
    // Events: each clump disk m on its circle about Q meets a deposit disk or the floor.
    double best = 1e300;
    std::vector<std::pair<double, Contact>> hits;
    auto consider = [&](double phi, const Contact& c) {
      if (phi > phi_max) return;
      hits.push_back({phi, c});
      best = std::min(best, phi);
    };
    double reach = 0;
    double cxs[3], cys[3];
    for (int m = 0; m < 3; ++m) {
      centre(p, m, cxs[m], cys[m]);
      reach = std::max(reach, std::hypot(cxs[m] - qx, cys[m] - qy));
    }
    const std::vector<int> near = dep_.within(qx, qy, reach + R_ + rmax_);
    const double W = dep_.period();
    for (int m = 0; m < 3; ++m) {
      const double ux = cxs[m] - qx, uy = cys[m] - qy, rho = std::hypot(ux, uy), al = std::atan2(uy, ux);
      if (piv.i < 0 && m == piv.m) continue;  // turns in place on the floor
      // The angle turned (direction w) to angle ap about Q, in [0, 2 pi).
      auto turned = [&](double ap) {
        double f = std::fmod(w * (ap - al), 2 * pi);
        return f < 0 ? f + 2 * pi : f;
      };
      for (int i : near) {
        if (i == piv.i) continue;  // every clump disk keeps its distance to Q
        const Disk& d = dep_.disks[static_cast<std::size_t>(i)];
        const double L = R_ + d.r;
        for (int n = -1; n <= 1; ++n) {
          const double ix = dep_.nearest_image(d.x, qx) + n * W, dx = ix - qx, dy = d.y - qy;
          const double D = std::hypot(dx, dy), now = std::hypot(cxs[m] - ix, cys[m] - d.y);
          if (D == 0 || rho == 0 || D > rho + L) continue;
          if (std::abs(now - L) <= 1e-9 * L) {  // touching now: blocks at once if the turn pushes into it
            const double g = (cxs[m] - ix) * (-w * uy) + (cys[m] - d.y) * (w * ux);
            if (g < -1e-12 * L * rho) {
              consider(0, {m, i, ix});
              continue;
            }
          }
          const double cv = (rho * rho + D * D - L * L) / (2 * rho * D);
          if (cv > 1 || cv < -1) continue;
          const double be = std::atan2(dy, dx), h = std::acos(cv);
          for (double ap : {be - h, be + h}) {
            const double f = turned(ap);
            if (f > 1e-9 && f < 2 * pi - 1e-9) consider(f, {m, i, ix});
          }
        }
      }
      // The floor: centre height floor + R.
      const double yf = dep_.floor() + R_;
      if (std::abs(cys[m] - yf) <= 1e-9 * R_ && w * ux < -1e-12 * rho) {
        consider(0, {m, -1, 0});
      } else {
        const double sv = (yf - qy) / rho;
        if (sv >= -1 && sv <= 1) {
          const double as = std::asin(sv);
          for (double ap : {as, pi - as}) {
            const double f = turned(ap);
            if (f > 1e-9 && f < 2 * pi - 1e-9) consider(f, {m, -1, 0});
          }
        }
      }
    }
    if (hits.empty()) {
      rotate(p, qx, qy, w * phi_max);
      return {end, phi_max};
    }
    rotate(p, qx, qy, w * best);
    // Every contact made at that angle: one beyond the centre of mass holds the clump.
    const double p1 = contact_x(p, piv) - p.X;
    Turn t{Turn::Pivot, best};
    double nearest = 1e300;
    for (const auto& [phi, c] : hits) {
      if (phi > best + 1e-9) continue;
      const double p2 = contact_x(p, c) - p.X;
      if (p1 * p2 <= 0) return {Turn::Rest, best};
      if (std::abs(p2) < nearest) nearest = std::abs(p2), t.next = c;
    }
    return t;
  }
};

// ballistic_deposit ... clump beta B [body ID]: n clumps (-1: fill).
void deposit_clumps(Simulation& sim, const Args& a, Deposit& dep, FixParticletemplateSphere& tmpl, long n, long seed,
                    double beta, double rmax, int body_col, std::chrono::steady_clock::time_point t0) {
  const Domain& dom = sim.domain;
  Atoms& at = sim.atoms;
  const double W = dom.length(0);
  for (std::size_t i = 0; i < at.n; ++i) dep.add({at.x[3 * i], at.x[3 * i + 1], at.radius[i]});
  const std::size_t first = dep.disks.size();
  struct Placed {
    FixParticletemplateSphere::Grain g;
    ClumpPose p;
    double cx[3];
  };
  std::vector<Placed> placed;
  Rng rng(static_cast<std::uint64_t>(seed));
  long added = 0, ends[4] = {0, 0, 0, 0};
  double ymax = dep.floor();
  while (n < 0 || added < n) {
    const auto g = tmpl.draw();
    const double R = g.radius, a3 = 2 * beta * R / std::sqrt(3.0);
    const double x0 = dom.lo[0] + rng.uniform() * W, th0 = 2 * std::numbers::pi * rng.uniform();
    ClumpFaller f(dep, R, a3, rmax);
    ClumpPose p;
    const auto end = f.settle(x0, th0, p);
    double top = -1e300;
    double cx[3], cy[3];
    for (int m = 0; m < 3; ++m) f.centre(p, m, cx[m], cy[m]), top = std::max(top, cy[m] + R);
    if (top > dom.hi[1]) {
      if (n < 0) break;
      a.fail_line("clump " + std::to_string(added + 1) + " of " + std::to_string(n) + " would rest with its top at y = " +
                  std::to_string(top) + ", above the box top " + std::to_string(dom.hi[1]) +
                  ": a taller box, fewer clumps, or 'fill'");
    }
    ++ends[static_cast<int>(end)];
    for (int m = 0; m < 3; ++m) {
      double x = cx[m] - W * std::floor((cx[m] - dom.lo[0]) / W);
      if (x >= dom.hi[0]) x = dom.lo[0];
      dep.add({x, cy[m], R});
    }
    placed.push_back({g, p, {cx[0], cx[1], cx[2]}});
    ++added;
    ymax = std::max(ymax, top);
  }
  // Atoms only once every clump found its place: a failed command adds none.
  // A clump's three atoms have consecutive IDs; each keeps the image counter
  // that unwraps it next to its clump's centroid (fix rigid/small unwraps bodies so).
  double body0 = 0;
  if (body_col >= 0)
    for (std::size_t i = 0; i < at.n; ++i) body0 = std::max(body0, at.column(body_col)[i]);
  for (std::size_t k = 0; k < placed.size(); ++k) {
    const double shift = W * std::floor((placed[k].p.X - dom.lo[0]) / W);
    for (int m = 0; m < 3; ++m) {
      const Disk& d = dep.disks[first + 3 * k + static_cast<std::size_t>(m)];
      const double ux = placed[k].cx[m] - shift;  // the centre next to the centroid's image in the box
      const double pos[3] = {d.x, d.y, 0.0};
      const std::size_t i = at.add(at.max_id + 1, placed[k].g.type, pos, d.r, placed[k].g.density);
      at.rmass[i] = placed[k].g.mass;
      at.mask[i] |= tmpl.groupbit;
      at.image[3 * i] = static_cast<int>(std::lround((ux - d.x) / W));
      if (body_col >= 0) at.column(body_col)[i] = body0 + static_cast<double>(k + 1);
    }
  }
  const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  char buf[320];
  std::snprintf(buf, sizeof buf,
                "ballistic_deposit: %ld clumps (%ld disks, beta %g), deposit top %.6g; at rest on contacts either "
                "side of the centre of mass %ld, wedged %ld, hanging %ld, stopped after 10000 moves %ld; %.3f s",
                added, 3 * added, beta, ymax, ends[0], ends[1], ends[2], ends[3], secs);
  sim.print(buf);
}

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
  if (dynamic_cast<FixParticletemplateMultisphere*>(tmpl))  // a sphere template, not its multisphere kin
    a.fail(2, "a fix particletemplate/sphere (for clumps too: 'clump beta B' draws one radius per clump)");
  long seed = 0;
  double floor = dom.lo[1], beta = 0;
  std::string body;
  std::size_t body_at = 0;
  for (std::size_t i = 3; i < a.size(); i += 2) {
    if (a[i] == "clump") {
      if (a.word(i + 1, "'beta B' after clump") != "beta") a.fail(i + 1, "'beta B' after clump");
      ++i;
      beta = a.num(i + 1, "the clump angularity beta = r/(2R), 0 < beta <= 1");
      if (!(beta > 0 && beta <= 1)) a.fail(i + 1, "a clump angularity beta = r/(2R) with 0 < beta <= 1");
    } else if (a[i] == "body") {
      body = a.word(i + 1, "the ID of a fix property/atom (scalar) to hold each clump's body ID");
      body_at = i + 1;
    } else if (a[i] == "seed") {
      seed = parse_prime_seed(a, i + 1);
    } else if (a[i] == "floor") {
      floor = a.num(i + 1, "the floor height y");
      if (!(floor >= dom.lo[1] && floor < dom.hi[1])) a.fail(i + 1, "a floor height inside the box's y range");
    } else {
      a.fail(i, "a ballistic_deposit keyword: seed, floor, clump, body");
    }
  }
  if (seed == 0) a.fail(a.size(), "'seed S' (a prime > 10000)");
  const bool clumps = beta > 0;
  int body_col = -1;
  if (!body.empty()) {
    if (!clumps) a.fail(body_at - 1, "'body' only with 'clump beta B' (a body ID per clump)");
    body_col = sim.atoms.find_column("f_" + body);
    const Fix* bf = sim.find_fix(body);
    if (body_col < 0 || !dynamic_cast<const FixPropertyAtom*>(bf) || sim.atoms.column_stride(body_col) != 1)
      a.fail(body_at, "the ID of a scalar fix property/atom defined earlier (it holds each clump's body ID)");
  }
  Atoms& at = sim.atoms;
  double rmax = tmpl->radius.max();
  for (std::size_t i = 0; i < at.n; ++i) rmax = std::max(rmax, at.radius[i]);
  const double W = dom.length(0);
  // A narrower period lets a disk touch two images of one grain (or itself).
  if (!(W > 4 * rmax))
    a.fail(0, "a box wider than 4 largest radii (" + std::to_string(4 * rmax) + ") in x: it is " + std::to_string(W));
  // A clump spans up to 3 diameters; turning about a pivot it reaches about 8 radii from it.
  if (clumps && !(W > 16 * rmax))
    a.fail(0, "a box wider than 16 largest radii (" + std::to_string(16 * rmax) + ") in x for clumps: it is " +
                  std::to_string(W));
  if (floor + 2 * tmpl->radius.max() * (clumps ? 1 + beta : 1) > dom.hi[1])
    a.fail(0, std::string("a box taller than one ") + (clumps ? "clump" : "grain") + " above the floor");
  // Disks cover at most ~0.91 of the area: a bound that stops a runaway 'fill' before it starts.
  constexpr double kMaxGrains = 1e7;
  const double rmin = tmpl->radius.min();
  const double fits = W * (dom.hi[1] - floor) / (std::numbers::pi * rmin * rmin);
  if ((n < 0 && fits > kMaxGrains) || n > kMaxGrains)
    a.fail(1, "at most 1e7 grains (" + (n < 0 ? "the box holds up to " + std::to_string(fits) + " of the smallest"
                                               : std::to_string(n) + " asked") + "): a smaller box or a smaller N");

  const auto t0 = std::chrono::steady_clock::now();
  Deposit dep(dom.lo[0], W, floor, rmax);
  if (clumps) {
    deposit_clumps(sim, a, dep, *tmpl, n, seed, beta, rmax, body_col, t0);
    return;
  }
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
