#include "core/engine/neighbor.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <numeric>

#include "core/engine/atoms.h"
#include "core/engine/domain.h"
#include "core/engine/threads.h"

#ifdef _OPENMP
#include <omp.h>
#endif

namespace sable {

int ContactStore::thread_slot() {
#ifdef _OPENMP
  return omp_get_thread_num();
#else
  return 0;
#endif
}

std::size_t ContactStore::slack() {
#ifdef _OPENMP
  const int nt = omp_get_max_threads();
#else
  const int nt = 1;
#endif
  return static_cast<std::size_t>(std::min(nt, kSlots)) * kBlock;
}

void ContactStore::set_used(int rows) {
  used_ = rows;
  for (int t = 0; t < kSlots; ++t) cursor_[t] = Cursor{};
}

void ContactStore::configure(const std::vector<HistorySlot>& s) {
  slots = s;
  size = static_cast<int>(s.size());
  saved_.configure(size), injected_.configure(size);
  buf_.reset();
  cap_ = 0;
}

void ContactStore::reserve_rows(std::size_t rows) {
  set_used(0);
  if (rows <= cap_ && buf_) return;
  cap_ = rows;
  buf_ = std::make_unique_for_overwrite<double[]>(std::max<std::size_t>(cap_ * size, 1));
}

// Twice the entries: make_room() then only compacts after as many new contacts
// as there are entries, which a rebuild usually comes well before.
void ContactStore::resize(std::size_t entries) {
  row.assign(entries, kNone);
  reserve_rows(2 * entries + 16 + slack());
}

void ContactStore::make_room() {
  const std::size_t entries = row.size();
  if (static_cast<std::size_t>(used_) + entries + slack() <= cap_) return;
  std::vector<double> live;
  for (int& r : row)
    if (r >= 0) {
      live.insert(live.end(), buf_.get() + static_cast<std::size_t>(r) * size, buf_.get() + (r + 1ul) * size);
      r = static_cast<int>(live.size() / size) - 1;
    }
  reserve_rows(std::max(2 * entries + 16 + slack(), cap_));
  std::copy(live.begin(), live.end(), buf_.get());
  set_used(static_cast<int>(live.size() / size));
}

std::size_t ContactStore::contacts() const {
  return static_cast<std::size_t>(std::count_if(row.begin(), row.end(), [](int r) { return r >= 0; }));
}

// In blocks of atoms, in parallel for large lists: each block counts its
// contacts, then writes them at its offset (atom order, as a serial pass).
HistoryStore ContactStore::touching(const NeighborList& list, const std::vector<long>& ids) const {
  HistoryStore out;
  touching(list, ids, out);
  return out;
}

// Into `out`, whose buffers are reused and resized, not cleared: fresh ones
// each rebuild cost page faults and zero-filling in the serial part.
void ContactStore::touching(const NeighborList& list, const std::vector<long>& ids, HistoryStore& out) const {
  if (out.size() != size) out.configure(size);
  if (row.empty() || row.size() != list.size()) {
    out.clear();
    return;
  }
  const std::size_t n = list.first.empty() ? 0 : list.first.size() - 1;
  const int nth = loop_thread_count(list.size(), 2);
  std::vector<std::size_t> base(nth + 1, 0);
  auto entries = [&](int t) { return std::pair(list.first[n * t / nth], list.first[n * (t + 1) / nth]); };
#pragma omp parallel num_threads(nth) if (nth > 1)
  {
#pragma omp for schedule(static, 1)
    for (int t = 0; t < nth; ++t) {
      const auto [k0, k1] = entries(t);
      base[t + 1] = static_cast<std::size_t>(std::count_if(row.begin() + k0, row.begin() + k1, [](int r) { return r >= 0; }));
    }
#pragma omp single
    {
      std::partial_sum(base.begin(), base.end(), base.begin());
      out.resize(base[nth]);
    }
#pragma omp for schedule(static, 1)
    for (int t = 0; t < nth; ++t) {
      std::size_t c = base[t];
      for (std::size_t i = n * t / nth; i < n * (t + 1) / nth; ++i)
        for (int k = list.first[i]; k < list.first[i + 1]; ++k) {
          const double* h = history(k);
          if (!h) continue;
          out.set_key(c, {ids[i], ids[list.j[k]], 0});
          std::copy_n(h, size, out.row(c));
          ++c;
        }
    }
  }
}

void ContactStore::save(const NeighborList& list, const std::vector<long>& ids) {
  touching(list, ids, saved_);
  // Restart contacts go after the list's own: restore() sees them the same way.
  saved_.append(injected_);
  injected_.clear();
}

std::vector<std::string> ContactStore::inject(const std::vector<HistorySlot>& from, const HistoryStore& c) {
  std::vector<int> src(size, -1);  // our slot m <- their slot src[m]
  std::vector<std::string> missing;
  for (int m = 0; m < size; ++m) {
    for (std::size_t q = 0; q < from.size(); ++q)
      if (from[q].name == slots[m].name) src[m] = static_cast<int>(q);
    if (src[m] < 0) missing.push_back(slots[m].name);
  }
  const std::size_t first = injected_.count();
  injected_.resize(first + c.count());
  for (std::size_t s = 0; s < c.count(); ++s) {
    injected_.set_key(first + s, c.key(s));
    double* h = injected_.row(first + s);
    for (int m = 0; m < size; ++m) h[m] = src[m] < 0 ? 0.0 : c.row(s)[src[m]];
  }
  return missing;
}

// Each saved contact finds its entries in the new list directly: the half list
// holds a pair (a, b), a < b, among the few entries of a; where two saved
// contacts name the same entry, the later one (a restart's) wins. Rows are
// then taken in list order. In parallel for large lists, with the serial
// result; each thread fills the arrays of its own block of entries (a serial
// fill would take the lines from the other core).
void ContactStore::restore(const NeighborList& list, const Atoms& atoms) {
  const std::size_t entries = list.size(), listed = list.first.size() - 1, count = saved_.count();
  row.resize(entries);  // every entry is set below
  reserve_rows(2 * entries + 16 + slack());
  from_.resize(entries);  // entry k <- saved contact s: 2 (s + 1) + (pair seen reversed), 0 for none
  if (count) atoms.index_of(saved_.key(0).tag);  // builds the id map here, before the threads read it
  const int nth = loop_thread_count(entries, 2);
  std::vector<int> base(nth + 1, 0);
  auto block = [&](int t) { return std::pair(entries * t / nth, entries * (t + 1) / nth); };
#pragma omp parallel num_threads(nth) if (nth > 1)
  {
#pragma omp for schedule(static, 1)
    for (int t = 0; t < nth; ++t) {
      const auto [k0, k1] = block(t);
      std::fill(from_.begin() + k0, from_.begin() + k1, 0);
    }
#pragma omp for schedule(static)
    for (long s = 0; s < static_cast<long>(count); ++s) {
      const HistoryStore::Key key = saved_.key(static_cast<std::size_t>(s));
      const std::size_t a = atoms.index_of(key.tag), b = atoms.index_of(key.partner);
      if (a == Atoms::npos || b == Atoms::npos || a == b) continue;
      const std::size_t lo = std::min(a, b), hi = std::max(a, b);
      if (lo >= listed) continue;
      const int tag = 2 * static_cast<int>(s + 1) + (a > b);
      for (int k = list.first[lo]; k < list.first[lo + 1]; ++k)
        if (list.j[k] == static_cast<int>(hi)) {
          std::atomic_ref<int> f(from_[k]);
          int cur = f.load(std::memory_order_relaxed);
          while (cur < tag && !f.compare_exchange_weak(cur, tag, std::memory_order_relaxed)) {
          }
        }
    }
    // Rows in list order: each block counts its contacts, then fills its rows.
#pragma omp for schedule(static, 1)
    for (int t = 0; t < nth; ++t) {
      const auto [k0, k1] = block(t);
      base[t + 1] = static_cast<int>(std::count_if(from_.begin() + k0, from_.begin() + k1, [](int v) { return v; }));
    }
#pragma omp single
    std::partial_sum(base.begin(), base.end(), base.begin());
#pragma omp for schedule(static, 1)
    for (int t = 0; t < nth; ++t) {
      const auto [k0, k1] = block(t);
      int r = base[t];
      for (std::size_t k = k0; k < k1; ++k) {
        if (!from_[k]) {
          row[k] = kNone;
          continue;
        }
        const bool swapped = from_[k] & 1;
        const double* v = saved_.row(static_cast<std::size_t>(from_[k] / 2 - 1));
        double* h = buf_.get() + static_cast<std::size_t>(row[k] = r++) * size;
        for (int m = 0; m < size; ++m) h[m] = (swapped && slots[m].flip) ? -v[m] : v[m];
      }
    }
  }
  set_used(base[nth]);  // saved_ stays: the next save() overwrites it in place
}

// The largest squared displacement since the last build over atoms [lo, hi).
// A maximum does not depend on the order: threads and SIMD give the same value.
// A non-finite position gives NaN (a comparison alone would skip it). Kept in
// kLanes independent lanes: one chain of dependent maxima and sums made this
// pass latency-bound.
static double range_max_displacement_sq(const double* x, const double* xh, std::size_t lo, std::size_t hi) {
  constexpr long kLanes = 8;
  double ml[kLanes] = {}, nl[kLanes] = {};
  auto lane = [&](long l, long i) {
    const double dx = x[3 * i] - xh[3 * i], dy = x[3 * i + 1] - xh[3 * i + 1], dz = x[3 * i + 2] - xh[3 * i + 2];
    const double d2 = dx * dx + dy * dy + dz * dz;
    ml[l] = d2 > ml[l] ? d2 : ml[l];
    nl[l] += d2 - d2;  // 0, or NaN for an infinite or NaN d2
  };
  long i = static_cast<long>(lo);
  for (; i + kLanes <= static_cast<long>(hi); i += kLanes)
    for (long l = 0; l < kLanes; ++l) lane(l, i + l);
  for (; i < static_cast<long>(hi); ++i) lane(0, i);
  double m = 0.0, nan = 0.0;
  for (long l = 0; l < kLanes; ++l) {
    m = ml[l] > m ? ml[l] : m;
    nan += nl[l];
  }
  return m + nan;
}

// The ranges' maxima: the largest, or NaN if any is.
static double max_of_parts(const std::vector<double>& part) {
  double m = 0.0, nan = 0.0;
  for (double p : part) {
    m = p > m ? p : m;
    nan += p - p;
  }
  return m + nan;
}

bool Neighbor::decide(const Atoms& atoms, long step) {
  if (last_build_step < 0 || xhold_.size() != 3 * atoms.n) return true;
  if (radii_vary && rhold_.size() != atoms.n) return true;
  const long since = step - last_build_step;
  if (since < delay || (every > 0 && since % every != 0)) return false;
  if (!check) return true;
  positions_scanned_step = step;
  if (radii_vary) {
    prescan_.step = -1;
    return moved_or_grew(atoms);
  }
  const bool ahead = prescan_.step == step && prescan_.n == atoms.n;  // announced for this step
  const double d2 = ahead ? max_of_parts(prescan_.part) : max_displacement_sq(atoms);
  prescans_used += ahead;
  prescan_.step = -1;
  return !(d2 <= 0.25 * skin * skin);  // NaN too: the rebuild checks positions
}

double Neighbor::max_displacement_sq(const Atoms& atoms) const {
  const double* x = atoms.x.data();
  const double* xh = xhold_.data();
  std::vector<double> part(atom_pass_threads(), 0.0);
  atoms.for_ranges([&](int t, std::size_t lo, std::size_t hi) { part[t] = range_max_displacement_sq(x, xh, lo, hi); });
  return max_of_parts(part);
}

// A pair's gap closes by both displacements plus both growths since the build:
// each grain may use skin/2 of it (LIGGGHTS' rule for varying radii), so grain i
// triggers a rebuild when |dx_i| > skin/2 - dr_i or |dr_i| > skin/2.
bool Neighbor::moved_or_grew(const Atoms& atoms) const {
  const double half = 0.5 * skin;
  const double* x = atoms.x.data();
  const double* r = atoms.radius.data();
  std::vector<char> part(atom_pass_threads(), 0);
  atoms.for_ranges([&](int t, std::size_t lo, std::size_t hi) {
    bool any = false;
    for (std::size_t i = lo; i < hi; ++i) {
      const double dx = x[3 * i] - xhold_[3 * i], dy = x[3 * i + 1] - xhold_[3 * i + 1],
                   dz = x[3 * i + 2] - xhold_[3 * i + 2];
      const double dr = r[i] - rhold_[i], room = half - dr;
      any |= !(std::fabs(dr) <= half) || !(dx * dx + dy * dy + dz * dz <= room * room);  // NaN too
    }
    part[t] = any;
  });
  return std::find(part.begin(), part.end(), 1) != part.end();
}

void Neighbor::expect_prescan(const Atoms& atoms, long step) {
  prescan_.step = xhold_.size() == 3 * atoms.n ? step : -1;
  prescan_.n = atoms.n;
  prescan_.part.assign(atom_pass_threads(), 0.0);
}

void Neighbor::prescan_range(const Atoms& atoms, int t, std::size_t lo, std::size_t hi) {
  if (prescan_.step >= 0) prescan_.part[t] = range_max_displacement_sq(atoms.x.data(), xhold_.data(), lo, hi);
}

// One atom's entries by partner index, then image code (insertion sort: a
// few entries; a full sort when a cutoff as wide as the box gives each atom
// thousands, which insertion sort would crawl through). The threaded force pass
// relies on it: the entries whose partner lies in a later thread's range are
// then the atom's last ones.
static void sort_entries(int* j, std::uint8_t* shift, std::size_t n) {
  if (n > 64) {
    thread_local std::vector<std::int64_t> key;
    key.resize(n);
    for (std::size_t a = 0; a < n; ++a) key[a] = (static_cast<std::int64_t>(j[a]) << 8) | shift[a];
    std::sort(key.begin(), key.end());
    for (std::size_t a = 0; a < n; ++a) {
      j[a] = static_cast<int>(key[a] >> 8);
      shift[a] = static_cast<std::uint8_t>(key[a] & 0xff);
    }
    return;
  }
  for (std::size_t a = 1; a < n; ++a) {
    const int jj = j[a];
    const std::uint8_t sh = shift[a];
    std::size_t b = a;
    for (; b > 0 && (j[b - 1] > jj || (j[b - 1] == jj && shift[b - 1] > sh)); --b) {
      j[b] = j[b - 1];
      shift[b] = shift[b - 1];
    }
    j[b] = jj;
    shift[b] = sh;
  }
}

// The slowest axis has the most bins (or nearly: within 20 %), so that the
// two faster ones span the fewest bins (cache locality, above). Among those,
// the threads' atom ranges being contiguous in bin order, each boundary
// between them is a slab of bins across the slowest axis, and every contact
// across it costs the threaded force pass a cross entry, whose grains' cache
// lines both cores touch at each step. So it is the one whose slab at the
// median grain holds the fewest grains (a periodic axis counts twice: its
// ranges meet again across the wrap), counted on a sample of at most 4096
// grains; the last build's axis stays unless another is 20 % better (a flip
// re-deals every grain between the threads). A rotating drum (47 x 47 x 8
// bins) is then cut across its bed's height, not across its wide free
// surface. Any choice gives a valid list; only speed depends on it.
int Neighbor::pick_slow_axis(const Atoms& atoms, const Domain& domain, const int nb[3], const double inv[3]) {
  // Every grain, or 4096 spread by the golden ratio (a fixed stride can alias
  // with a lattice of grains just created), in one pass for all axes.
  const std::size_t n = atoms.n, samples = std::min<std::size_t>(n, 4096);
  const int most = std::max({nb[0], nb[1], nb[2]});
  bool candidate[3] = {false, false, false};
  std::vector<int> count[3];
  for (int k = 0; k < domain.dimension; ++k)
    if (nb[k] >= 2 && 1.2 * nb[k] >= most) {
      candidate[k] = true;
      count[k].assign(nb[k], 0);
    }
  // Each thread counts the samples among its own grains (a serial look would
  // take the other core's lines).
  std::vector<std::vector<int>> part(atom_pass_threads());
  atoms.for_ranges([&](int t, std::size_t lo, std::size_t hi) {
    std::vector<int>& cnt = part[t];
    cnt.assign(nb[0] + nb[1] + nb[2], 0);
    double u = 0.0;  // s times the golden ratio, modulo 1
    for (std::size_t s = 0; s < samples; ++s) {
      const std::size_t i = samples == n ? s : std::min(static_cast<std::size_t>(u * n), n - 1);
      u += 0.6180339887498949;
      u -= u >= 1.0 ? 1.0 : 0.0;
      if (i < lo || i >= hi) continue;
      for (int k = 0, at = 0; k < 3; at += nb[k++])
        if (candidate[k]) {
          const int c = static_cast<int>((atoms.x[3 * i + k] - domain.lo[k]) * inv[k]);
          ++cnt[at + std::clamp(c, 0, nb[k] - 1)];
        }
    }
  });
  for (const std::vector<int>& cnt : part)
    for (int k = 0, at = 0; k < 3; at += nb[k++])
      if (candidate[k] && !cnt.empty())
        for (int c = 0; c < nb[k]; ++c) count[k][c] += cnt[at + c];
  double cut[3] = {1e300, 1e300, 1e300};
  for (int k = 0; k < 3; ++k) {
    if (!candidate[k]) continue;
    std::size_t below = 0;
    int c = 0;
    while (c + 1 < nb[k] && 2 * (below + count[k][c]) < samples) below += count[k][c++];
    cut[k] = count[k][c] * (domain.wraps(k) ? 2.0 : 1.0);
  }
  int best = 0;
  for (int k = 1; k < 3; ++k)
    if (cut[k] < cut[best] || (cut[k] == cut[best] && nb[k] > nb[best])) best = k;
  if (slow_axis_ >= 0 && cut[slow_axis_] < 1e300 && cut[slow_axis_] <= 1.2 * cut[best]) return slow_axis_;
  return best;
}

void Neighbor::ids_renumbered(const std::vector<long>& old_ids, const std::vector<long>& new_ids) {
  for (long& id : ids_) {
    const auto at = std::lower_bound(old_ids.begin(), old_ids.end(), id);
    id = at == old_ids.end() || *at != id ? -1 : new_ids[static_cast<std::size_t>(at - old_ids.begin())];
  }
}

void Neighbor::save_history(ContactStore* store) {
  if (store) store->save(list, ids_);
  history_saved_ = true;
}

void Neighbor::sort_owned(Atoms& atoms, const Domain& box, double cutoff) {
  const std::size_t n = atoms.n;
  if (!sort || n == 0 || !(cutoff > 0)) return;
  int nb[3] = {1, 1, 1};
  for (int k = 0; k < box.dimension; ++k)
    nb[k] = std::clamp(static_cast<int>(box.length(k) / cutoff), 1, 1 << 10);
  std::vector<std::size_t> key(n);
  for (std::size_t i = 0; i < n; ++i) {
    std::size_t b = 0;
    for (int k = 2; k >= 0; --k) {
      const int c = static_cast<int>((atoms.x[3 * i + k] - box.lo[k]) / box.length(k) * nb[k]);
      b = b * static_cast<std::size_t>(nb[k]) + static_cast<std::size_t>(std::clamp(c, 0, nb[k] - 1));
    }
    key[i] = b;
  }
  order_.resize(n);
  std::iota(order_.begin(), order_.end(), std::size_t{0});
  std::stable_sort(order_.begin(), order_.end(), [&](std::size_t a, std::size_t b) { return key[a] < key[b]; });
  atoms.permute(order_);
}

void Neighbor::build(Atoms& atoms, const Domain& box, ContactStore* store, long step) {
  if (store && !history_saved_) store->save(list, ids_);
  history_saved_ = false;
  const bool ghosts = ghosted.on;
  const Domain& domain = ghosts ? ghosted.bins : box;
  const std::size_t n = atoms.n, nall = atoms.nall();
  const long nl = static_cast<long>(n), nal = static_cast<long>(nall);
  // Per-atom passes are threaded for large systems; the list is built in
  // blocks of atoms and joined in atom order, so it is the same list (same
  // entries, same order) for every thread count.
  const int nth = loop_thread_count(n, 8);
  double* xa = atoms.x.data();
  int* image = atoms.image.data();
  const double* radius = atoms.radius.data();
  if (!ghosts) {
#pragma omp parallel for schedule(static) if (nth > 1)
    for (long i = 0; i < nl; ++i) domain.remap(&xa[3 * i], &image[3 * i]);
  }

  double rmax = 0.0;
#pragma omp parallel for reduction(max : rmax) schedule(static) if (nth > 1)
  for (long i = 0; i < nl; ++i) rmax = std::max(rmax, radius[i]);
  cutoff_ = ghosts ? ghosted.cutoff : 2.0 * rmax + skin;

  // Bins at least one cutoff wide: the 27 (9 in 2D) surrounding bins hold every partner.
  // In a sparse scene bins grow so that there are at most ~8 per atom. An axis
  // shorter than a bin keeps one and leaves the cap to the others (a tall thin box).
  double binsize = std::max(cutoff_, 1e-300);
  const double cap = 8.0 * std::max<std::size_t>(n, 128);
  for (int pass = 0; pass < 3; ++pass) {
    double cells = 1.0;
    int spread = 0;  // axes with more than one bin
    for (int k = 0; k < domain.dimension; ++k)
      if (const double c = domain.length(k) / binsize; c > 1.0) cells *= c, ++spread;
    if (cells <= cap || spread == 0) break;
    binsize *= std::pow(cells / cap, 1.0 / spread);
  }
  int nb[3] = {1, 1, 1};
  double inv[3] = {0, 0, 0};
  for (int k = 0; k < domain.dimension; ++k) {
    const double L = domain.length(k);
    nb[k] = std::max(1, static_cast<int>(L / binsize));
    inv[k] = nb[k] / L;
  }
  const int nbins = nb[0] * nb[1] * nb[2];
  // Bin numbering: the slowest axis is the one the threads' ranges cut across
  // (pick_slow_axis); of the other two the one with fewer bins varies fastest.
  // After the sort, a grain's partners then lie within about one slab of the
  // two faster axes in memory (a flat bed: 15 x 72 bins instead of 72 x 72),
  // which keeps the force pass's j-side reads in cache.
  int ax[3] = {0, 1, 2};
  std::stable_sort(ax, ax + 3, [&](int a, int b) { return nb[a] < nb[b]; });
  slow_axis_ = pick_slow_axis(atoms, domain, nb, inv);
  std::stable_partition(ax, ax + 3, [&](int a) { return a != slow_axis_; });
  int stride[3];
  stride[ax[0]] = 1;
  stride[ax[1]] = nb[ax[0]];
  stride[ax[2]] = nb[ax[0]] * nb[ax[1]];
  bin_of_.resize(nall);
  auto coord = [&](double x, int k) {
    int c = static_cast<int>(std::floor((x - domain.lo[k]) * inv[k]));
    return std::clamp(c, 0, nb[k] - 1);
  };
  int* bin_of = bin_of_.data();
#pragma omp parallel for schedule(static) if (nth > 1)
  for (long i = 0; i < nal; ++i) {
    const double* xi = &xa[3 * i];
    bin_of[i] = coord(xi[0], 0) * stride[0] + coord(xi[1], 1) * stride[1] + coord(xi[2], 2) * stride[2];
  }
  // Counting sort by bin: the atoms in bin order, as the new order of the
  // atoms (sorted: then a bin's atoms are consecutive indices) or as a list.
  bin_start_.assign(nbins + 1, 0);
  for (std::size_t i = 0; i < nall; ++i) ++bin_start_[bin_of_[i] + 1];
  std::partial_sum(bin_start_.begin(), bin_start_.end(), bin_start_.begin());
  const bool sorted = sort && n > 0 && !ghosts;
  {
    std::vector<int> fill(bin_start_.begin(), bin_start_.end() - 1);
    if (sorted) {
      order_.resize(n);
      for (std::size_t i = 0; i < n; ++i) order_[fill[bin_of_[i]]++] = i;
    } else {
      bin_atoms_.resize(nall);
      for (std::size_t i = 0; i < nall; ++i) bin_atoms_[fill[bin_of_[i]]++] = static_cast<int>(i);
    }
  }
  if (sorted) {
    atoms.permute(order_);
    const int nbl = nbins;
#pragma omp parallel for schedule(static) if (nth > 1)
    for (int b = 0; b < nbl; ++b)
      for (int s = bin_start_[b]; s < bin_start_[b + 1]; ++s) bin_of_[s] = b;
  }

  for (int c = 0; c < 27; ++c) {
    const int s[3] = {c % 3 - 1, (c / 3) % 3 - 1, c / 9 - 1};
    for (int k = 0; k < 3; ++k) list.shift_vec[c][k] = s[k] * domain.length(k);
  }

  const int zr = domain.dimension == 3 ? 1 : 0;
  const double* x = atoms.x.data();  // after the sort
  radius = atoms.radius.data();
  // The bins around bin b with the image code of each (through a periodic
  // axis of one or two bins a bin can come twice, as two images). Sorted atoms
  // are in bin order, so a lower bin holds only atoms j < i: left out.
  struct Stencil {
    int n = 0;
    int bin[27];
    std::uint8_t code[27];
  };
  // Inside the box (a bin away from every face along the stencil's axes) the
  // stencil is b + fixed offsets, in increasing order (then each atom's
  // entries come out sorted by j), all without image shift.
  const int dims = domain.dimension == 3 ? 3 : 2;
  int inner[27], ninner = 0;
  for (int oz = -zr; oz <= zr; ++oz)
    for (int oy = -1; oy <= 1; ++oy)
      for (int ox = -1; ox <= 1; ++ox) {
        const int off = ox * stride[0] + oy * stride[1] + oz * stride[2];
        if (!sorted || off >= 0) inner[ninner++] = off;
      }
  std::sort(inner, inner + ninner);
  auto stencil = [&](int b, Stencil& st) {
    const int bc[3] = {(b / stride[0]) % nb[0], (b / stride[1]) % nb[1], (b / stride[2]) % nb[2]};
    bool interior = true;
    for (int k = 0; k < dims; ++k) interior = interior && bc[k] >= 1 && bc[k] <= nb[k] - 2;
    if (interior) {
      st.n = ninner;
      for (int q = 0; q < ninner; ++q) {
        st.bin[q] = b + inner[q];
        st.code[q] = NeighborList::kNoShift;
      }
      return;
    }
    st.n = 0;
    for (int oz = -zr; oz <= zr; ++oz)
      for (int oy = -1; oy <= 1; ++oy)
        for (int ox = -1; ox <= 1; ++ox) {
          const int o[3] = {ox, oy, oz};
          int nbc[3], sh[3];
          bool ok = true;
          for (int k = 0; k < 3 && ok; ++k) {
            nbc[k] = bc[k] + o[k];
            sh[k] = 0;
            if (nbc[k] < 0 || nbc[k] >= nb[k]) {
              if (!domain.wraps(k)) {
                ok = false;
              } else {
                sh[k] = nbc[k] < 0 ? -1 : 1;
                nbc[k] -= sh[k] * nb[k];
              }
            }
          }
          // Without wrap, a neighbouring offset outside a single-bin axis is not a new cell.
          if (!ok) continue;
          const int nbin = nbc[0] * stride[0] + nbc[1] * stride[1] + nbc[2] * stride[2];
          if (sorted && nbin < b) continue;
          st.bin[st.n] = nbin;
          st.code[st.n++] = static_cast<std::uint8_t>((sh[0] + 1) + 3 * (sh[1] + 1) + 9 * (sh[2] + 1));
        }
  };
  // Entries of atom i (partners j > i within the cutoff plus skin) in the bins
  // of `st`, appended to (js, shifts).
  const double* exclusion = atoms.pair_exclusion >= 0 ? atoms.column(atoms.pair_exclusion).data() : nullptr;
  const bool rules = !exclusions.empty();
  const int* type = atoms.type.data();
  const std::uint32_t* mask = atoms.mask.data();
  auto ruled_out = [&](int i, int j) {
    for (const Exclusion& e : exclusions) {
      const bool hit = e.by_type ? (type[i] == e.type_a && type[j] == e.type_b) ||
                                       (type[i] == e.type_b && type[j] == e.type_a)
                                 : ((mask[i] & e.bit_a) && (mask[j] & e.bit_b)) ||
                                       ((mask[i] & e.bit_b) && (mask[j] & e.bit_a));
      if (hit) return true;
    }
    return false;
  };
  auto scan = [&](std::size_t i, const Stencil& st, std::vector<int>& js, std::vector<std::uint8_t>& shifts) {
    const double xi0 = x[3 * i], xi1 = x[3 * i + 1], xi2 = x[3 * i + 2], ri = radius[i];
    const int ii = static_cast<int>(i);
    const double key = exclusion ? exclusion[i] : 0.0;
    for (int q = 0; q < st.n; ++q) {
      const int nbin = st.bin[q];
      const std::uint8_t code = st.code[q];
      const double* sv = list.shift_vec[code];
      const double s0 = sv[0], s1 = sv[1], s2 = sv[2];
      auto test = [&](int j) {
        const double dx = x[3 * j] + s0 - xi0, dy = x[3 * j + 1] + s1 - xi1, dz = x[3 * j + 2] + s2 - xi2;
        const double cut = ri + radius[j] + skin;
        if (dx * dx + dy * dy + dz * dz < cut * cut && (key == 0.0 || exclusion[j] != key) &&
            !(rules && ruled_out(ii, j))) {
          js.push_back(j);
          shifts.push_back(code);
        }
      };
      if (sorted) {  // a bin's atoms are consecutive indices
        for (int j = std::max(bin_start_[nbin], ii + 1); j < bin_start_[nbin + 1]; ++j) test(j);
      } else {
        for (int s = bin_start_[nbin]; s < bin_start_[nbin + 1]; ++s)
          if (bin_atoms_[s] > ii) test(bin_atoms_[s]);
      }
    }
  };
  // Atoms [lo, hi) appended to (js, shifts), first[i + 1] = js.size() after atom i;
  // returns the largest j - i of an entry without image shift. The stencil is
  // found once per bin (sorted atoms come bin after bin).
  auto scan_range = [&](std::size_t lo, std::size_t hi, std::vector<int>& js, std::vector<std::uint8_t>& shifts) {
    int span = 0;
    Stencil st;
    int st_bin = -1;
    for (std::size_t i = lo; i < hi; ++i) {
      if (bin_of_[i] != st_bin) stencil(st_bin = bin_of_[i], st);
      const std::size_t k0 = js.size();
      scan(i, st, js, shifts);
      sort_entries(js.data() + k0, shifts.data() + k0, js.size() - k0);
      for (std::size_t k = k0; k < js.size(); ++k)
        if (shifts[k] == NeighborList::kNoShift && js[k] < nl) span = std::max(span, js[k] - static_cast<int>(i));
      list.first[i + 1] = static_cast<int>(js.size());
    }
    return span;
  };
  list.first.assign(n + 1, 0);
  if (nth <= 1) {
    list.j.clear();
    list.shift.clear();
    list.span = scan_range(0, n, list.j, list.shift);
  } else {
    // One block of atoms per thread; first[i + 1] holds the count within the
    // block until the join. Each block's vectors sit on their own cache lines
    // (their end pointers change at every entry) and are kept between builds.
    if (blocks_.size() < static_cast<std::size_t>(nth)) blocks_.resize(nth);
    std::vector<std::size_t> base(nth + 1, 0);
    int span = 0;
#pragma omp parallel num_threads(nth) reduction(max : span)
    {
#pragma omp for schedule(static, 1)
      for (int t = 0; t < nth; ++t) {
        ScanBlock& bk = blocks_[t];
        bk.j.clear();
        bk.shift.clear();
        span = std::max(span, scan_range(n * t / nth, n * (t + 1) / nth, bk.j, bk.shift));
      }
#pragma omp single
      {
        for (int t = 0; t < nth; ++t) base[t + 1] = base[t] + blocks_[t].j.size();
        list.j.resize(base[nth]);
        list.shift.resize(base[nth]);
      }
#pragma omp for schedule(static, 1)
      for (int t = 0; t < nth; ++t) {
        const std::size_t lo = n * t / nth, hi = n * (t + 1) / nth;
        for (std::size_t i = lo; i < hi; ++i) list.first[i + 1] += static_cast<int>(base[t]);
        std::copy(blocks_[t].j.begin(), blocks_[t].j.end(), list.j.begin() + base[t]);
        std::copy(blocks_[t].shift.begin(), blocks_[t].shift.end(), list.shift.begin() + base[t]);
      }
    }
    list.span = span;
  }
  if (store) store->restore(list, atoms);
  // On the per-atom passes' ranges (atom_pass_threaded), not serially.
  ids_.resize(nall);
  std::copy(atoms.id.begin() + nl, atoms.id.begin() + nal, ids_.begin() + nl);  // ghosts
  xhold_.resize(3 * n);
  rhold_.resize(radii_vary ? n : 0);
  atoms.for_ranges([&](int, std::size_t lo, std::size_t hi) {
    std::copy(atoms.id.begin() + lo, atoms.id.begin() + hi, ids_.begin() + lo);
    std::copy(atoms.x.begin() + 3 * lo, atoms.x.begin() + 3 * hi, xhold_.begin() + 3 * lo);
    if (radii_vary) std::copy(atoms.radius.begin() + lo, atoms.radius.begin() + hi, rhold_.begin() + lo);
  });
  last_build_step = step;
  ++builds;
}

}  // namespace sable
