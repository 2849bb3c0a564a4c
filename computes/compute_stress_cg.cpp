// compute stress/cg: see computes/compute_stress_cg.h.
#include "computes/compute_stress_cg.h"

#include <cmath>
#include <numbers>

#include "core/engine/contact_source.h"
#include "core/engine/simulation.h"
#include "core/input/style_registry.h"
#include "fixes/fix_mesh_surface.h"

namespace sable {

ComputeStressCG::ComputeStressCG(Simulation& s, const Args& a) : Compute(s, a) {
  parse(a);
  vector_size = static_cast<int>(field_->nodes()) * CgField::kFields;
  init();
}

void ComputeStressCG::parse(const Args& a) {
  CgKernel::Kind kind = CgKernel::Kind::Lucy;
  double w = 1;
  bool have_kernel = false, have_grid = false;
  int n[3] = {1, 1, 1};
  static const char* axis[3] = {"x", "y", "z"};
  for (std::size_t i = 4; i < a.size();) {
    if (a[i] == "kernel") {
      kind = a.choice(i + 1, {"lucy", "gauss"}) == 0 ? CgKernel::Kind::Lucy : CgKernel::Kind::Gauss;
      w = a.num(i + 2, "the kernel width W");
      if (!(w > 0)) a.fail(i + 2, "a kernel width W > 0");
      have_kernel = true;
      i += 3;
    } else if (a[i] == "grid") {
      for (int d = 0; d < 3; ++d) {
        const std::size_t at = i + 1 + 3 * d;
        const std::string ax = axis[d];
        lo_[d] = a.num(at, "the grid's " + ax + "lo");
        hi_[d] = a.num(at + 1, "the grid's " + ax + "hi");
        if (!(hi_[d] > lo_[d])) a.fail(at + 1, "the grid's " + ax + "hi > " + ax + "lo");
        const long m = a.integer(at + 2, "the number of nodes along " + ax);
        if (m < 1 || m > 100000) a.fail(at + 2, "a number of nodes along " + ax + " between 1 and 100000");
        n[d] = static_cast<int>(m);
      }
      have_grid = true;
      i += 10;
    } else if (a[i] == "frame") {
      if (a.word(i + 1, "mesh") != "mesh") a.fail(i + 1, "mesh (frame mesh MESHFIXID)");
      frame_id_ = a.word(i + 2, "the ID of a fix mesh/surface");
      frame_at_ = i + 2;
      i += 3;
    } else {
      a.fail(i, "a stress/cg keyword: kernel, grid or frame");
    }
  }
  if (!have_kernel) a.fail(a.size(), "'kernel lucy|gauss W'");
  if (!have_grid) a.fail(a.size(), "'grid xlo xhi nx ylo yhi ny zlo zhi nz'");
  const double nodes = static_cast<double>(n[0]) * n[1] * n[2];
  if (nodes * CgField::kFields > 2e8) a.fail_line("the grid has too many nodes (" + std::to_string(nodes) + ")");
  field_ = std::make_unique<CgField>(CgKernel(kind, w, sim.domain.dimension), lo_, hi_, n);
}

void ComputeStressCG::init() {
  invoked_step = -1;  // atoms may have changed between runs at the same step
  const CgField& g = *field_;
  if (g.kernel().dimension() != sim.domain.dimension) {  // a 2D box made after this compute
    const CgKernel k(g.kernel().kind(), g.kernel().w(), sim.domain.dimension);
    field_ = std::make_unique<CgField>(k, lo_, hi_, g.shape());
  }
  frame_ = nullptr;
  if (frame_id_.empty()) return;
  Fix* f = sim.find_fix(frame_id_);
  if (!f) args.fail(frame_at_, "the ID of a fix mesh/surface ('" + frame_id_ + "' is not defined)");
  frame_ = dynamic_cast<FixMeshSurface*>(f);
  if (!frame_) args.fail(frame_at_, "the ID of a fix mesh/surface or mesh/surface/stress (" + frame_id_ + " is a fix " + f->style + ")");
}

double ComputeStressCG::compute_vector(int i) { return fields()[static_cast<std::size_t>(i - 1)]; }

const std::vector<double>& ComputeStressCG::fields() {
  if (invoked_step != sim.step || out_.empty()) {
    init();  // the mesh fix may have been removed since
    evaluate();
    invoked_step = sim.step;
  }
  return out_;
}

void ComputeStressCG::to_grid(const double xw[3], double out[3]) const {
  if (!frame_) {
    for (int k = 0; k < 3; ++k) out[k] = xw[k];
    return;
  }
  const Vec3d b = frame_->mesh().to_body({xw[0], xw[1], xw[2]});
  for (int k = 0; k < 3; ++k) out[k] = b[k];
}

void ComputeStressCG::dir_to_grid(const double vw[3], double out[3]) const {
  if (!frame_) {
    for (int k = 0; k < 3; ++k) out[k] = vw[k];
    return;
  }
  const double* R = frame_->mesh().R;  // row-major, x_world = R x_body + T: R^T v
  for (int k = 0; k < 3; ++k) out[k] = R[k] * vw[0] + R[3 + k] * vw[1] + R[6 + k] * vw[2];
}

void ComputeStressCG::reach_box() {
  const CgField& g = *field_;
  const double R = g.kernel().support();
  double lo[3], hi[3];
  for (int k = 0; k < 3; ++k) {
    lo[k] = g.coord(k, 0) - R;
    hi[k] = g.coord(k, g.shape()[k] - 1) + R;
    reach_lo_[k] = frame_ ? INFINITY : lo[k];
    reach_hi_[k] = frame_ ? -INFINITY : hi[k];
  }
  if (frame_)
    for (int c = 0; c < 8; ++c) {  // the world box around the moved grid's corners
      const Vec3d p = frame_->mesh().to_world({c & 1 ? hi[0] : lo[0], c & 2 ? hi[1] : lo[1], c & 4 ? hi[2] : lo[2]});
      for (int k = 0; k < 3; ++k) {
        reach_lo_[k] = std::min(reach_lo_[k], p[k]);
        reach_hi_[k] = std::max(reach_hi_[k], p[k]);
      }
    }
  if (g.kernel().dimension() == 2) {  // a 2D kernel does not look at z
    reach_lo_[2] = -INFINITY;
    reach_hi_[2] = INFINITY;
  }
}

template <class Put>
void ComputeStressCG::images(const double a[3], const double b[3], Put&& put) const {
  const Domain& dom = sim.domain;
  long m0[3], m1[3];
  for (int k = 0; k < 3; ++k) {
    if (!dom.wraps(k)) {
      if (b[k] < reach_lo_[k] || a[k] > reach_hi_[k]) return;
      m0[k] = m1[k] = 0;
      continue;
    }
    const double L = dom.length(k);
    m0[k] = static_cast<long>(std::ceil((reach_lo_[k] - b[k]) / L));
    m1[k] = static_cast<long>(std::floor((reach_hi_[k] - a[k]) / L));
    if (m1[k] < m0[k]) return;
  }
  for (long i = m0[0]; i <= m1[0]; ++i)
    for (long j = m0[1]; j <= m1[1]; ++j)
      for (long k = m0[2]; k <= m1[2]; ++k) {
        const double s[3] = {i * dom.length(0), j * dom.length(1), k * dom.length(2)};
        put(s);
      }
}

void ComputeStressCG::evaluate() {
  if (frame_) frame_->update_pose();
  reach_box();
  CgField& g = *field_;
  g.clear();
  const bool plane = g.kernel().dimension() == 2;
  const Atoms& at = sim.atoms;
  for (std::size_t i = 0; i < at.n; ++i) {
    if (!(at.mask[i] & groupbit)) continue;
    const double* x = &at.x[3 * i];
    const double r = at.radius[i];
    // 2D: the grain's area in the plane, pi r^2, for disks and for spheres (their equator) alike.
    const double vol = plane ? std::numbers::pi * r * r : 4.0 / 3.0 * std::numbers::pi * r * r * r;
    double v[3];
    dir_to_grid(&at.v[3 * i], v);
    images(x, x, [&](const double s[3]) {
      const double xs[3] = {x[0] + s[0], x[1] + s[1], x[2] + s[2]};
      double xg[3];
      to_grid(xs, xg);
      g.add_grain(xg, v, at.rmass[i], vol);
    });
  }
  // A contact of grain i: branch b (world), force f on i.
  auto contact = [&](std::size_t i, const double b[3], const double f[3]) {
    const double* x = &at.x[3 * i];
    double lo[3], hi[3], bg[3], fg[3];
    for (int k = 0; k < 3; ++k) {
      lo[k] = std::min(x[k], x[k] - b[k]);
      hi[k] = std::max(x[k], x[k] - b[k]);
    }
    dir_to_grid(b, bg);
    dir_to_grid(f, fg);
    images(lo, hi, [&](const double s[3]) {
      const double xs[3] = {x[0] + s[0], x[1] + s[1], x[2] + s[2]};
      double xg[3];
      to_grid(xs, xg);
      g.add_contact(xg, bg, fg);
    });
  };
  ContactRecords rec;
  // Pair branches x_i - x_j = en (r_i + r_j - delta): the image partner's centre without its shift code;
  // wall branches from the contact point to the centre: en (r_i - delta).
  for (ContactSource* s : contact_sources(sim)) {
    const bool pair = s->contact_kind() == ContactSource::Kind::Pairs;
    s->records(groupbit, rec);
    for (const ContactRecord& c : rec.rows) {
      const double len = at.radius[c.i] + (pair ? at.radius[c.j] : 0.0) - c.delta;
      const double b[3] = {c.en[0] * len, c.en[1] * len, c.en[2] * len};
      contact(c.i, b, c.f);
    }
  }
  g.finish(out_);  // in frame mode b, f and v were turned into body axes: R^T s R already
}

SABLE_COMPUTE("stress/cg", ComputeStressCG);

}  // namespace sable
