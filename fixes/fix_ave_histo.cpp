// fix ID group ave/histo Nevery Nrepeat Nfreq lo hi Nbin value1 value2 ... keyword args ...
//   value = x y z vx vy vz fx fy fz (per-atom, group members), c_ID, c_ID[I], f_ID, f_ID[I],
//           v_name (equal-style: global; atom-style: per-atom)
//   keywords: mode scalar|vector, ave one|running|window M, start S, beyond ignore|end|extra,
//             file F, overwrite, title1/title2/title3 STRING, hdf5 F (sable addition)
// LIGGGHTS 3.8 semantics and file format (fix_ave_histo.cpp). Inputs are all
// global, all per-atom or all local; per-atom and local ones need mode vector.
// c_ID is a global scalar/vector, a per-atom vector (c_ID[I]: column I) or a
// local array column (c_ID[I]). Nbin equal bins on [lo, hi]; a value on a bin
// boundary goes to the upper bin, hi to the last. Outputs f_ID[1..4] = total
// counts, missing counts, min, max. `hdf5 F` writes `step` and `time` (N; the
// time axis of core/io/h5_series.h), `stats` (N x 4), `counts` and `fraction`
// (N x nbins), constant `coord` (nbins).
#include <algorithm>
#include <cstdio>
#include <memory>

#include "core/engine/simulation.h"
#include "core/input/style_registry.h"
#include "core/io/thermo.h"
#include "core/input/variable.h"
#include "fixes/fix_ave_time.h"

namespace sable {
namespace {

constexpr double kBig = 1.0e20;  // LIGGGHTS' initial min/max

class FixAveHisto : public Fix {
 public:
  FixAveHisto(Simulation& s, const Args& a) : Fix(s, a) {
    hooks = END_OF_STEP;
    vector_size = 4;
    sched_.parse(a, 4);
    lo_ = a.num(7, "the lower bound lo");
    hi_ = a.num(8, "the upper bound hi");
    if (!(hi_ > lo_)) a.fail(8, "hi > lo");
    nbins_ = static_cast<int>(a.integer(9, "the number of bins"));
    if (nbins_ <= 0) a.fail(9, "a number of bins > 0");
    std::size_t i = 10;
    for (; i < a.size(); ++i) {
      Value v;
      v.word = a[i];
      v.at = i;
      static const char* attr[] = {"x", "y", "z", "vx", "vy", "vz", "fx", "fy", "fz"};
      const auto* hit = std::find(std::begin(attr), std::end(attr), a[i]);
      if (hit != std::end(attr)) {
        v.kind = 'a';
        v.index = static_cast<int>(hit - std::begin(attr));
      } else if (!parse_reference(a[i], v.kind, v.id, v.index)) {
        break;
      }
      values_.push_back(v);
    }
    if (values_.empty())
      a.fail(10, "at least one value: x, y, z, vx, vy, vz, fx, fy, fz, c_ID, c_ID[I], f_ID, f_ID[I], v_name");
    while (i < a.size()) {
      if (opt_.parse(a, i, sched_, "the first step to histogram from")) continue;
      if (a[i] == "beyond") {
        beyond_ = static_cast<Beyond>(a.choice(i + 1, {"ignore", "end", "extra"}));  // in the enum's order
        i += 2;
      } else {
        a.fail(i,
               "a value or an ave/histo keyword: mode, ave, start, beyond, file, overwrite, title1, title2, "
               "title3, hdf5");
      }
    }
    opt_.check(a);
    check_values();

    // Bins and their centre coordinates; 'extra' adds one bin below lo and one above hi.
    if (beyond_ == Extra) nbins_ += 2;
    binsize_ = (hi_ - lo_) / (beyond_ == Extra ? nbins_ - 2 : nbins_);
    bininv_ = 1.0 / binsize_;
    coord_.resize(nbins_);
    for (int b = 0; b < nbins_; ++b)
      coord_[b] = beyond_ == Extra ? lo_ + (b - 1 + 0.5) * binsize_ : lo_ + (b + 0.5) * binsize_;
    if (beyond_ == Extra) coord_.front() = lo_, coord_.back() = hi_;
    bin_.assign(nbins_, 0.0);
    bin_total_.assign(nbins_, 0.0);
    if (opt_.ave == Window) {
      bin_list_.assign(opt_.nwindow * nbins_, 0.0);
      stats_list_.assign(opt_.nwindow * 4, 0.0);
    }

    if (!opt_.file.empty()) {
      text_.open(opt_, a);
      text_.header(
          opt_.title_or(0, "# Histogrammed data for fix " + id) + "\n" +
          opt_.title_or(1, "# TimeStep Number-of-bins Total-counts Missing-counts Min-value Max-value") + "\n" +
          opt_.title_or(2, "# Bin Coord Count Count/Total") + "\n");
    }
    if (!opt_.h5file.empty()) {
      h5_ = ave::open_h5(opt_, values_, "values", *this);
      h5_->attribute("stats_columns", {"total", "missing", "min", "max"});
      h5_->constant("coord", coord_);
      h5_stats_ = h5_->series("stats", {4}, false);
      h5_counts_ = h5_->series("counts", {static_cast<std::size_t>(nbins_)}, false);
      h5_fraction_ = h5_->series("fraction", {static_cast<std::size_t>(nbins_)}, false);
      h5_->time_axis(sim.units);
      h5_->start();
    }
    sched_.begin(s.step);
  }

  void init() override {
    for (auto& v : values_) resolve(v);
    sched_.resume(sim.step);
  }
  void setup() override { end_of_step(); }

  void end_of_step() override {
    if (sim.step != sched_.nvalid) return;
    if (sched_.irepeat == 0) {
      stats_[0] = stats_[1] = 0.0;
      stats_[2] = kBig;
      stats_[3] = -kBig;
      std::fill(bin_.begin(), bin_.end(), 0.0);
    }
    for (auto& v : values_) bin_value(v);
    if (!sched_.sampled(sim.step)) return;
    if (opt_.ave == One) {
      std::copy(stats_, stats_ + 4, stats_total_);
      bin_total_ = bin_;
    } else if (opt_.ave == Running) {
      stats_total_[0] += stats_[0];
      stats_total_[1] += stats_[1];
      stats_total_[2] = std::min(stats_total_[2], stats_[2]);
      stats_total_[3] = std::max(stats_total_[3], stats_[3]);
      for (int b = 0; b < nbins_; ++b) bin_total_[b] += bin_[b];
    } else {
      double* st = &stats_list_[4 * iwindow_];
      for (int q = 0; q < 2; ++q) {
        stats_total_[q] += stats_[q];
        if (window_full_) stats_total_[q] -= st[q];
        st[q] = stats_[q];
      }
      st[2] = stats_[2];
      st[3] = stats_[3];
      const long m = window_full_ ? opt_.nwindow : iwindow_ + 1;
      stats_total_[2] = stats_list_[2];
      stats_total_[3] = stats_list_[3];
      for (long w = 1; w < m; ++w) {
        stats_total_[2] = std::min(stats_total_[2], stats_list_[4 * w + 2]);
        stats_total_[3] = std::max(stats_total_[3], stats_list_[4 * w + 3]);
      }
      double* bl = &bin_list_[iwindow_ * nbins_];
      for (int b = 0; b < nbins_; ++b) {
        bin_total_[b] += bin_[b];
        if (window_full_) bin_total_[b] -= bl[b];
        bl[b] = bin_[b];
      }
      if (++iwindow_ == opt_.nwindow) iwindow_ = 0, window_full_ = true;
    }
    write_outputs();
  }

  double compute_vector(int i) override {
    if (i < 1 || i > 4) args.fail_line("f_" + id + "[" + std::to_string(i) + "]: index out of range 1..4");
    return stats_total_[i - 1];
  }

 private:
  using Value = ave::Value;  // kinds a (atom attribute), c, f, v
  enum Kind { Global, PerAtom, Local };
  using enum ave::Ave;
  enum Beyond { Ignore, End, Extra };
  ave::Schedule sched_;
  std::vector<Value> values_;
  Kind kind_ = Global;
  ave::Options opt_;  // mode, ave, file, ... as given
  Beyond beyond_ = Ignore;
  long iwindow_ = 0;
  bool window_full_ = false;
  double lo_ = 0, hi_ = 0, binsize_ = 1, bininv_ = 1;
  int nbins_ = 0;
  double stats_[4] = {0, 0, kBig, -kBig}, stats_total_[4] = {0, 0, 0, 0};
  std::vector<double> coord_, bin_, bin_total_, bin_list_, stats_list_;
  std::vector<double> atom_values_;
  ave::TextFile text_;
  std::unique_ptr<ave::H5Series> h5_;
  int h5_stats_ = -1, h5_counts_ = -1, h5_fraction_ = -1;

  void resolve(Value& v) { v.resolve(sim, args, this, "histogram"); }

  // Every value of the same kind, and one the mode and the source can give.
  void check_values() {
    for (std::size_t q = 0; q < values_.size(); ++q) {
      Value& v = values_[q];
      resolve(v);
      Kind k = Global;
      if (v.kind == 'a')
        k = PerAtom;
      else if (v.kind == 'c')
        k = (v.c->scalar_flag || v.c->vector_size > 0) ? Global : v.c->peratom_flag ? PerAtom : Local;
      else if (v.kind == 'v')
        k = sim.variables->is_atom_style(v.id) ? PerAtom : Global;
      if (v.kind == 'c' && k == Local && !v.c->local_flag)
        args.fail(v.at, "a compute with global, per-atom or local values");
      if (q == 0)
        kind_ = k;
      else if (k != kind_)
        args.fail(v.at, "a value of the same kind as the first (all global, all per-atom or all local)");
      if (k != Global && !opt_.vector_mode)
        args.fail(v.at, std::string("a global value, or 'mode vector' for ") + (k == PerAtom ? "per-atom" : "local") +
                            " values");
      const std::string what = global_output_name(v.kind, v.id);
      if ((v.kind == 'c' || v.kind == 'f') && k == Global) {
        const bool scalar = v.g->scalar_flag != 0;
        const int size = v.g->vector_size;
        if (!opt_.vector_mode && v.index == 0 && !scalar) args.fail(v.at, "a global scalar (" + what + " has none)");
        if (!opt_.vector_mode && v.index > size)
          args.fail(v.at, "an index within 1.." + std::to_string(size) + " of " + what);
        if (opt_.vector_mode && v.index > 0) args.fail(v.at, "a global vector without [I] (no global arrays in sable)");
        if (opt_.vector_mode && size <= 0) args.fail(v.at, "a global vector (" + what + " has none)");
      }
      if (v.kind == 'c' && k == PerAtom) {
        const int cols = v.c->peratom_cols;
        if (v.index == 0 && cols)
          args.fail(v.at, what + "[I], a column of its per-atom array (1.." + std::to_string(cols) + ")");
        if (v.index > 0 && v.index > cols)
          args.fail(v.at, "a per-atom column within 1.." + std::to_string(cols) + " of " + what);
      }
      if (v.kind == 'c' && k == Local) {
        const int cols = v.c->local_cols;
        if (v.index == 0 && cols > 1)
          args.fail(v.at, what + "[I], a column of its local array (1.." + std::to_string(cols) + ")");
        if (v.index > cols) args.fail(v.at, "a local column within 1.." + std::to_string(cols) + " of " + what);
      }
    }
  }

  void bin_one(double x) {
    stats_[2] = std::min(stats_[2], x);
    stats_[3] = std::max(stats_[3], x);
    if (x < lo_ || x > hi_) {
      if (beyond_ == Ignore) {
        stats_[1] += 1.0;
        return;
      }
      bin_[x < lo_ ? 0 : nbins_ - 1] += 1.0;
    } else {
      int b = std::min(static_cast<int>((x - lo_) * bininv_), nbins_ - 1);
      if (beyond_ == Extra) ++b;
      bin_[b] += 1.0;
    }
    stats_[0] += 1.0;
  }

  // Per-atom values of group members: values[i * stride].
  void bin_atoms(const double* values, int stride) {
    const Atoms& at = sim.atoms;
    for (std::size_t i = 0; i < at.n; ++i)
      if (at.mask[i] & groupbit) bin_one(values[i * stride]);
  }

  void bin_value(const Value& v) {
    const Atoms& at = sim.atoms;
    if (v.kind == 'a') {
      const std::vector<double>& src = v.index < 3 ? at.x : v.index < 6 ? at.v : at.f;
      return bin_atoms(src.data() + v.index % 3, 3);
    }
    if (v.kind == 'v') {
      if (kind_ == PerAtom) {
        if (!sim.variables->atom_values(v.id, atom_values_)) args.fail(v.at, "an atom-style variable");
        return bin_atoms(atom_values_.data(), 1);
      }
      double x;
      if (!sim.variables->numeric(v.id, x)) args.fail(v.at, "an equal-style variable");
      return bin_one(x);
    }
    if (kind_ == Global) {
      if (opt_.vector_mode) {
        for (int i = 1; i <= v.g->vector_size; ++i) bin_one(v.g->global(i));
      } else {
        bin_one(v.g->global(v.index));
      }
    } else if (kind_ == PerAtom) {
      v.c->peratom_now();
      const int cols = std::max(1, v.c->peratom_cols);
      bin_atoms(v.c->peratom.data() + std::max(0, v.index - 1), cols);
    } else {
      v.c->local_now();
      const std::size_t rows = v.c->local_rows(), cols = v.c->local_cols;
      for (std::size_t r = 0; r < rows; ++r) bin_one(v.c->local[r * cols + std::max(0, v.index - 1)]);
    }
  }

  void write_outputs() {
    std::vector<double> frac(nbins_, 0.0);
    if (stats_total_[0] != 0.0)
      for (int b = 0; b < nbins_; ++b) frac[b] = bin_total_[b] / stats_total_[0];
    if (text_.is_open()) {
      char buf[160];
      std::snprintf(buf, sizeof buf, "%ld %d %g %g %g %g\n", sim.step, nbins_, stats_total_[0], stats_total_[1],
                    stats_total_[2], stats_total_[3]);
      std::string s = buf;
      for (int b = 0; b < nbins_; ++b) {
        // LIGGGHTS prints zero counts when the histogram is empty
        std::snprintf(buf, sizeof buf, "%d %g %g %g\n", b + 1, coord_[b], stats_total_[0] != 0.0 ? bin_total_[b] : 0.0,
                      frac[b]);
        s += buf;
      }
      text_.block(s);
    }
    if (h5_) {
      h5_->append(h5_stats_, stats_total_);
      h5_->append(h5_counts_, bin_total_.data());
      h5_->append(h5_fraction_, frac.data());
      h5_->end_record(sim.step, sim.time, sim.dt);  // last: the record is complete
    }
  }
};

}  // namespace

SABLE_FIX("ave/histo", FixAveHisto);

}  // namespace sable
