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
//     samples (samples in the window), time (its end, attributes units and
//     timestep), step (its last step);
//   constants: x, y, z (node coordinates along each axis), points ([nodes 3],
//     every node's x y z, z fastest), shape (nx ny nz), bounds (xlo xhi ylo
//     yhi zlo zhi), width, support;
//   attributes: fields, stress_components, kernel, normalised (per volume, or
//     per area in 2D: the units), frame, nodes, compute, fix, units, timestep.
// Beside F.h5, F.xdmf (XDMF 2) lets ParaView open the windows as a time series
// (its "XDMF Reader"): a temporal collection with one grid per window on disk,
// rewritten (atomically) whenever a block of windows reaches F.h5, so that it
// is valid after a kill. The grid is a 3DSMesh whose XYZ geometry is `points`:
// the arrays are [nx][ny][nz] (z fastest) and XDMF's regular meshes
// (3DCoRectMesh, 3DRectMesh) take the fastest index as x, which would swap x
// and z. Each field is a HyperSlab of its dataset (one window): rho and phi
// Scalar, u Vector, the stresses Matrix (6 components, xx yy zz xy xz yz;
// not Tensor6, whose order is xx xy xz yy yz zz).
// f_ID[i]: the last window's mean, laid out as the compute's vector.
#include <filesystem>
#include <memory>
#include <sstream>

#include "computes/compute_stress_cg.h"
#include "core/io/h5_series.h"
#include "core/io/text_file.h"
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
  // The windows' steps and times (the sidecar's), declared before h5_: its
  // destructor may still write a block and call back.
  std::vector<long> steps_;
  std::vector<double> times_;
  std::string xdmf_path_, h5_name_;
  std::unique_ptr<H5Series> h5_;
  int series_[6] = {}, samples_ = -1;

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
    std::vector<double> points;
    for (int i = 0; i < n[0]; ++i)
      for (int j = 0; j < n[1]; ++j)
        for (int k = 0; k < n[2]; ++k) points.insert(points.end(), {g.coord(0, i), g.coord(1, j), g.coord(2, k)});
    h5_->constant("points", points, {g.nodes(), 3});
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
    h5_->time_axis(sim.units);
    h5_->start();
    const std::filesystem::path p(path);
    h5_name_ = p.filename().string();
    xdmf_path_ = (p.extension() == ".h5" || p.extension() == ".hdf5" ? std::filesystem::path(p).replace_extension()
                                                                       : p).string() + ".xdmf";
    h5_->on_written = [this](std::size_t windows) { write_file_atomic(xdmf_path_, xdmf(windows), "fix " + id); };
  }

  // The sidecar: one grid per window in the file (the first `windows` rows).
  std::string xdmf(std::size_t windows) const {
    const int* n = cg_->field().shape();
    const std::string dims = std::to_string(n[0]) + " " + std::to_string(n[1]) + " " + std::to_string(n[2]);
    const std::string h5 = xml_escape(h5_name_);
    auto hdf = [&](const std::string& indent, const std::string& d, const std::string& name) {
      return indent + "<DataItem Dimensions=\"" + d + "\" NumberType=\"Float\" Precision=\"8\" Format=\"HDF\">" + h5 +
             ":/" + name + "</DataItem>\n";
    };
    std::ostringstream x;
    x.precision(17);
    x << "<?xml version=\"1.0\"?>\n<Xdmf Version=\"2.0\">\n <Domain>\n"
      << "  <Grid Name=\"" << xml_escape(id) << "\" GridType=\"Collection\" CollectionType=\"Temporal\">\n";
    for (std::size_t w = 0; w < windows; ++w) {
      x << "   <Grid Name=\"step " << steps_[w] << "\" GridType=\"Uniform\">\n    <Time Value=\"" << times_[w]
        << "\"/>\n    <Topology TopologyType=\"3DSMesh\" Dimensions=\"" << dims << "\"/>\n"
        << "    <Geometry GeometryType=\"XYZ\">\n"
        << hdf("     ", std::to_string(cg_->field().nodes()) + " 3", "points") << "    </Geometry>\n";
      for (const auto& grp : CgField::kGroups) {
        const bool vec = grp.count > 1;
        const std::string c = vec ? " " + std::to_string(grp.count) : "";
        x << "    <Attribute Name=\"" << grp.name << "\" AttributeType=\""
          << (grp.count == 1 ? "Scalar" : grp.count == 3 ? "Vector" : "Matrix") << "\" Center=\"Node\">\n"
          << "     <DataItem ItemType=\"HyperSlab\" Type=\"HyperSlab\" Dimensions=\"" << dims << c << "\">\n"
          << "      <DataItem Dimensions=\"3 " << (vec ? 5 : 4) << "\" Format=\"XML\">" << w << " 0 0 0" << (vec ? " 0" : "")
          << "  1 1 1 1" << (vec ? " 1" : "") << "  1 " << dims << c << "</DataItem>\n"
          << hdf("      ", std::to_string(windows) + " " + dims + c, grp.name) << "     </DataItem>\n    </Attribute>\n";
      }
      x << "   </Grid>\n";
    }
    x << "  </Grid>\n </Domain>\n</Xdmf>\n";
    return x.str();
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
    steps_.push_back(sim.step);
    times_.push_back(sim.time);
    h5_->end_record(sim.step, sim.time, sim.dt);  // last: the window is complete
    std::fill(sum_.begin(), sum_.end(), 0.0);
    count_ = 0;
  }
};

}  // namespace

SABLE_FIX("ave/cg", FixAveCG);

}  // namespace sable
