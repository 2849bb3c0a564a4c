// fix ID group insert/stream seed S distributiontemplate D
//     nparticles N|INF | mass M|INF   particlerate R | massrate MR
//     insertion_face MESH   extrude_length L | insert_every K [duration D]
//     [start STEP] [maxattempt M] [overlapcheck yes|no] [all_in no] [verbose yes|no]
//     [vel constant|uniform|gaussian ...] [omega constant wx wy wz]
//     [random_distribute exact|uncorrelated] [ntry_mc N] [parallel yes|no]
// LIGGGHTS 3.8 semantics. The insertion volume is the planar face MESH (a fix
// mesh/surface that does not move) extruded upstream, against the insertion
// velocity v, by L. The face normal n is taken from its first triangle and
// turned so that n.v > 0; v_n = (v.n) n. With extrude_length, K = int(L / (|v_n| dt));
// with insert_every K, L = D |v_n| dt (D = K unless `duration`); L >= 3 r_max.
// The counts: FixInsertRated (fixes/fix_insert.h). Each grain's centre lies
// at a uniformly random point of the face (area-weighted), moved upstream by
// r + u L (overlapcheck yes) or r + u (L - 2r) (no), u uniform in [0, 1);
// positions within r of a box face are drawn again. A grain starts with v_n
// and no spin and, until it reaches the face, moves with v_n whatever acts on
// it: at each end of step its position is reset to x0 + v_n (step - step0) dt,
// its force and torque zeroed. At its release step, step0 + int(d / (|v_n| dt))
// (d: its centre's distance upstream of the face at insertion), it takes v
// (vel uniform/gaussian: drawn then) and `omega`. The first insert/stream fix
// moves every such grain of its group (LIGGGHTS). Per grain: x0, step0, release
// step, v_n (a per-atom column, kept in restart files). A reset_timestep moves
// those steps with the counter, so grains in flight fly on. (LIGGGHTS 3.8
// differs there: it also sets x0 to the grain's current position and the
// velocity to v_n as known then, which is 0 before the first run after a
// read_restart: such grains hang still until their release step; after a run
// they jump ahead by the flight already made. Its tutorial
// insert_stream_reset_timestep shows the first.) Not supported:
// all_in yes (LIGGGHTS needs a mesh/surface/planar face), multisphere
// templates, 2D.
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "core/geometry/mesh.h"
#include "core/engine/simulation.h"
#include "core/input/style_registry.h"
#include "fixes/fix_insert.h"
#include "fixes/fix_particletemplate_multisphere.h"

namespace sable {
namespace {

constexpr double kTiny = 1e-14;  // LIGGGHTS: round-off guard in step counts

// Per-atom release record: x0 (3), insertion step, release step, v_n (3).
constexpr int kStride = 8;
const char* const kColumn = "release_fix_insert_stream";  // LIGGGHTS' name; one for all such fixes

double dot_v(const Vec3d& a, const Vec3d& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

class FixInsertStream : public FixInsertRated {
 public:
  FixInsertStream(Simulation& s, const Args& a) : FixInsertRated(s, a) {
    once_allowed_ = false;
    hooks |= END_OF_STEP;
    parse(a);
    col_ = s.atoms.add_column(kColumn, kStride);
    face_geometry();
  }

  void init() override {
    if (dynamic_cast<MeshHolder*>(sim.find_fix(face_id_)) != face_)
      args.fail_line("fix '" + face_id_ + "' (the insertion face) was removed or redefined");
    if (!face_->mesh().motions.empty())
      args.fail_line("the insertion face '" + face_id_ + "' moves (move/mesh): LIGGGHTS forbids a moving insertion face");
    mover_ = nullptr;  // the first insert/stream fix moves the grains in flight
    for (auto& f : sim.fixes)
      if (auto* s = dynamic_cast<FixInsertStream*>(f.get()); s && !mover_) mover_ = s;
    FixInsertRated::init();  // schedule() first, then a reset_timestep's shift_steps()
    flight_end_ = 0;
    const auto& c = sim.atoms.column(col_);
    for (std::size_t i = 0; i < sim.atoms.n; ++i)
      if (in_record(i)) flight_end_ = std::max(flight_end_, static_cast<long>(c[kStride * i + 4]));
  }

  void end_of_step() override;

 private:
  std::string face_id_;
  MeshHolder* face_ = nullptr;
  double extrude_ = 0;
  long duration_ = 0;
  bool extrude_given_ = false;
  int col_ = -1;
  Vec3d n_{0, 0, 0}, vn_{0, 0, 0}, pref_{0, 0, 0};  // face normal (along v), normal velocity, a face point
  double speed_n_ = 0;                            // |v_n|
  std::vector<Vec3d> corners_;                    // world-frame triangles, 3 corners each
  std::vector<double> cum_area_;                  // cumulative triangle areas
  FixInsertStream* mover_ = nullptr;
  long flight_end_ = 0;  // the last release step of any grain (nothing to do after it)

  bool uses_region() const override { return false; }
  bool keeps_off_faces_always() const override { return true; }

  bool own_keyword(const Args& a, std::size_t& i) override {
    const std::string& k = a[i];
    if (rate_keyword(a, i)) return true;
    if (k == "insertion_face") {
      face_id_ = a.word(i + 1, "the ID of a fix mesh/surface");
      face_ = dynamic_cast<MeshHolder*>(sim.find_fix(face_id_));
      if (!face_) a.fail(i + 1, "the ID of a fix mesh/surface defined earlier");
    } else if (k == "extrude_length") {
      extrude_ = a.num(i + 1, "the extrusion length");
      if (!(extrude_ > 0)) a.fail(i + 1, "an extrusion length > 0");
      extrude_given_ = true;
    } else if (k == "duration") {
      duration_ = a.integer(i + 1, "the duration of each insertion in steps");
      if (duration_ < 1) a.fail(i + 1, "a duration >= 1 step");
    } else if (k == "parallel") {
      a.yes_no(i + 1, "yes or no");  // one process: nothing to pre-compute
    } else {
      return false;
    }
    i += 2;
    return true;
  }

  void check_own(const Args& a) override {
    check_rate(a);
    if (!face_) a.fail(a.size(), "'insertion_face MESH' (a fix mesh/surface to extrude)");
    if (!extrude_given_ && !every_given_) a.fail(a.size(), "'extrude_length L' or 'insert_every K'");
    if (extrude_given_ && every_given_)
      a.fail(last(a, "insert_every"), "either 'extrude_length' or 'insert_every', not both");
    if (duration_ > 0 && extrude_given_) a.fail(last(a, "duration"), "no 'duration' with 'extrude_length' (LIGGGHTS)");
    if (duration_ > insert_every_ && every_given_)
      a.fail(last(a, "duration") + 1,
             "a 'duration' of at most 'insert_every' (" + std::to_string(insert_every_) + " steps)");
    if (all_in_)
      a.fail(last(a, "all_in") + 1, "'no' (all_in yes needs a fix mesh/surface/planar face, which sable lacks)");
    if (sim.domain.dimension != 3) a.fail(0, "a 3D box (insert/stream inserts in 3D only, as LIGGGHTS)");
    for (auto* t : dist_->templates)
      if (dynamic_cast<FixParticletemplateMultisphere*>(t))
        a.fail(a.size(), "sphere templates only (insert/stream with multisphere templates is not supported)");
  }

  // The position of the last keyword k in the command (for errors that point at it).
  static std::size_t last(const Args& a, const std::string& k) {
    for (std::size_t i = a.size(); i-- > 6;)
      if (a[i] == k) return i;
    return a.size();
  }

  std::string keyword_list() const override {
    return "distributiontemplate, nparticles, mass, particlerate, massrate, insertion_face, extrude_length, "
           "insert_every, duration, start, maxattempt, overlapcheck, all_in, random_distribute, verbose, vel, "
           "omega, ntry_mc, parallel";
  }

  void face_geometry();
  void schedule() override;
  void random_position(double r, double* x) override;
  void start_motion(double* v, double* w) override {
    for (int k = 0; k < 3; ++k) v[k] = vn_[k], w[k] = 0.0;
  }
  void inserted(std::size_t first) override;
  void shift_steps(long delta) override;
  // Atom i carries a release record (was inserted by an insert/stream fix): v_n is never 0.
  bool in_record(std::size_t i) const {
    const double* c = &sim.atoms.column(col_)[kStride * i];
    return c[5] != 0 || c[6] != 0 || c[7] != 0;
  }
};

// The face in the world frame: planar, its normal turned along v, its triangles by area.
void FixInsertStream::face_geometry() {
  const TriMesh& m = face_->mesh();
  if (m.ntri() == 0) args.fail_line("the insertion face '" + face_id_ + "' has no triangles");
  corners_.clear();
  cum_area_.clear();
  double total = 0, size = 0;
  for (std::size_t t = 0; t < m.ntri(); ++t) {
    for (int k = 0; k < 3; ++k) corners_.push_back(m.to_world(m.corner(static_cast<int>(t), k)));
    const Vec3d* c = &corners_[3 * t];
    const Vec3d e1{c[1][0] - c[0][0], c[1][1] - c[0][1], c[1][2] - c[0][2]};
    const Vec3d e2{c[2][0] - c[0][0], c[2][1] - c[0][1], c[2][2] - c[0][2]};
    const Vec3d cr{e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
    total += 0.5 * std::sqrt(dot_v(cr, cr));
    cum_area_.push_back(total);
    size = std::max({size, std::sqrt(dot_v(e1, e1)), std::sqrt(dot_v(e2, e2))});
  }
  n_ = m.dir_to_world({m.normal[0], m.normal[1], m.normal[2]});
  pref_ = corners_[0];
  // Planar: every corner on the first triangle's plane (to 1e-6 of the face's size).
  for (const Vec3d& c : corners_) {
    const Vec3d d{c[0] - pref_[0], c[1] - pref_[1], c[2] - pref_[2]};
    if (std::fabs(dot_v(d, n_)) > 1e-6 * size)
      args.fail_line("the insertion face '" + face_id_ + "' is not planar (LIGGGHTS needs a planar face)");
  }
  const Vec3d v{v_[0], v_[1], v_[2]};
  if (std::sqrt(dot_v(v, v)) < 1e-5) args.fail_line("the insertion velocity (vel) is zero: insert/stream needs one");
  if (dot_v(v, n_) < 0)
    for (double& c : n_) c = -c;
  speed_n_ = dot_v(v, n_);
  if (speed_n_ < 1e-3)
    args.fail_line("the insertion velocity projected on the face normal is below 1e-3 (LIGGGHTS' bound): "
                   "vel must cross face '" + face_id_ + "'");
  for (int k = 0; k < 3; ++k) vn_[k] = speed_n_ * n_[k];
}

// K from L or L from K (dt may change between runs), then the box where positions lie.
void FixInsertStream::schedule() {
  const double rmax = dist_->max_radius, step_len = speed_n_ * sim.dt;
  if (extrude_given_) {
    if (extrude_ < 3 * rmax)
      args.fail_line("extrude_length " + std::to_string(extrude_) + " is below 3 times the largest grain radius (" +
                     std::to_string(3 * rmax) + ", LIGGGHTS' bound)");
    insert_every_ = static_cast<long>((extrude_ + kTiny) / step_len);
    if (insert_every_ == 0)
      args.fail_line("extrude_length " + std::to_string(extrude_) +
                     " is crossed in less than one step at the insertion velocity: lengthen it or lower vel");
  } else {
    const long d = duration_ > 0 ? duration_ : insert_every_;
    extrude_ = static_cast<double>(d) * step_len;
    if (extrude_ < 3 * rmax)
      args.fail_line("the extruded length (duration x |v_n| x dt = " + std::to_string(extrude_) +
                     ") is below 3 times the largest grain radius: raise insert_every/duration or vel");
  }
  // Face box and its extrusion, widened by r_max so the overlap check's grid holds every neighbour.
  bool outside = false;
  for (int k = 0; k < 3; ++k) {
    double lo = corners_[0][k], hi = lo;
    for (const Vec3d& c : corners_) lo = std::min(lo, c[k]), hi = std::max(hi, c[k]);
    const double shift = -n_[k] * (extrude_ + rmax);
    slo_[k] = std::min(lo, lo + shift) - rmax;
    shi_[k] = std::max(hi, hi + shift) + rmax;
    outside = outside || std::min(lo, lo + shift) < sim.domain.lo[k] || std::max(hi, hi + shift) > sim.domain.hi[k];
  }
  if (outside)
    sim.warn("fix insert/stream " + id + ": the extruded insertion face extends outside the box; "
             "grains are inserted only inside it");
}

void FixInsertStream::random_position(double r, double* x) {
  const double pick = pos_rng_.uniform() * cum_area_.back();
  const std::size_t t = std::min<std::size_t>(
      std::upper_bound(cum_area_.begin(), cum_area_.end(), pick) - cum_area_.begin(), cum_area_.size() - 1);
  // Uniform in the triangle: corners weighted 1 - sqrt(a), sqrt(a)(1 - b), sqrt(a) b.
  const double sa = std::sqrt(pos_rng_.uniform()), b = pos_rng_.uniform();
  const double w0 = 1 - sa, w1 = sa * (1 - b), w2 = sa * b;
  const double depth = overlap_ ? r + pos_rng_.uniform() * extrude_ : r + pos_rng_.uniform() * (extrude_ - 2 * r);
  const Vec3d* c = &corners_[3 * t];
  for (int k = 0; k < 3; ++k) x[k] = w0 * c[0][k] + w1 * c[1][k] + w2 * c[2][k] - depth * n_[k];
}

void FixInsertStream::inserted(std::size_t first) {
  Atoms& at = sim.atoms;
  auto& c = at.column(col_);
  for (std::size_t i = first; i < at.n; ++i) {
    const Vec3d x{at.x[3 * i], at.x[3 * i + 1], at.x[3 * i + 2]};
    const double d = dot_v({pref_[0] - x[0], pref_[1] - x[1], pref_[2] - x[2]}, n_);
    const long release = sim.step + static_cast<long>((d + kTiny) / (speed_n_ * sim.dt));
    double* rec = &c[kStride * i];
    for (int k = 0; k < 3; ++k) rec[k] = x[k], rec[5 + k] = vn_[k];
    rec[3] = static_cast<double>(sim.step);
    rec[4] = static_cast<double>(release);
    flight_end_ = std::max(flight_end_, release);
    if (mover_ && mover_ != this) mover_->flight_end_ = std::max(mover_->flight_end_, release);
  }
}

// One shared column: only the fix that moves the grains moves their steps.
void FixInsertStream::shift_steps(long delta) {
  if (mover_ != this) return;
  auto& c = sim.atoms.column(col_);
  for (std::size_t i = 0; i < sim.atoms.n; ++i)
    if (in_record(i)) c[kStride * i + 3] += delta, c[kStride * i + 4] += delta;
}

// Grains before their release step fly straight at v_n; at it they take v and omega.
void FixInsertStream::end_of_step() {
  if (mover_ != this || sim.step > flight_end_) return;
  Atoms& at = sim.atoms;
  const auto& c = at.column(col_);
  for (std::size_t i = 0; i < at.n; ++i) {
    if (!(at.mask[i] & groupbit) || !in_record(i)) continue;
    const double* rec = &c[kStride * i];
    const long release = std::lround(rec[4]);  // steps are stored as whole doubles
    if (sim.step > release) continue;
    const double t = static_cast<double>(sim.step - std::lround(rec[3])) * sim.dt;
    for (int k = 0; k < 3; ++k) {
      at.x[3 * i + k] = rec[k] + rec[5 + k] * t;
      at.v[3 * i + k] = rec[5 + k];
      at.omega[3 * i + k] = 0.0;
      at.f[3 * i + k] = 0.0;
      at.torque[3 * i + k] = 0.0;
    }
    if (sim.step == release) {
      draw_velocity(&at.v[3 * i]);
      for (int k = 0; k < 3; ++k) at.omega[3 * i + k] = w_[k];
    }
  }
}

}  // namespace

SABLE_FIX("insert/stream", FixInsertStream);

}  // namespace sable
