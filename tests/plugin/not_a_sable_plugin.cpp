// A shared library built without sable's headers: `plugin load` must refuse it
// without running its constructor (tests/unit/test_plugin.cpp).
#include <cstdlib>

namespace {
[[gnu::constructor]] void loaded() { setenv("SABLE_TEST_FOREIGN_LIBRARY_RAN", "1", 1); }
}  // namespace
