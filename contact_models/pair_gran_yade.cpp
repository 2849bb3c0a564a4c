// pair_style gran in sable --export-yade (core/io/yade_script.h): the models
// YADE has a law for, hertz (Mindlin) and linear/kneib (CundallStrackVisco),
// with tangential history; the materials and laws are written from the model.
#include "contact_models/pair_gran.h"
#include "core/io/yade_script.h"

namespace sable {

void PairGran::export_yade(YadeScript& s) const {
  const Args& a = args;
  if (a.size() < 4 || a[2] != "model") a.fail(1, "gran model ... (export-yade)");
  s.model = a[3];
  if (s.model != "hertz" && s.model != "linear/kneib")
    a.fail(3, "hertz or linear/kneib (the laws export-yade maps onto YADE)");
  bool history = false;
  for (std::size_t i = 4; i + 1 < a.size(); i += 2) {
    if (a[i] == "tangential" && a[i + 1] == "history") history = true;
    else if ((a[i] == "rolling_friction" || a[i] == "cohesion") && a[i + 1] == "off") continue;
    else if (a[i] == "damping" && a[i + 1] == "liggghts") continue;
    else if (a[i] == "limitForce" && (s.model == "hertz" || a[i + 1] == "off")) s.limit_force = a[i + 1] == "on";
    else if (a[i] != "tangential") a.fail(i, "tangential history (export-yade translates no other keyword)");
  }
  if (!history) a.fail_line("export-yade needs tangential history (YADE's laws keep the shear spring)");
}

}  // namespace sable
