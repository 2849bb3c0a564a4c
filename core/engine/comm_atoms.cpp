// The atoms split over the ranks (core/engine/comm.h): exchange, borders, forward.
// Messages go all to all (Comm::all_to_all): simple and enough for the few ranks of
// one machine; each rank's part is in its rank order, so what arrives, and where
// ghosts land, does not depend on timing.
#include <algorithm>
#include <cmath>
#include <numeric>
#include <string>

#include "core/engine/comm.h"
#include "core/engine/contact_source.h"
#include "core/engine/error.h"
#include "core/engine/simulation.h"

namespace sable {

int Comm::owner_of(const double* x, const Domain& box) const {
  Grid c{0, 0, 0};
  for (int k = 0; k < 3; ++k) {
    const int p = grid[k];
    if (p == 1) continue;
    const double lo = box.lo[k], hi = box.hi[k];
    int ck = std::clamp(static_cast<int>(std::floor((x[k] - lo) / (hi - lo) * p)), 0, p - 1);
    while (ck > 0 && x[k] < face_at(box, k, ck)) --ck;  // the faces as split() cuts them, to the bit
    while (ck < p - 1 && x[k] >= face_at(box, k, ck + 1)) ++ck;
    c[k] = ck;
  }
  return rank_at(c);
}

namespace {

// The history stores that travel with their grains: the pair's saved rows, then
// each wall's, in the deck's order (the same on every rank).
struct Stores {
  std::vector<HistoryStore*> store;
  std::vector<std::vector<char>> flip;
  std::vector<ContactSource*> wall;  // per store after the pair's (nullptr for the pair)
};

Stores stores_of(Simulation& sim) {
  Stores s;
  if (sim.pair && sim.pair->history()) {
    ContactStore* c = sim.pair->history();
    s.store.push_back(&c->saved());
    s.flip.emplace_back();
    for (const HistorySlot& h : c->slots) s.flip.back().push_back(h.flip);
    s.wall.push_back(nullptr);
  }
  for (ContactSource* src : contact_sources(sim)) {
    if (src->contact_kind() == ContactSource::Kind::Pairs) continue;
    for (HistoryStore* h : src->histories_by_grain()) {
      s.store.push_back(h);
      s.flip.emplace_back(static_cast<std::size_t>(h->size()), 0);
      s.wall.push_back(src);
    }
  }
  return s;
}

}  // namespace

// Before: the pair's history saved (Neighbor::save_history), no ghosts. Each owned
// atom, remapped into the box, goes to the rank owning its position.
void Comm::exchange(Simulation& sim) {
  Atoms& a = sim.atoms;
  a.drop_ghosts();
  for (std::size_t i = 0; i < a.n; ++i) sim.domain.remap(&a.x[3 * i], &a.image[3 * i]);
  std::vector<int> to(a.n);
  for (std::size_t i = 0; i < a.n; ++i) to[i] = owner_of(&a.x[3 * i], sim.domain);
  // dest(id): where an owned grain goes (-1 stays, -2 not owned here). The first time
  // every rank holds every atom: each keeps its own, nothing is sent.
  const bool first = !distributed;
  std::vector<std::pair<long, int>> moves;  // (id, rank), by id
  for (std::size_t i = 0; i < a.n; ++i) moves.emplace_back(a.id[i], to[i] == rank_ ? -1 : (first ? -2 : to[i]));
  std::sort(moves.begin(), moves.end());
  auto dest = [&](long id) {
    const auto at = std::lower_bound(moves.begin(), moves.end(), std::pair<long, int>{id, -3});
    return at == moves.end() || at->first != id ? -2 : at->second;
  };
  std::vector<std::vector<double>> out(static_cast<std::size_t>(size_));
  std::vector<char> gone(a.n, 0);
  std::vector<std::size_t> natoms(static_cast<std::size_t>(size_), 0);
  for (std::size_t i = 0; i < a.n; ++i) {
    if (to[i] == rank_) continue;
    gone[i] = 1;
    if (first) continue;
    a.pack(i, out[to[i]]);
    ++natoms[to[i]];
  }
  // Each message: the atom count, the atoms, then per store its row count and rows.
  Stores st = stores_of(sim);
  std::vector<std::vector<double>> msg(static_cast<std::size_t>(size_));
  for (int r = 0; r < size_; ++r) {
    msg[r].push_back(static_cast<double>(natoms[r]));
    msg[r].insert(msg[r].end(), out[r].begin(), out[r].end());
  }
  for (std::size_t s = 0; s < st.store.size(); ++s) {
    std::vector<std::vector<double>> rows(static_cast<std::size_t>(size_));
    st.store[s]->migrate(dest, st.flip[s], rows);
    const double per = static_cast<double>(st.store[s]->record_size());
    for (int r = 0; r < size_; ++r) {
      msg[r].push_back(static_cast<double>(rows[r].size()) / per);
      msg[r].insert(msg[r].end(), rows[r].begin(), rows[r].end());
    }
  }
  a.remove_if(gone);
  distributed = true;
  if (first) {
    for (std::size_t s = 0; s < st.store.size(); ++s)
      if (st.wall[s]) st.wall[s]->history_moved();
    return;
  }
  std::vector<double> in;
  std::vector<int> from;
  all_to_all(msg, in, from);
  const std::size_t rec = a.record_size();
  const double* p = in.data();
  for (int r = 0; r < size_; ++r) {
    const double* end = p + from[r];
    const std::size_t count = static_cast<std::size_t>(*p++);
    const std::size_t first_new = a.n;
    a.resize(a.n + count);
    for (std::size_t q = 0; q < count; ++q, p += rec) a.unpack(first_new + q, p);
    for (HistoryStore* h : st.store) {
      const std::size_t rows = static_cast<std::size_t>(*p++);
      p += h->receive(p, rows);
    }
    if (p != end) fail("internal error: a message between ranks was misread (rank " + std::to_string(r) + ")");
  }
  for (std::size_t s = 0; s < st.store.size(); ++s)
    if (st.wall[s]) st.wall[s]->history_moved();
}

// A histogram of the grains along each axis, summed over the ranks (or of every grain
// before they are split), and each inner cut where its share of grains lies below it.
void Comm::balance_shift(Simulation& sim, const std::string& dims, double min_width) {
  const Atoms& a = sim.atoms;
  const Domain& box = sim.domain;
  constexpr int kBins = 4096;
  for (char d : dims) {
    const int k = d - 'x', p = grid[k];
    if (p == 1) continue;
    std::vector<double> hist(kBins, 0.0);
    const double lo = box.lo[k], len = box.length(k);
    for (std::size_t i = 0; i < a.n; ++i)
      hist[static_cast<std::size_t>(std::clamp(static_cast<int>((a.x[3 * i + k] - lo) / len * kBins), 0, kBins - 1))] += 1;
    total(hist.data(), kBins);
    const double all = std::accumulate(hist.begin(), hist.end(), 0.0);
    if (all == 0) continue;
    std::vector<double> c(static_cast<std::size_t>(p - 1));
    double below = 0;
    int b = 0, last = -1;  // bins taken; the last one with grains
    for (int q = 1; q < p; ++q) {  // midway between the grains below the q-th quantile and the next
      while (b < kBins && below + hist[b] <= all * q / p) {
        if (hist[b] > 0) last = b;
        below += hist[b++];
      }
      c[q - 1] = 0.5 * (last + 1 + b) / kBins;
    }
    const double m = std::min(min_width / len, 1.0 / p);  // no slab thinner than the ghost cutoff
    for (int q = 0; q < p - 1; ++q) c[q] = std::max(c[q], (q == 0 ? 0.0 : c[q - 1]) + m);
    for (int q = p - 2; q >= 0; --q) c[q] = std::min(c[q], (q == p - 2 ? 1.0 : c[q + 1]) - m);
    cut[k] = c;
  }
  split(box);
}

std::vector<double> Comm::grains_per_rank(const Simulation& sim) const {
  std::vector<double> c(static_cast<std::size_t>(size_), 0.0);
  for (std::size_t i = 0; i < sim.atoms.n; ++i) c[static_cast<std::size_t>(owner_of(&sim.atoms.x[3 * i], sim.domain))] += 1;
  total(c.data(), size_);
  return c;
}

double Comm::imbalance(const std::vector<double>& c) {
  const double sum = std::accumulate(c.begin(), c.end(), 0.0);
  return sum > 0 ? *std::max_element(c.begin(), c.end()) / (sum / static_cast<double>(c.size())) : 1.0;
}

// No slab thinner than the ghost cutoff: twice the largest radius of all ranks plus the skin.
std::array<double, 2> Comm::rebalance(Simulation& sim, double thresh, const std::string& dims) {
  const double before = imbalance(grains_per_rank(sim));
  if (size_ == 1 || before <= thresh) return {before, before};
  double rmax = 0;
  for (std::size_t i = 0; i < sim.atoms.n; ++i) rmax = std::max(rmax, sim.atoms.radius[i]);
  const double skin = sim.neighbor.skin_set ? sim.neighbor.skin : 0.001;  // the run's default (Simulation::setup)
  balance_shift(sim, dims, 2 * highest(rmax) + skin);
  return {before, imbalance(grains_per_rank(sim))};
}

// An owned atom within `cutoff` of a face it shares with a neighbouring subdomain
// (across the periodic wrap too) becomes a ghost there: offsets of -1, 0, +1 along
// each axis the grid splits, so corners and edges go straight to their rank.
void Comm::borders(Simulation& sim, double cutoff) {
  Atoms& a = sim.atoms;
  const Domain& box = sim.domain;
  a.drop_ghosts();
  for (int k = 0; k < 3; ++k)
    if (grid[k] > 1 && subhi[k] - sublo[k] < cutoff)
      fail("the subdomains along " + std::string(1, char('x' + k)) + " (" + std::to_string(subhi[k] - sublo[k]) +
           ") are thinner than the ghost cutoff " + std::to_string(cutoff) +
           " (twice the largest radius plus the skin): use fewer ranks along that axis (processors)");
  sent_.assign(static_cast<std::size_t>(size_), {});
  std::vector<std::vector<double>> out(static_cast<std::size_t>(size_));
  for (std::size_t i = 0; i < a.n; ++i) {
    const double* x = &a.x[3 * i];
    int near[3][3] = {};  // near[k][off + 1]: within the cutoff of that face
    bool any = false;
    for (int k = 0; k < 3; ++k) {
      near[k][1] = 1;
      if (grid[k] == 1) continue;
      near[k][0] = x[k] < sublo[k] + cutoff;
      near[k][2] = x[k] >= subhi[k] - cutoff;
      any = any || near[k][0] || near[k][2];
    }
    if (!any) continue;
    for (int oz = -1; oz <= 1; ++oz)
      for (int oy = -1; oy <= 1; ++oy)
        for (int ox = -1; ox <= 1; ++ox) {
          const int off[3] = {ox, oy, oz};
          if (!ox && !oy && !oz) continue;
          Grid c = coord;
          double shift[3] = {0, 0, 0};
          bool ok = true;
          for (int k = 0; k < 3 && ok; ++k) {
            if (!near[k][off[k] + 1]) ok = false;
            if (!ok || !off[k]) continue;
            c[k] += off[k];
            if (c[k] < 0 || c[k] >= grid[k]) {
              if (!box.wraps(k)) ok = false;
              c[k] = (c[k] + grid[k]) % grid[k];
              shift[k] = off[k] < 0 ? box.length(k) : -box.length(k);
            }
          }
          if (!ok) continue;
          const int r = rank_at(c);
          Sent& s = sent_[static_cast<std::size_t>(r)];
          s.atom.push_back(static_cast<int>(i));
          s.shift.insert(s.shift.end(), shift, shift + 3);
          const std::size_t at = out[r].size();
          a.pack(i, out[r]);
          for (int k = 0; k < 3; ++k) out[r][at + 3 + k] += shift[k];  // x follows id, type, mask
        }
  }
  std::vector<double> in;
  all_to_all(out, in, ghosts_from_);
  const std::size_t rec = a.record_size();
  for (int& g : ghosts_from_) g /= static_cast<int>(rec);
  const std::size_t count = in.size() / rec;
  const std::size_t first = a.add_ghosts(count);
  for (std::size_t q = 0; q < count; ++q) a.unpack(first + q, in.data() + q * rec);
}

void Comm::forward(Atoms& a) const {
  std::vector<std::vector<double>> out(static_cast<std::size_t>(size_));
  std::vector<int> from(ghosts_from_.size());
  for (std::size_t r = 0; r < ghosts_from_.size(); ++r) from[r] = 9 * ghosts_from_[r];
  for (std::size_t r = 0; r < sent_.size(); ++r) {
    const Sent& s = sent_[r];
    std::vector<double>& o = out[r];
    o.resize(9 * s.atom.size());
    for (std::size_t q = 0; q < s.atom.size(); ++q) {
      const std::size_t i = static_cast<std::size_t>(s.atom[q]);
      for (int k = 0; k < 3; ++k) {
        o[9 * q + k] = a.x[3 * i + k] + s.shift[3 * q + k];
        o[9 * q + 3 + k] = a.v[3 * i + k];
        o[9 * q + 6 + k] = a.omega[3 * i + k];
      }
    }
  }
  std::vector<double> in;
  all_to_all(out, in, from, true);
  for (std::size_t g = 0; g < a.nghost; ++g) {
    const std::size_t i = a.n + g;
    for (int k = 0; k < 3; ++k) {
      a.x[3 * i + k] = in[9 * g + k];
      a.v[3 * i + k] = in[9 * g + 3 + k];
      a.omega[3 * i + k] = in[9 * g + 6 + k];
    }
  }
}

}  // namespace sable
