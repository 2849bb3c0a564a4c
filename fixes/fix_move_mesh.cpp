// fix ID group move/mesh mesh MESHID linear vx vy vz
// fix ID group move/mesh mesh MESHID rotate origin x y z axis ax ay az period T
// Rigid motion of a fix mesh/surface (LIGGGHTS 3.8): translation at constant
// velocity, or rotation about a fixed axis through `origin` (right-handed,
// omega = 2 pi / T). Motion starts when the fix is defined; the mesh is where
// it should be at each step's force evaluation and its surface velocity is
// the wall velocity of the contacts. Several move/mesh on one mesh superpose:
// each advances the pose by its own step increment, in definition order, and
// the velocities add. unfix stops the motion (the mesh stays where it got
// to). The group is ignored.
#include <cmath>
#include <memory>
#include <numbers>

#include "core/engine/simulation.h"
#include "core/input/style_registry.h"
#include "fixes/fix_mesh_surface.h"
#include "core/io/yade_script.h"

namespace sable {

class FixMoveMesh : public Fix {
 public:
  FixMoveMesh(Simulation& s, const Args& a) : Fix(s, a) {
    if (a.word(4, "'mesh' and the ID of a fix mesh/surface") != "mesh") a.fail(4, "'mesh'");
    auto* m = dynamic_cast<FixMeshSurface*>(s.find_fix(a.word(5, "the ID of a fix mesh/surface")));
    if (!m) a.fail(5, "the ID of a fix mesh/surface defined before this fix");
    const Vec3d& belt = m->mesh().belt;
    if (belt[0] != 0 || belt[1] != 0 || belt[2] != 0)
      a.fail(5, "a mesh without surface_vel (a moving conveyor mesh is not supported, as in LIGGGHTS)");
    mesh_id_ = a[5];
    TriMesh::Motion mo;
    const std::string& k = a.word(6, "'linear' or 'rotate'");
    auto vec = [&](std::size_t at, const std::string& what) {
      return Vec3d{a.num(at, what + " x"), a.num(at + 1, what + " y"), a.num(at + 2, what + " z")};
    };
    if (k == "linear") {
      mo.v = vec(7, "the velocity");
      if (a.size() > 10) a.fail(10, "the end of the line");
    } else if (k == "rotate") {
      if (a.word(7, "'origin'") != "origin") a.fail(7, "'origin'");
      mo.origin = vec(8, "the origin");
      if (a.word(11, "'axis'") != "axis") a.fail(11, "'axis'");
      const Vec3d ax = vec(12, "the axis");
      const double n = std::sqrt(ax[0] * ax[0] + ax[1] * ax[1] + ax[2] * ax[2]);
      if (!(n > 0)) a.fail(12, "a non-zero axis");
      mo.axis = {ax[0] / n, ax[1] / n, ax[2] / n};
      if (a.word(15, "'period'") != "period") a.fail(15, "'period'");
      const double T = a.num(16, "the period");
      if (T == 0) a.fail(16, "a non-zero period");
      mo.rotate = true;
      mo.omega = 2 * std::numbers::pi / T;
      if (a.size() > 17) a.fail(17, "the end of the line");
    } else {
      a.fail(6, "'linear' or 'rotate' (other LIGGGHTS movements are not available)");
    }
    TriMesh& mesh = m->mesh();
    mesh.advance_to(s.step, s.dt);  // earlier motions up to now; this one starts here
    mo.owned = true;
    mo.owner = token_;
    mesh.motions.push_back(mo);
    speed_ = mo.rotate ? std::fabs(mo.omega) * reach(mesh, mo) : std::sqrt(mo.v[0] * mo.v[0] + mo.v[1] * mo.v[1] + mo.v[2] * mo.v[2]);
  }
  double max_speed() const override { return speed_; }
  void export_yade(YadeScript& s) const override;
  // The pose catches up at each run's end, so an unfix between runs keeps all the motion made.
  void post_run() override {
    if (auto* m = dynamic_cast<FixMeshSurface*>(sim.find_fix(mesh_id_))) m->update_pose();
  }

 private:
  std::string mesh_id_;
  double speed_ = 0;
  std::shared_ptr<const void> token_ = std::make_shared<int>(0);  // the mesh's motion lives as long as this fix
  // Largest distance of a mesh vertex from the rotation axis (now).
  static double reach(const TriMesh& m, const TriMesh::Motion& mo) {
    double r2 = 0;
    for (std::size_t i = 0; i < m.vert.size(); i += 3) {
      const Vec3d p = m.to_world({m.vert[i], m.vert[i + 1], m.vert[i + 2]});
      const double d[3] = {p[0] - mo.origin[0], p[1] - mo.origin[1], p[2] - mo.origin[2]};
      const double along = d[0] * mo.axis[0] + d[1] * mo.axis[1] + d[2] * mo.axis[2];
      r2 = std::max(r2, d[0] * d[0] + d[1] * d[1] + d[2] * d[2] - along * along);
    }
    return std::sqrt(r2);
  }
};

// fix move/mesh linear | rotate: a YADE TranslationEngine or RotationEngine on
// the mesh's facets (IDS stands for them until the script's mesh index is known).
void FixMoveMesh::export_yade(YadeScript& s) const {
  const Args a = args.tail(1);  // ID group move/mesh mesh MESHID linear|rotate ...
  const std::string& id = a.word(4, "a mesh ID");
  YadeScript::MeshWall* m = s.mesh(id);
  if (!m) a.fail(4, "the ID of a fix mesh/surface");
  if (!m->motion.empty())
    s.refuse(a, "one move/mesh per mesh (YADE's kinematic engines set the facets' velocity, they do not add)");
  auto vec = [&](std::size_t i) {
    double v[3] = {a.num(i, "x"), a.num(i + 1, "y"), a.num(i + 2, "z")};
    return v[0] * v[0] + v[1] * v[1] + v[2] * v[2];
  };
  if (a.word(5, "linear or rotate") == "linear") {
    const double speed = std::sqrt(vec(6));
    if (speed == 0) return;
    m->motion = "TranslationEngine(ids=IDS, translationAxis=Vector3(" + yade_num(a.num(6, "vx") / speed) + ", " +
                yade_num(a.num(7, "vy") / speed) + ", " + yade_num(a.num(8, "vz") / speed) +
                "), velocity=" + yade_num(speed) + ")";
    for (int k = 0; k < 3; ++k) m->shift[k] = a.num(6 + k, "v") * sim.dt;
  } else if (a[5] == "rotate") {
    const double axis = std::sqrt(vec(11));
    // LIGGGHTS: right-handed about the axis, omega = 2 pi / period; YADE's RotationEngine turns the same way.
    m->motion = "RotationEngine(ids=IDS, rotationAxis=Vector3(" + yade_num(a.num(11, "ax") / axis) + ", " +
                yade_num(a.num(12, "ay") / axis) + ", " + yade_num(a.num(13, "az") / axis) +
                "), angularVelocity=" + yade_num(2 * std::numbers::pi / a.num(15, "a period")) +
                ", rotateAroundZero=True, zeroPoint=Vector3(" + yade_num(a.num(7, "ox")) + ", " +
                yade_num(a.num(8, "oy")) + ", " + yade_num(a.num(9, "oz")) + "))";
    for (int k = 0; k < 3; ++k) {
      m->origin[k] = a.num(7 + k, "origin");
      m->axis[k] = a.num(11 + k, "axis") / axis;
    }
    m->angle = 2 * std::numbers::pi / a.num(15, "a period") * sim.dt;
  } else {
    a.fail(5, "linear or rotate (export-yade)");
  }
}

SABLE_FIX("move/mesh", FixMoveMesh);

}  // namespace sable
