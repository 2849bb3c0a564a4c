// fix ID group ave/cg Nevery Nfreq c_ID file F.h5                 (sable addition)
// Time average of a compute stress/cg: every Nevery steps the compute's
// fields are added to a running sum; on every multiple of Nfreq (a multiple
// of Nevery) the mean over the samples of that window (steps that are
// multiples of Nevery in (t - Nfreq, t]; fewer when a run starts inside a
// window) is appended to F.h5 and the sum restarts. The group is not used
// (the compute's group picks the grains).
// HDF5 layout (core/io/h5_series.h: SWMR, a killed run leaves every complete
// window readable; `step` is written last, its length counts the windows):
//   growing, one row per window: rho, phi [nx ny nz]; u [nx ny nz 3];
//     stress, stress_contact, stress_kinetic [nx ny nz 6] (xx yy zz xy xz yz);
//     samples (samples in the window), step (its last step);
//   constants: x, y, z (node coordinates along each axis), shape (nx ny nz),
//     bounds (xlo xhi ylo yhi zlo zhi), width, support;
//   attributes: fields, stress_components, kernel, normalised (per volume, or
//     per area in 2D: the units), frame, nodes, compute, fix.
// f_ID[i]: the last window's mean, laid out as the compute's vector.
#include <memory>

#include "computes/compute_stress_cg.h"
#include "core/io/h5_series.h"
#include "core/engine/simulation.h"
#include "core/input/style_registry.h"

namespace sable {

namespace {

class FixAveCG : public Fix {
 public:
  FixAveCG(Simulation& s, const Args& a) : Fix(s, a) {
    hooks = END_OF_STEP;
    nevery = static_cast<int>(a.integer(4, "Nevery (steps between samples)"));
    if (nevery <= 0) a.fail(4, "Nevery > 0");
    nfreq_ = a.integer(5, "Nfreq (steps between averages)");
    if (nfreq_ <= 0 || nfreq_ % nevery) a.fail(5, "Nfreq > 0, a multiple of Nevery (" + std::to_string(nevery) + ")");
    const std::string& c = a.word(6, "c_ID of a compute stress/cg");
    if (c.rfind("c_", 0) != 0 || c.size() < 3) a.fail(6, "c_ID of a compute stress/cg");
    cid_ = c.substr(2);
    resolve();
    if (a.word(7, "file F.h5") != "file") a.fail(7, "file F.h5");
    const std::string& path = a.word(8, "an HDF5 file name");
    if (a.size() > 9) a.fail(9, "the end of the line (fix ID group ave/cg Nevery Nfreq c_ID file F.h5)");
    size_ = cg_->field().nodes() * CgField::kFields;
    vector_size = static_cast<int>(size_);
    sum_.assign(size_, 0.0);
    open(path);
  }

  void init() override {
    resolve();
    if (cg_->field().nodes() * CgField::kFields != size_)
      args.fail(6, "the same grid as when the fix was defined (compute " + cid_ + " was redefined)");
  }

  void end_of_step() override {
    const std::vector<double>& f = cg_->fields();
    for (std::size_t k = 0; k < size_; ++k) sum_[k] += f[k];
    ++count_;
    if (sim.step % nfreq_ == 0) write();
  }

  double compute_vector(int i) override {
    if (i < 1 || i > vector_size)
      args.fail_line("f_" + id + "[" + std::to_string(i) + "]: index out of range 1.." + std::to_string(vector_size));
    return mean_.empty() ? 0.0 : mean_[static_cast<std::size_t>(i - 1)];
  }

 private:
  std::string cid_;
  ComputeStressCG* cg_ = nullptr;
  long nfreq_ = 1, count_ = 0;
  std::size_t size_ = 0;
  std::vector<double> sum_, mean_;
  std::unique_ptr<H5Series> h5_;
  int series_[6] = {}, samples_ = -1, step_ = -1;

  void resolve() {
    Compute* c = sim.find_compute(cid_);
    if (!c) args.fail(6, "c_ID of a compute stress/cg ('" + cid_ + "' is not defined)");
    cg_ = dynamic_cast<ComputeStressCG*>(c);
    if (!cg_) args.fail(6, "c_ID of a compute stress/cg (" + cid_ + " is a compute " + c->style + ")");
  }

  void open(const std::string& path) {
    const CgField& g = cg_->field();
    h5_ = std::make_unique<H5Series>(path);
    std::vector<std::string> names;
    for (const auto& grp : CgField::kGroups) names.push_back(grp.name);
    h5_->attribute("fields", names);
    h5_->attribute("stress_components", {"xx", "yy", "zz", "xy", "xz", "yz"});
    h5_->attribute("kernel", {g.kernel().name()});
    h5_->attribute("normalised", {g.kernel().dimension() == 2
                                      ? "per area (dimension 2): rho kg/m^2, phi area fraction, stresses N/m"
                                      : "per volume: rho kg/m^3, phi volume fraction, stresses Pa"});
    h5_->attribute("frame", {cg_->frame()});
    h5_->attribute("nodes", {"cell centres lo + (i + 1/2) (hi - lo) / n; arrays [nx][ny][nz]"});
    h5_->attribute("compute", {cg_->args.joined()});
    h5_->attribute("fix", {args.joined()});
    const int* n = g.shape();
    for (int k = 0; k < 3; ++k) {
      std::vector<double> c(n[k]);
      for (int i = 0; i < n[k]; ++i) c[i] = g.coord(k, i);
      h5_->constant(std::string(1, "xyz"[k]), c);
    }
    h5_->constant("shape", {double(n[0]), double(n[1]), double(n[2])});
    h5_->constant("bounds", {cg_->lo()[0], cg_->hi()[0], cg_->lo()[1], cg_->hi()[1], cg_->lo()[2], cg_->hi()[2]});
    h5_->constant("width", {g.kernel().w()});
    h5_->constant("support", {g.kernel().support()});
    for (int s = 0; s < 6; ++s) {
      std::vector<std::size_t> shape{std::size_t(n[0]), std::size_t(n[1]), std::size_t(n[2])};
      if (CgField::kGroups[s].count > 1) shape.push_back(CgField::kGroups[s].count);
      series_[s] = h5_->series(CgField::kGroups[s].name, shape, false);
    }
    samples_ = h5_->series("samples", {}, false);
    step_ = h5_->series("step", {}, true);
    h5_->start();
  }

  void write() {
    const std::size_t nodes = cg_->field().nodes();
    mean_.resize(size_);
    for (std::size_t k = 0; k < size_; ++k) mean_[k] = sum_[k] / static_cast<double>(count_);
    std::vector<double> row;
    for (int s = 0; s < 6; ++s) {
      const auto& grp = CgField::kGroups[s];
      row.resize(nodes * grp.count);
      for (std::size_t p = 0; p < nodes; ++p)
        for (int c = 0; c < grp.count; ++c) row[p * grp.count + c] = mean_[p * CgField::kFields + grp.first + c];
      h5_->append(series_[s], row.data());
    }
    const double samples = static_cast<double>(count_);
    h5_->append(samples_, &samples);
    h5_->append(step_, static_cast<std::int64_t>(sim.step));  // last: the window is complete
    std::fill(sum_.begin(), sum_.end(), 0.0);
    count_ = 0;
  }
};

}  // namespace

SABLE_FIX("ave/cg", FixAveCG);

}  // namespace sable
