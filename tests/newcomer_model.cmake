# A newcomer's sub-model is one header: written here into a copy of
# contact_models/, with nothing else edited, the build's generator
# (contact_models/models.cmake) must list it on its axis, and the source that
# registers every listed model for laws composed at run time
# (contact_models/builtin_parts.cpp) must compile with it; once a line of
# compiled_laws.txt names it, its compiled law must be generated and compile.
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
list(TRANSFORM INC PREPEND -I)
function(compiles what file)
  execute_process(COMMAND ${CXX} -std=c++20 -fsyntax-only -I${WORK} -I${WORK}/generated -I${SRC} ${INC} ${file}
                  RESULT_VARIABLE rc ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "${what} does not compile:\n${err}")
  endif()
  message(STATUS "${what}: compiles")
endfunction()
# Composed at run time with every other model: no list edited.
compiles("the newcomer as a part of composed laws (builtin_parts.cpp)" ${WORK}/contact_models/builtin_parts.cpp)
# Compiled once the list names it.
file(APPEND ${WORK}/contact_models/compiled_laws.txt "hertz liggghts history newcomer off  # the newcomer, fast\n")
sable_generate_models(${WORK} ${WORK}/generated)
set(law ${WORK}/generated/law_hertz_liggghts_history_newcomer_off.cpp)
list(FIND SABLE_MODEL_SOURCES ${law} at)
if(at EQUAL -1)
  message(FATAL_ERROR "no compiled law generated for the newcomer's line: ${SABLE_MODEL_SOURCES}")
endif()
compiles("the newcomer's compiled law (${law})" ${law})
