# A newcomer's sub-model is one header: written here into a copy of
# contact_models/, with nothing else edited, the build's generator
# (contact_models/models.cmake) must list it on its axis and register it with
# every other model, and that composition must compile.
# cmake -DSRC=<source dir> -DWORK=<scratch dir> -DCXX=<compiler> -P newcomer_model.cmake
file(REMOVE_RECURSE ${WORK})
file(COPY ${SRC}/contact_models DESTINATION ${WORK})
file(WRITE ${WORK}/contact_models/rolling/newcomer.h [=[
#pragma once
// A test's rolling model: a torque opposing the relative spin, proportional to it.
#include "contact_models/contact.h"
#include "contact_models/materials.h"
namespace sable {
struct RollingNewcomer {
  static constexpr const char* kName = "newcomer";
  static constexpr int kHistory = 1;
  static void history_slots(std::vector<HistorySlot>& s) { s.push_back({"newcomer_angle", false}); }
  void settings(ModelSettings&) {}
  void connect(PropertyRequest&) {}
  Vec3 torque(const Contact& c, const NormalForce&, double* h, const StepContext& x) const {
    if (x.update) h[0] += x.dt;
    return {1e-9 * c.wroll[0], 1e-9 * c.wroll[1], 1e-9 * c.wroll[2]};
  }
};
}  // namespace sable

SABLE_ROLLING_MODEL(sable::RollingNewcomer);
]=])
include(${WORK}/contact_models/models.cmake)
sable_generate_models(${WORK} ${WORK}/generated)
file(READ ${WORK}/generated/contact_models/builtin_models.h models)
if(NOT models MATCHES "#include \"contact_models/rolling/newcomer.h\"")
  message(FATAL_ERROR "the newcomer's header is not included:\n${models}")
endif()
if(NOT models MATCHES "using Rollings = TypeList<[^>]*sable::RollingNewcomer")
  message(FATAL_ERROR "the newcomer is not on the rolling axis:\n${models}")
endif()
list(LENGTH SABLE_MODEL_SOURCES n)
message(STATUS "generated ${n} law sources; the rolling axis: newcomer listed")
# Every normal x damping source composes the newcomer; compile one of them in full semantic analysis.
list(GET SABLE_MODEL_SOURCES 0 first)
list(TRANSFORM INC PREPEND -I)
execute_process(COMMAND ${CXX} -std=c++20 -fsyntax-only -I${WORK} -I${WORK}/generated -I${SRC} ${INC} ${first}
                RESULT_VARIABLE rc ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "the composition with the newcomer does not compile:\n${err}")
endif()
message(STATUS "compiled ${first} with the newcomer: ok")
