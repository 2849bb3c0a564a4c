#include "fixes/fix_wall_gran.h"
#include "fixes/fix_wall_gran_mesh.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "contact_models/materials.h"
#include "contact_models/pair_gran.h"
#include "contact_models/registry.h"
#include "core/engine/simulation.h"
#include "core/io/restart.h"
#include "core/input/style_registry.h"
#include "core/engine/threads.h"

namespace sable {

static int axis_of(const std::string& w) { return w == "x" ? 0 : w == "y" ? 1 : w == "z" ? 2 : -1; }

FixWallGran::FixWallGran(Simulation& s, const Args& a) : Fix(s, a) {
  hooks = atom_tasks = POST_FORCE;
  vector_size = 3;
  const ModelSelection sel = parse_model_selection(a, 4);
  kernel_ = make_kernel(sel, a, s);
  ModelSettings settings;
  kernel_->settings(settings);
  bool have_wall = false;
  std::size_t i = sel.next;
  while (i < a.size()) {
    const std::string& k = a[i];
    if (k == "primitive") {
      if (a.word(i + 1, "'type' and the wall's material type") != "type") a.fail(i + 1, "'type'");
      const long t = a.integer(i + 2, "the wall's material (atom) type");
      if (t < 1 || t > s.atoms.ntypes)
        a.fail(i + 2, "a type between 1 and " + std::to_string(s.atoms.ntypes) + " (as defined by create_box)");
      type_ = static_cast<int>(t);
      const std::string& w = a.word(i + 3, "a primitive: xplane, yplane, zplane, xcylinder, ycylinder, zcylinder");
      if (w.size() == 6 && w.substr(1) == "plane" && axis_of(w.substr(0, 1)) >= 0) {
        shape_ = Shape::Plane;
        axis_ = axis_of(w.substr(0, 1));
        pos0_ = a.num(i + 4, "the plane position");
        if (axis_ == 2 && s.domain.dimension == 2)
          a.fail(i + 3, "xplane or yplane: grains of a 2D deck lie in one z plane, a zplane wall never meets them");
        i += 5;
      } else if (w.size() == 9 && w.substr(1) == "cylinder" && axis_of(w.substr(0, 1)) >= 0) {
        shape_ = Shape::Cylinder;
        axis_ = axis_of(w.substr(0, 1));
        radius_ = a.num(i + 4, "the cylinder radius");
        if (!(radius_ > 0)) a.fail(i + 4, "a radius > 0");
        c1_ = a.num(i + 5, "the first axis coordinate");
        c2_ = a.num(i + 6, "the second axis coordinate");
        if (axis_ != 2 && s.domain.dimension == 2)
          a.fail(i + 3, "zcylinder: in a 2D deck a cylinder must stand along z");
        i += 7;
      } else {
        a.fail(i + 3, "a primitive: xplane, yplane, zplane, xcylinder, ycylinder, zcylinder");
      }
      have_wall = true;
    } else if (k == "mesh") {
      a.fail(i, "'primitive' (mesh walls: FixWallGranMesh, chosen at registration below)");
    } else if (k == "shear") {
      if (!have_wall) a.fail(i, "'primitive ...' before 'shear' (as LIGGGHTS)");
      shear_dim_ = axis_of(a.word(i + 1, "x, y or z"));
      if (shear_dim_ < 0) a.fail(i + 1, "x, y or z");
      if (shape_ == Shape::Plane && shear_dim_ == axis_)
        a.fail(i + 1, "a direction in the plane (use 'wiggle' to move a plane along its normal)");
      vshear_ = a.num(i + 2, "the shear velocity");
      i += 3;
    } else if (k == "wiggle") {
      if (!have_wall) a.fail(i, "'primitive ...' before 'wiggle'");
      if (shape_ != Shape::Plane) a.fail(i, "a plane wall for 'wiggle'");
      if (a.word(i + 1, "'amplitude' A 'period' P") == "amplitude") {
        wiggle_amp_ = a.num(i + 2, "the wiggle amplitude");
        if (a.word(i + 3, "'period'") != "period") a.fail(i + 3, "'period'");
        wiggle_period_ = a.num(i + 4, "the wiggle period");
        i += 5;
      } else {  // LAMMPS form: wiggle dim A P, dim = the plane's normal
        if (axis_of(a[i + 1]) != axis_) a.fail(i + 1, "'amplitude' or the plane's normal axis");
        wiggle_amp_ = a.num(i + 2, "the wiggle amplitude");
        wiggle_period_ = a.num(i + 3, "the wiggle period");
        i += 4;
      }
      if (!(wiggle_period_ > 0)) a.fail(i - 1, "a period > 0");
      wiggle_step0_ = s.step;
    } else if (k == "store_force" || k == "store_force_contact") {
      if (a.yes_no(i + 1, "yes or no")) a.fail(i + 1, "'no' (use f_" + id + "[1..3] for the total wall force)");
      i += 2;
    } else if (!settings.try_parse(a, i)) {
      a.fail(i, "primitive, shear, wiggle, or a model keyword: " + settings.names());
    }
  }
  if (!have_wall) a.fail(a.size(), "'primitive type T xplane|yplane|zplane|xcylinder|... ARGS'");
  hist_size_ = static_cast<int>(kernel_->history_slots().size());
  hist_.configure(hist_size_);
}

void FixWallGran::init() {
  kernel_->connect(Materials::of(sim), args);
  freeze_bit_ = frozen_groupbits(sim);
  setup_pass_ = true;
}

double FixWallGran::max_speed() const {
  double v = std::fabs(vshear_);
  if (shape_ == Shape::Cylinder && shear_dim_ >= 0 && shear_dim_ != axis_) v *= radius_;  // spin: |w| R at the wall
  if (wiggle_period_ > 0) v += std::fabs(wiggle_amp_) * 2.0 * std::numbers::pi / wiggle_period_;
  return v;
}

void FixWallGran::Staged::clear() {
  atom.clear();
  place.clear();
  row.clear();
  hist.clear();
  force.clear();
  deltan.clear();
  en.clear();
  vwall.clear();
  point.clear();
}

FixWallGran::Now FixWallGran::now() const {
  Now w{pos0_, 0.0};
  if (wiggle_period_ > 0) {
    const double om = 2.0 * std::numbers::pi / wiggle_period_, t = (sim.step - wiggle_step0_) * sim.dt;
    w.pos += wiggle_amp_ * std::sin(om * t);
    w.vnormal = wiggle_amp_ * om * std::cos(om * t);
  }
  return w;
}

// Unit normal (wall -> grain), wall velocity at the grain and centre distance of
// grain i; false for a grain on a cylinder's axis (no defined normal).
bool FixWallGran::geometry(std::size_t i, const Now& w, double n[3], double vw[3], double& dist) const {
  const double* x = &sim.atoms.x[3 * i];
  n[0] = n[1] = n[2] = 0.0;
  vw[0] = vw[1] = vw[2] = 0.0;
  if (shape_ == Shape::Plane) {
    const double d = x[axis_] - w.pos;
    n[axis_] = d > 0 ? 1.0 : -1.0;  // grains on either side, pushed away from the plane
    dist = std::fabs(d);
    vw[axis_] = w.vnormal;
    if (shear_dim_ >= 0) vw[shear_dim_] = vshear_;
    return true;
  }
  const int a1 = (axis_ + 1) % 3, a2 = (axis_ + 2) % 3;  // cylinder cross-section axes (LIGGGHTS' Dim<>)
  const double d1 = x[a1] - c1_, d2 = x[a2] - c2_, rho = std::sqrt(d1 * d1 + d2 * d2);
  if (rho == 0.0) return false;
  const double sgn = rho > radius_ ? 1.0 : -1.0;  // outside: pushed outward; inside: towards the axis
  n[a1] = sgn * d1 / rho;
  n[a2] = sgn * d2 / rho;
  dist = std::fabs(rho - radius_);
  if (shear_dim_ >= 0 && shear_dim_ != axis_) {  // spin: (vshear e_axis) x r_radial, r_radial = (d1, d2)
    vw[a1] = -vshear_ * d2;
    vw[a2] = vshear_ * d1;
  } else if (shear_dim_ >= 0) {
    vw[shear_dim_] = vshear_;
  }
  return true;
}

void FixWallGran::collect(std::size_t c0, std::size_t c1, std::uint32_t also, const Now& w, Staged& out) const {
  const Atoms& at = sim.atoms;
  auto add = [&](std::size_t c, std::size_t i, const double n[3], const double vw[3], double dist, double overlap) {
    const double* x = &at.x[3 * i];
    out.atom.push_back(static_cast<int>(i));
    out.place.push_back(static_cast<int>(c));
    out.deltan.push_back(overlap);
    for (int k = 0; k < 3; ++k) {
      out.en.push_back(n[k]);
      out.vwall.push_back(vw[k]);
      out.point.push_back(x[k] - n[k] * dist);
    }
  };
  const std::uint32_t bits = groupbit;
  const double* x = at.x.data();
  const double* rad = at.radius.data();
  if (shape_ == Shape::Plane) {
    for (std::size_t c = c0; c < c1; ++c) {
      const int i = near_[c];
      at.prefetch_ahead(near_, c);
      const double overlap = rad[i] - std::fabs(x[3 * i + axis_] - w.pos);
      if (overlap <= 0.0) continue;
      if (!(at.mask[i] & bits) || !(at.mask[i] & also)) continue;
      double n[3], vw[3], dist = 0.0;
      geometry(i, w, n, vw, dist);
      add(c, i, n, vw, dist, at.radius[i] - dist);
    }
    return;
  }
  // Most grains are far from the cylinder: a test on squared distances (with
  // a margin far above round-off) skips the square root; geometry() decides.
  const int a1 = (axis_ + 1) % 3, a2 = (axis_ + 2) % 3;
  for (std::size_t c = c0; c < c1; ++c) {
    const int i = near_[c];
    at.prefetch_ahead(near_, c);
    const double d1 = x[3 * i + a1] - c1_, d2 = x[3 * i + a2] - c2_, rho2 = d1 * d1 + d2 * d2;
    const double in = radius_ - rad[i], out_r = radius_ + rad[i];
    if ((in > 0.0 && rho2 < in * in * (1.0 - 1e-9)) || rho2 > out_r * out_r * (1.0 + 1e-9)) continue;
    if (!(at.mask[i] & bits) || !(at.mask[i] & also)) continue;
    double n[3], vw[3], dist = 0.0;
    if (!geometry(i, w, n, vw, dist)) continue;
    const double overlap = at.radius[i] - dist;
    if (overlap > 0.0) add(c, i, n, vw, dist, overlap);
  }
}

// Between rebuilds no grain moves more than skin/2 (the rebuild rule) and a
// wiggling plane at most |A| from POS: a grain whose gap to the wall at POS
// was skin + |A| or more at the rebuild cannot touch it before the next one.
void FixWallGran::refresh_near() {
  const Atoms& at = sim.atoms;
  if (near_builds_ == sim.neighbor.builds && near_n_ == at.n) return;
  keep_places();  // by grain id: the indices are about to change meaning
  near_builds_ = sim.neighbor.builds;
  near_n_ = at.n;
  const double reach = sim.neighbor.skin + std::fabs(wiggle_amp_);
  const int a1 = (axis_ + 1) % 3, a2 = (axis_ + 2) % 3;
  at.select(
      [&](std::size_t i) {
        const double* x = &at.x[3 * i];
        double dist;
        if (shape_ == Shape::Plane) {
          dist = std::fabs(x[axis_] - pos0_);
        } else {
          const double d1 = x[a1] - c1_, d2 = x[a2] - c2_;
          dist = std::fabs(std::sqrt(d1 * d1 + d2 * d2) - radius_);
        }
        return dist - at.radius[i] < reach;
      },
      near_);
  load_places();
}

// hist_ becomes the last pass's contacts, by grain id, in key order.
void FixWallGran::keep_places() const {
  if (!store_behind_) return;
  store_behind_ = false;
  const std::size_t hs = static_cast<std::size_t>(hist_size_);
  std::vector<std::pair<long, int>> by_id;  // (id, place) of the last pass's contacts
  for (std::size_t p = 0; p < near_.size(); ++p)
    if (place_pass_[p] == last_pass_) by_id.emplace_back(near_id_[p], static_cast<int>(p));
  std::sort(by_id.begin(), by_id.end());
  HistoryStore::Order order(by_id.size());
  for (std::size_t q = 0; q < by_id.size(); ++q) order[q] = {0, static_cast<int>(q)};
  hist_.keep(
      order, [&](int, int q) { return HistoryStore::Key{by_id[q].first, HistoryStore::kWall, 0}; },
      [&](int, int q) { return place_hist_.data() + static_cast<std::size_t>(by_id[q].second) * hs; });
}

// Each near place takes its grain's row of hist_ (one sort, one walk), marked
// as the last pass's contact where there was one.
void FixWallGran::load_places() {
  const Atoms& at = sim.atoms;
  const std::size_t n = near_.size(), hs = static_cast<std::size_t>(hist_size_);
  near_id_.resize(n);
  for (std::size_t p = 0; p < n; ++p) near_id_[p] = at.id[near_[p]];
  place_pass_.assign(n, -1);
  place_hist_.assign(n * hs, 0.0);
  store_behind_ = false;
  if (hs == 0 || hist_.count() == 0) return;
  std::vector<std::pair<long, int>> by_id(n);
  for (std::size_t p = 0; p < n; ++p) by_id[p] = {near_id_[p], static_cast<int>(p)};
  std::sort(by_id.begin(), by_id.end());
  std::vector<HistoryStore::Key> keys(n);
  for (std::size_t q = 0; q < n; ++q) keys[q] = {by_id[q].first, HistoryStore::kWall, 0};
  std::vector<double> rows(n * hs);
  std::vector<char> found(n);
  hist_.look_up(keys.data(), n, rows.data(), found.data());
  for (std::size_t q = 0; q < n; ++q) {
    if (!found[q]) continue;
    const std::size_t p = static_cast<std::size_t>(by_id[q].second);
    place_pass_[p] = last_pass_;
    std::copy_n(rows.data() + q * hs, hs, place_hist_.data() + p * hs);
  }
}

void FixWallGran::ids_renumbered(const std::vector<long>& o, const std::vector<long>& n) {
  keep_places();
  hist_.renumber(o, n);
  near_builds_ = -1;  // reload the places at the next pass
}

void FixWallGran::pass_history(const Staged& st, WallBatch& b) {
  const std::size_t hs = static_cast<std::size_t>(hist_size_);
  for (const int p : st.place) {
    if (place_pass_[p] != last_pass_) std::fill_n(place_hist_.data() + static_cast<std::size_t>(p) * hs, hs, 0.0);
    place_pass_[p] = pass_no_;
  }
  b.hist = place_hist_.data();
  b.hist_index = st.place.data();
  b.hist_stride = hist_size_;
}

void FixWallGran::copy_history(Staged& st, WallBatch& b) const {
  const std::size_t n = st.atom.size(), hs = static_cast<std::size_t>(hist_size_);
  st.hist.assign(n * hs, 0.0);
  st.row.resize(n);
  for (std::size_t c = 0; c < n; ++c) {
    st.row[c] = static_cast<int>(c);
    const std::size_t p = static_cast<std::size_t>(st.place[c]);
    if (place_pass_[p] == last_pass_) std::copy_n(place_hist_.data() + p * hs, hs, st.hist.data() + c * hs);
  }
  b.hist = st.hist.data();
  b.hist_index = st.row.data();
  b.hist_stride = hist_size_;
}

WallBatch FixWallGran::batch(Staged& st) {
  Atoms& at = sim.atoms;
  WallBatch b;
  b.a = atom_view(at, at.n, freeze_bit_);
  b.n = st.atom.size();
  b.atom = st.atom.data();
  b.deltan = st.deltan.data();
  b.en = st.en.data();
  b.vwall = st.vwall.data();
  b.wall_type = type_;
  b.ctx.dt = sim.dt;
  return b;
}

// Each thread searches and evaluates the near grains of its own atoms (the
// ranges of the pair pass and the integrator): a grain's state, forces and
// wall history stay in the cache of the core that integrates it. (Blocks of
// the near list run on any thread made the integrator fetch every wall
// grain's lines from the other core at each step.)
void FixWallGran::begin(FixHook) {
  refresh_near();
  pass_now_ = now();
  pass_update_ = !setup_pass_;  // LIGGGHTS: no history update in the setup force pass
  setup_pass_ = false;
  pass_atoms_ = sim.atoms.n;
  pass_no_ = last_pass_ + 1;
  parts_.start([](Staged& p) { p.clear(); });
  sum_.begin(near_.size(), thread_settings().wall_block, parts_.size());
}

void FixWallGran::range(FixHook, const AtomRange& r) {
  const int t = r.thread;
  const auto c0 = std::lower_bound(near_.begin(), near_.end(), static_cast<int>(r.lo)) - near_.begin();
  const auto c1 = std::lower_bound(near_.begin(), near_.end(), static_cast<int>(r.hi)) - near_.begin();
  Staged& st = parts_[t];
  collect(static_cast<std::size_t>(c0), static_cast<std::size_t>(c1), ~0u, pass_now_, st);
  st.force.resize(3 * st.atom.size());
  WallBatch b = batch(st);
  if (hist_size_ > 0) pass_history(st, b);
  b.force = st.force.data();
  b.ctx.update = pass_update_;
  kernel_->wall_forces(b);
  // The total force: per block of ThreadSettings::wall_block near grains (core's BlockSum)
  sum_.range(t, static_cast<std::size_t>(c0));
  for (std::size_t c = 0; c < st.atom.size(); ++c) sum_.add(t, static_cast<std::size_t>(st.place[c]), &st.force[3 * c]);
}

// The history kept is this pass's contacts': a grain that left the wall starts afresh.
void FixWallGran::end(FixHook) {
  last_pass_ = pass_no_;
  store_behind_ = hist_size_ > 0;
  double total[3];
  sum_.finish(total);
  for (int d = 0; d < 3; ++d) force_[d] = 0.0 - total[d];  // (0.0 - x, not -x: no "-0" in thermo output)
}

bool FixWallGran::last_pass(const PassFn& fn) const {
  if (pass_atoms_ != sim.atoms.n) return false;  // sorted or deleted since: the indices no longer hold
  for (const Staged& p : parts_)
    for (std::size_t c = 0; c < p.atom.size(); ++c) fn(p.atom[c], &p.point[3 * c], &p.force[3 * c]);
  return true;
}

void FixWallGran::records(std::uint32_t bits, ContactRecords& out) {
  refresh_near();
  records_.clear();
  collect(0, near_.size(), bits, now(), records_);
  WallBatch b = batch(records_);
  if (hist_size_ > 0) copy_history(records_, b);
  b.ctx.update = false;
  kernel_->wall_records(b, out);
}

bool FixWallGran::write_state(std::string& out) const {
  restart::Packer p;
  keep_places();
  hist_.write(p);
  out = p.bytes;
  return true;
}

void FixWallGran::read_state(const std::string& in) {
  restart::Unpacker u(in, "the restart state of fix " + id);
  if (!hist_.read(u)) args.fail_line("the restart file's fix " + id + " has another model");
  store_behind_ = false;
  near_builds_ = -1;  // the places load it at the next pass
}

double FixWallGran::compute_vector(int i) {
  if (i < 1 || i > 3) args.fail_line("f_" + id + "[" + std::to_string(i) + "]: index out of range 1..3");
  return sim.comm.total(force_[i - 1]);
}

// `... mesh n_meshes K meshes ...` is the mesh wall (fixes/fix_wall_gran_mesh.cpp).
static const bool sable_registered_wall_gran = FixRegistry::add("wall/gran", [](Simulation& s, const Args& a) {
  const bool mesh = std::find(a.words().begin(), a.words().end(), "mesh") != a.words().end();
  return mesh ? std::unique_ptr<Fix>(std::make_unique<FixWallGranMesh>(s, a)) : std::make_unique<FixWallGran>(s, a);
});

}  // namespace sable
