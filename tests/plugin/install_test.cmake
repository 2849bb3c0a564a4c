# ctest plugin.installed_out_of_tree: installs the build into a scratch prefix, builds
# tests/plugin/example_contact_plugin.cpp there as a user's law with find_package(sable)
# (tests/plugin/out_of_tree/, against the installed headers only) and runs
# tests/plugin/restitution.in with the installed sable, judged by tests/check_deck.py.
# cmake -DBUILD=<build dir> -DSRC=<source dir> -DWORK=<scratch dir> -DCXX=<compiler>
#       -DPYTHON=<python3> -P install_test.cmake
function(run what)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE out)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "${what} failed (${rc}):\n${out}")
  endif()
  message(STATUS "${what}: ok\n${out}")
endfunction()

file(REMOVE_RECURSE ${WORK})
set(prefix ${WORK}/prefix)
run("cmake --install" ${CMAKE_COMMAND} --install ${BUILD} --prefix ${prefix})
foreach(f bin/sable bin/sable-analyze include/sable/contact_models/registry.h
          include/sable/contact_models/builtin_models.h include/sable/sable_plugin_version.h
          lib/cmake/sable/sableConfig.cmake lib/cmake/sable/sableConfigVersion.cmake
          lib/cmake/sable/sableTargets.cmake)
  if(NOT EXISTS ${prefix}/${f})
    message(FATAL_ERROR "the install lacks ${f}")
  endif()
endforeach()
# The package must not point back into the trees it was built from.
file(GLOB package ${prefix}/lib/cmake/sable/*.cmake)
foreach(f ${package})
  file(READ ${f} text)
  foreach(tree ${SRC} ${BUILD})
    string(FIND "${text}" "${tree}" at)
    if(NOT at EQUAL -1)
      message(FATAL_ERROR "${f} names ${tree}")
    endif()
  endforeach()
endforeach()

# The law, copied out of the source tree so that only the installed headers are found.
file(COPY ${SRC}/tests/plugin/example_contact_plugin.cpp DESTINATION ${WORK}/law)
run("configure the law with find_package(sable)" ${CMAKE_COMMAND} -S ${SRC}/tests/plugin/out_of_tree
    -B ${WORK}/build -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_COMPILER=${CXX} -DCMAKE_PREFIX_PATH=${prefix}
    -DLAW=${WORK}/law/example_contact_plugin.cpp)
run("build the law" ${CMAKE_COMMAND} --build ${WORK}/build)
file(GLOB plugin ${WORK}/build/*hertz_petit.so)
if(NOT plugin)
  message(FATAL_ERROR "no plugin built in ${WORK}/build")
endif()

set(PLUGIN ${plugin})
configure_file(${SRC}/tests/plugin/restitution.in ${WORK}/run/restitution.in @ONLY)
run("restitution.in with the installed sable" ${CMAKE_COMMAND} -E chdir ${WORK}/run
    ${CMAKE_COMMAND} -E env PYTHONPATH=${SRC} ${PYTHON} ${SRC}/tests/check_deck.py
    --sable ${prefix}/bin/sable ${WORK}/run/restitution.in)
