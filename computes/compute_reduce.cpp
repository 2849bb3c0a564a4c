// compute ID group reduce [update_on_run_end yes|no] mode input ... [replace v1 v2 ...]
// compute ID group reduce/region regionID mode input ...
// Reduces per-atom inputs (the dump custom attributes: x, vx, fx, radius, mass,
// omegax, ..., c_ID / c_ID[N] of per-atom computes, v_name of atom-style
// variables) over the group, or local inputs (c_ID[N] of per-contact computes)
// over all rows, with sum, min, max or ave. One input: a global scalar; several:
// a global vector, one value per input (LIGGGHTS semantics, incl. its 1e20
// for min/max of nothing and 0 for ave of nothing).
#include "core/io/dump_columns.h"
#include "core/input/style_registry.h"

namespace sable {

class ComputeReduce : public Compute {
 public:
  // in_region: reduce/region (a region ID before the mode).
  ComputeReduce(Simulation& s, const Args& a, bool in_region = false) : Compute(s, a) {
    std::size_t i = 4;
    while (i < a.size() && a[i] == "update_on_run_end") {
      a.yes_no(i + 1, "yes or no");  // lazy evaluation makes it moot
      i += 2;
    }
    if (in_region) {
      region_ = a.word(i, "a region ID");
      if (!s.find_region(region_)) a.fail(i, "an existing region ID");
      ++i;
    }
    const std::string& m = a.word(i, "a reduce mode: sum, min, max or ave");
    if (m == "sum") mode_ = SUM;
    else if (m == "min") mode_ = MIN;
    else if (m == "max") mode_ = MAX;
    else if (m == "ave") mode_ = AVE;
    else a.fail(i, "a reduce mode: sum, min, max or ave");
    for (++i; i < a.size() && a[i] != "replace"; ++i) inputs_.push_back(parse_input(a, i));
    if (inputs_.empty()) a.fail(i, std::string("at least one input: ") + atom_column_words());
    replace_.assign(inputs_.size(), -1);
    for (; i < a.size(); i += 3) {
      if (a[i] != "replace") a.fail(i, "'replace vec1 vec2' or nothing after the inputs");
      if (mode_ != MIN && mode_ != MAX) a.fail(i, "no 'replace' (it needs mode min or max)");
      if (s.comm.size() > 1) a.fail(i, "no 'replace' on several MPI ranks (not done yet): run it on one rank");
      const long n = static_cast<long>(inputs_.size());
      const long v1 = a.integer(i + 1, "an input index"), v2 = a.integer(i + 2, "an input index");
      if (v1 < 1 || v1 > n) a.fail(i + 1, "an input index in 1.." + std::to_string(n));
      if (v2 < 1 || v2 > n || v2 == v1) a.fail(i + 2, "an input index in 1.." + std::to_string(n) + " other than vec1");
      if (inputs_[v1 - 1].local != inputs_[v2 - 1].local)
        a.fail(i + 2, "an input of the same kind as vec1 (both per-atom or both local)");
      replace_[v1 - 1] = static_cast<int>(v2 - 1);
    }
    for (int r : replace_)  // a replaced value cannot be the index source of another (LAMMPS rule)
      if (r >= 0 && replace_[r] >= 0) a.fail_line("replace: input " + std::to_string(r + 1) + " is itself replaced");
    if (inputs_.size() == 1) scalar_flag = true;
    else vector_size = static_cast<int>(inputs_.size());
  }

  void init() override {
    invoked_step = -1;  // atoms may have changed since a run ended on this same step
    cache_step_ = -1;
  }
  double compute_scalar() override {
    if (!scalar_flag)
      fail("compute " + id + " reduces " + std::to_string(vector_size) + " inputs: use c_" + id + "[1.." +
           std::to_string(vector_size) + "], not c_" + id);
    evaluate();
    return values_[0];
  }
  double compute_vector(int i) override {
    evaluate();
    return values_[i - 1];
  }

 private:
  enum Mode { SUM, MIN, MAX, AVE };
  struct Input {
    bool local = false;
    AtomColumn col;     // per-atom input
    std::string ref;    // local input: compute ID
    int lcol = 0;       // local input: 0-based column
    std::string word;
  };

  Input parse_input(const Args& a, std::size_t i) {
    Input in;
    in.word = a[i];
    char kind;
    int index;
    if (parse_reference(a[i], kind, in.ref, index) && kind == 'c') {
      const Compute* c = sim.find_compute(in.ref);
      if (c && c->local_flag && !c->peratom_flag) {
        if (index == 0 && c->local_cols > 1)
          a.fail(i, "c_" + in.ref + "[N] (compute " + in.ref + " gives " + std::to_string(c->local_cols) + " columns)");
        if (c->local_cols > 0 && index > c->local_cols)
          a.fail(i, "a column of compute " + in.ref + " in 1.." + std::to_string(c->local_cols));
        in.local = true;
        in.lcol = std::max(index, 1) - 1;
        return in;
      }
    }
    in.col = parse_atom_column(sim, a, i);
    return in;
  }

  void evaluate() {
    // Thermo asks c_ID[1], c_ID[2], ... in one step; delete_atoms or an insertion
    // between runs changes the atoms without changing the step.
    // Several ranks: whether to evaluate must be every rank's same answer (each sums its part).
    if (sim.comm.distributed ? cache_step_ == sim.step && cache_builds_ == sim.neighbor.builds
                             : cache_step_ == sim.step && cache_atoms_ == sim.atoms.n && cache_max_id_ == sim.atoms.max_id)
      return;
    const Atoms& at = sim.atoms;
    const Region* reg = region_.empty() ? nullptr : sim.find_region(region_);
    if (!region_.empty() && !reg) fail("compute " + id + ": region '" + region_ + "' no longer exists");
    std::vector<std::size_t> sel;
    for (std::size_t i = 0; i < at.n; ++i)
      if ((at.mask[i] & groupbit) && (!reg || reg->match(&at.x[3 * i]))) sel.push_back(i);

    const std::size_t n = inputs_.size();
    std::vector<std::vector<double>> vec(n);
    std::vector<std::size_t> best(n, 0);  // row of the min/max, for replace
    values_.assign(n, 0.0);
    for (std::size_t q = 0; q < n; ++q) {
      const Input& in = inputs_[q];
      std::vector<double>& v = vec[q];
      if (in.local) {
        Compute* c = sim.find_compute(in.ref);
        if (!c || !c->local_flag) fail("compute " + id + ": '" + in.word + "': compute no longer exists or is not local");
        c->local_now();
        if (in.lcol >= std::max(1, c->local_cols))
          fail("compute " + id + ": '" + in.word + "': compute " + in.ref + " has only " +
               std::to_string(c->local_cols) + " columns");
        const std::size_t rows = c->local_rows(), nc = c->local_cols;
        v.resize(rows);
        for (std::size_t r = 0; r < rows; ++r) v[r] = c->local[r * nc + in.lcol];
      } else {
        gather_atom_column(sim, in.col, sel, v);
      }
      double r = mode_ == MIN ? 1.0e20 : mode_ == MAX ? -1.0e20 : 0.0;
      for (std::size_t j = 0; j < v.size(); ++j) {
        if (mode_ == SUM || mode_ == AVE) r += v[j];
        else if (mode_ == MIN ? v[j] < r : v[j] > r) {
          r = v[j];
          best[q] = j;
        }
      }
      if (sim.comm.distributed) {  // every rank's part
        const double count = sim.comm.total(static_cast<double>(v.size()));
        r = mode_ == MIN ? sim.comm.lowest(r) : mode_ == MAX ? sim.comm.highest(r) : sim.comm.total(r);
        if (mode_ == AVE && count > 0) r /= count;
      } else if (mode_ == AVE && !v.empty()) {
        r /= static_cast<double>(v.size());
      }
      values_[q] = r;
    }
    for (std::size_t q = 0; q < n; ++q) {
      const int src = replace_[q];
      if (src < 0 || vec[src].empty()) continue;
      if (vec[q].size() != vec[src].size())
        fail("compute " + id + ": replace: inputs " + std::to_string(q + 1) + " and " + std::to_string(src + 1) +
             " have different lengths");
      values_[q] = vec[q][best[src]];
    }
    cache_step_ = sim.step;
    cache_builds_ = sim.neighbor.builds;
    cache_atoms_ = sim.atoms.n;
    cache_max_id_ = sim.atoms.max_id;
  }

  Mode mode_ = SUM;
  std::string region_;
  std::vector<Input> inputs_;
  std::vector<int> replace_;  // per input: index of the input whose min/max row it reports, or -1
  std::vector<double> values_;
  long cache_step_ = -1;
  std::size_t cache_atoms_ = 0;
  decltype(sim.atoms.max_id) cache_max_id_ = 0;
  long cache_builds_ = -1;
};

SABLE_COMPUTE("reduce", ComputeReduce);
// The region variant: the same class, told by its registration, not by its name.
struct ComputeReduceRegion : ComputeReduce {
  ComputeReduceRegion(Simulation& s, const Args& a) : ComputeReduce(s, a, true) {}
};
SABLE_COMPUTE("reduce/region", ComputeReduceRegion);

}  // namespace sable
