#include "fixes/fix_mesh_surface.h"

#include <filesystem>
#include <stdexcept>

#include "core/io/restart.h"
#include "core/engine/simulation.h"
#include "core/input/style_registry.h"
#include "core/io/yade_script.h"

namespace sable {

// A relative STL name is looked up from the working directory (LIGGGHTS),
// then from the deck's folder.
static std::string find_stl(const std::string& name, const Args& a) {
  namespace fs = std::filesystem;
  if (fs::path(name).is_absolute() || fs::exists(name)) return name;
  const fs::path beside = fs::path(a.where().file).parent_path() / name;
  return fs::exists(beside) ? beside.string() : name;
}

FixMeshSurface::FixMeshSurface(Simulation& s, const Args& a) : Fix(s, a) {
  vector_size = 9;
  if (a.word(4, "'file' and an STL file name") != "file") a.fail(4, "'file' (the mesh comes from an STL file)");
  const std::string path = find_stl(a.word(5, "an STL file name"), a);
  try {
    mesh_ = TriMesh::read_stl(path);
  } catch (const std::exception& e) {
    a.fail(5, std::string("a readable STL file: ") + e.what());
  }
  double curvature = 0.256235, precision = 1e-8;  // LIGGGHTS 3.8 defaults (fix mesh/surface doc)
  Vec3d ref{0, 0, 0};
  bool have_type = false, wear = false;
  for (std::size_t i = 6; i < a.size();) {
    const std::string& k = a[i];
    auto vec = [&](std::size_t at, const std::string& what) {
      return Vec3d{a.num(at, what + " x"), a.num(at + 1, what + " y"), a.num(at + 2, what + " z")};
    };
    if (k == "type") {
      const long t = a.integer(i + 1, "the mesh's material (atom) type");
      if (t < 1 || t > s.atoms.ntypes) a.fail(i + 1, "a type between 1 and " + std::to_string(s.atoms.ntypes));
      type_ = static_cast<int>(t);
      have_type = true;
      i += 2;
    } else if (k == "scale") {
      const double f = a.num(i + 1, "the scale factor");
      if (!(f > 0)) a.fail(i + 1, "a scale factor > 0");
      mesh_.scale(f);
      i += 2;
    } else if (k == "move") {
      mesh_.translate(vec(i + 1, "the move"));
      i += 4;
    } else if (k == "rotate") {
      if (a.word(i + 1, "'axis'") != "axis") a.fail(i + 1, "'axis'");
      const Vec3d ax = vec(i + 2, "the rotation axis");
      if (ax[0] == 0 && ax[1] == 0 && ax[2] == 0) a.fail(i + 2, "a non-zero axis");
      if (a.word(i + 5, "'angle'") != "angle") a.fail(i + 5, "'angle'");
      mesh_.rotate(ax, a.num(i + 6, "the angle in degrees"));
      i += 7;
    } else if (k == "curvature") {
      curvature = a.num(i + 1, "the curvature angle in degrees");
      if (!(curvature >= 0 && curvature < 90)) a.fail(i + 1, "an angle in degrees, 0 <= c < 90");
      i += 2;
    } else if (k == "precision") {
      precision = a.num(i + 1, "the welding precision (length)");
      if (!(precision >= 0)) a.fail(i + 1, "a precision >= 0");
      i += 2;
    } else if (k == "surface_vel") {
      mesh_.belt = vec(i + 1, "the conveyor velocity");
      i += 4;
    } else if (k == "reference_point") {
      ref = vec(i + 1, "the reference point");
      i += 4;
    } else if (k == "stress") {
      a.yes_no(i + 1, "on or off");  // forces are always tracked
      i += 2;
    } else if (k == "wear") {
      wear = a.choice(i + 1, {"finnie", "off"}, " (the wear models of LIGGGHTS 3.8)") == 0;
      i += 2;
    } else if (k == "verbose") {
      a.yes_no(i + 1, "yes or no");
      i += 2;
    } else if (k == "heal") {
      if (a.word(i + 1, "'no'") != "no") a.fail(i + 1, "'no' (duplicate removal is not available)");
      i += 2;
    } else {
      a.fail(i, "a mesh/surface keyword: type, scale, move, rotate, curvature, precision, surface_vel, "
                "reference_point, stress, wear, verbose, heal");
    }
  }
  if (!have_type) a.fail(a.size(), "'type T' (the mesh's material type)");
  try {
    mesh_.build(curvature, precision);
  } catch (const std::exception& e) {
    a.fail_line(path + ": " + e.what());
  }
  mesh_.ref_body = ref;
  if (wear) mesh_.wear.assign(mesh_.ntri(), 0.0);
}

void FixMeshSurface::update_pose() { mesh_.advance_to(sim.step, sim.dt); }

bool FixMeshSurface::write_state(std::string& out) const {
  restart::Packer p;
  p.put(mesh_.R);
  p.put(mesh_.T);
  p.put<std::int64_t>(mesh_.pose_step);
  p.put_vector(mesh_.wear);
  out = p.bytes;
  return true;
}

void FixMeshSurface::read_state(const std::string& in) {
  restart::Unpacker u(in, "the restart state of fix " + id);
  const auto R = u.get<std::array<double, 9>>();
  std::copy(R.begin(), R.end(), mesh_.R);
  mesh_.T = u.get<Vec3d>();
  mesh_.pose_step = u.get<std::int64_t>();
  const std::vector<double> wear = u.get_vector<double>();
  if (wear.size() == mesh_.wear.size()) mesh_.wear = wear;  // wear off in the restarted deck: not kept
}

double FixMeshSurface::compute_vector(int i) {
  if (i < 1 || i > 9) args.fail_line("f_" + id + "[" + std::to_string(i) + "]: index out of range 1..9");
  if (i <= 3) return sim.comm.total(mesh_.force[i - 1]);  // several ranks: every rank's contacts
  if (i <= 6) return sim.comm.total(mesh_.torque[i - 4]);
  return mesh_.to_world(mesh_.ref_body)[i - 7];
}

// --export-yade: the triangles as sable loaded them (scale, move, rotate applied in
// the deck's order) become YADE facets (what ymport.stl makes) if a wall/gran uses them.
void FixMeshSurface::export_yade(YadeScript& s) const {
  if (mesh_.belt[0] != 0 || mesh_.belt[1] != 0 || mesh_.belt[2] != 0)
    s.refuse(args, "surface_vel (a conveyor mesh) is not translated to YADE");
  s.add_mesh(*this, mesh_, type_);
}

SABLE_FIX("mesh/surface", FixMeshSurface);
SABLE_FIX("mesh/surface/stress", FixMeshSurface);

}  // namespace sable
