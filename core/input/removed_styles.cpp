#include "core/input/removed_styles.h"

namespace sable {

namespace {
struct Removed {
  const char* kind;
  const char* name;
  const char* use;
};
// The granular pair styles took "Kn Kt gamma_n gamma_t xmu dampflag"; LIGGGHTS 3
// reads the law from `model` words and the coefficients from fix property/global.
constexpr const char* kPairGran =
    "'pair_style gran model hertz|hooke tangential history' with 'fix ID all property/global "
    "youngsModulus|poissonsRatio|coefficientRestitution|coefficientFriction ...' (or model "
    "hertz/stiffness|hooke/stiffness with kn kt gamman gammat)";
constexpr Removed kRemoved[] = {
    {"pair_style", "gran/hooke", kPairGran},
    {"pair_style", "gran/hooke/history", kPairGran},
    {"pair_style", "gran/hertz/history", kPairGran},
    {"pair_style", "gran/hooke/history/stiffness", kPairGran},
    {"pair_style", "gran/hertz/history/stiffness", kPairGran},
    {"fix", "pour", "'fix ID group insert/pack ...' or 'insert/rate/region ...' with fix particletemplate/sphere "
                    "and particledistribution/discrete"},
    {"fix", "wall/gran/hooke", "'fix ID group wall/gran model hooke tangential history primitive type T ...'"},
    {"fix", "wall/gran/hooke/history", "'fix ID group wall/gran model hooke tangential history primitive type T ...'"},
    {"fix", "wall/gran/hertz/history", "'fix ID group wall/gran model hertz tangential history primitive type T ...'"},
};
}  // namespace

std::string removed_style_hint(const std::string& kind, const std::string& name) {
  for (const Removed& r : kRemoved)
    if (kind == r.kind && name == r.name)
      return kind + " " + name + " is LIGGGHTS 2.x syntax, removed in LIGGGHTS 3 (3.8 rejects it too); use " + r.use;
  return "";
}

}  // namespace sable
