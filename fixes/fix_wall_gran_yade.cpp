// fix wall/gran in sable --export-yade (core/io/yade_script.h): a primitive plane
// becomes a YADE wall (a thin box in a periodic cell), a mesh wall the facets of
// its fix mesh/surface; the script gives each the Hertz or linear law of the
// pair style. What YADE has no counterpart for is refused at the fix's line.
#include "fixes/fix_wall_gran.h"
#include "fixes/fix_wall_gran_mesh.h"
#include "core/io/yade_script.h"

namespace sable {
namespace {

// The wall's model must be the pair style's (one law in the script); returns
// the index (in a, the words after `fix`) of `primitive` or `mesh`.
std::size_t wall_keyword(const Args& a, const YadeScript& s) {
  if (a.word(4, "a model") != s.model) a.fail(4, "the pair style's model (" + s.model + ")");
  std::size_t k = 5;
  while (k < a.size() && a[k] != "primitive" && a[k] != "mesh") k += 2;
  return k;
}

}  // namespace

// fix ID group wall/gran model M tangential history primitive type T xplane|yplane|zplane POS
void FixWallGran::export_yade(YadeScript& s) const {
  const Args a = args.tail(1);
  const std::size_t k = wall_keyword(a, s);
  if (k + 4 >= a.size() || a[k + 1] != "type") a.fail(k, "primitive type T xplane|yplane|zplane POS");
  if (shape_ != Shape::Plane) a.fail(k + 3, "xplane, yplane or zplane (export-yade)");
  if (k + 5 < a.size()) a.fail(k + 5, "nothing after the plane position (export-yade)");
  s.add_wall(*this, type_, axis_, pos0_);
}

// fix ID all wall/gran model hertz tangential history mesh n_meshes K meshes ID...
void FixWallGranMesh::export_yade(YadeScript& s) const {
  const Args a = args.tail(1);
  const std::size_t k = wall_keyword(a, s);
  if (k >= a.size() || a[k] != "mesh") a.fail(k, "primitive type T xplane|yplane|zplane POS");
  if (a[1] != "all") a.fail(1, "all (export-yade: a mesh wall acting on a group is not translated)");
  if (s.model != "hertz") a.fail(4, "hertz (export-yade translates mesh walls with the Hertz law only)");
  if (a.word(k + 1, "n_meshes") != "n_meshes") a.fail(k + 1, "n_meshes");
  const long n = a.integer(k + 2, "the number of meshes");
  if (a.word(k + 3, "meshes") != "meshes") a.fail(k + 3, "meshes");
  for (long m = 0; m < n; ++m) {
    const std::string& id = a.word(k + 4 + m, "a mesh/surface fix ID");
    if (!s.mesh(id)) a.fail(k + 4 + m, "the ID of a fix mesh/surface defined before");
    if (s.wall_uses_mesh(id)) a.fail(k + 4 + m, "a mesh no other wall/gran uses (export-yade)");
    s.wall_mesh(id);
  }
  for (std::size_t i = k + 4 + n; i < a.size(); i += 2)  // YADE's Mindlin law always clips the normal force
    if (a[i] != "limitForce" && a[i] != "store_force" && a[i] != "store_force_contact")
      a.fail(i, "limitForce, store_force or nothing after the mesh IDs (export-yade)");
}

}  // namespace sable
