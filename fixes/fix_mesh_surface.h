#pragma once
// fix ID group mesh/surface file F type T [scale s] [move dx dy dz]
//     [rotate axis ax ay az angle deg] [curvature c] [precision p] [heal no]
//     [verbose yes|no] [surface_vel vx vy vz] [reference_point x y z] [stress on|off]
//     [wear finnie|off]
// fix ID group mesh/surface/stress ...  (the same; LIGGGHTS' stress module)
// A triangle mesh of material type T read from an ASCII or binary STL file
// (a relative name: from the working directory, else next to the deck).
// scale, move and rotate apply at load in the order given (LIGGGHTS 3.8).
// curvature (degrees, default 0.256235 as LIGGGHTS): triangles whose normals
// differ by no more share one surface (inactive edge: history moves across it,
// no edge contact). surface_vel: a conveyor belt (each triangle's surface
// moves in its plane along the projection of v, at |v|; not with move/mesh,
// as LIGGGHTS). The group is ignored (as LIGGGHTS), except that only its
// grains load the mesh (f_ID, LIGGGHTS' stress module).
// Outputs: f_ID[1..3] total force of the grains on the mesh, f_ID[4..6]
// their torque about the reference point (which moves with the mesh),
// f_ID[7..9] the reference point. sable gives them for mesh/surface too.
// wear finnie (LIGGGHTS' stress module; needs property/global k_finnie
// peratomtypepair): per triangle, the eroded mass per area of Finnie's model as
// LIGGGHTS 3.8 sums it (fix wall/gran mesh), for dump mesh/vtk and mesh/gran/VTK.
#include "core/engine/fix.h"
#include "core/geometry/mesh.h"

namespace sable {

class FixMeshSurface : public Fix, public MeshHolder {
 public:
  FixMeshSurface(Simulation& sim, const Args& args);
  void export_yade(YadeScript& s) const override;  // the triangles as YADE facets
  double compute_vector(int i) override;
  TriMesh& mesh() override { return mesh_; }
  int wall_type() const override { return type_; }
  void update_pose() override;
  // Restart: the pose (a restarted deck's move/mesh fixes continue from it).
  bool write_state(std::string& out) const override;
  void read_state(const std::string& in) override;

 private:
  TriMesh mesh_;
  int type_ = 1;
};

}  // namespace sable
