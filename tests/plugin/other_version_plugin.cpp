// A plugin that claims the next minor version of sable (tests/CMakeLists.txt builds it
// with SABLE_VERSION_MINOR overridden): `plugin load` must refuse it before its
// registrar runs, so the command below stays unknown (tests/unit/test_plugin.cpp).
#include "core/input/style_registry.h"

namespace {
void cmd_probe(sable::Simulation&, const sable::Args&) {}
}  // namespace

SABLE_COMMAND("test/other_version_probe", cmd_probe);
