// fix aveforce / setforce fx fy fz (numbers, NULL or v_name) in sable
// --export-yade, as LAMMPS: each step every grain's force becomes the group's
// mean plus the value (aveforce) or the value (setforce); f_ID[1..3] is the
// group's total force before. YADE's integrator adds gravity after the force
// pass, so the weight that sable's fix gravity put in before this fix (gravity
// defined earlier) is counted in by hand and taken back out of what is set.
#include "fixes/group_force.h"
#include "core/io/yade_script.h"

namespace sable {

void export_yade_set_forces(YadeScript& s, const Fix& f, bool ave) {
  const Args& a = f.args;  // fix ID group aveforce|setforce fx fy fz
  if (a.size() > 7) a.fail(7, "nothing after fx fy fz (export-yade translates no region)");
  std::string F = "(";
  for (int k = 0; k < 3; ++k) {
    const std::string c = s.force_component(a, 4 + k);
    F += (c == "None" || a[4 + k].rfind("v_", 0) != 0 ? c : "lambda: " + c) + ", ";
  }
  std::string ids;
  for (std::size_t i = 0; i < s.sim.atoms.n; ++i)
    if (s.sim.atoms.mask[i] & f.groupbit) ids += std::to_string(s.sim.atoms.id[i]) + ", ";
  const double* g = s.gravity();
  const std::string weight = "Vector3(" + yade_num(g[0]) + ", " + yade_num(g[1]) + ", " + yade_num(g[2]) + ")";
  s.set_forces(f, "_set_forces(" + yade_quoted(f.id) + ", [" + ids + "], " + F + "), " + weight + ", " +
                      (ave ? "True" : "False") + ")");
}

}  // namespace sable
