# ctest package.consumer (criterion C22): install this build into a temporary prefix, check that no
# installed file names the source or build tree, then configure, build and run tests/package/consumer, a
# separate project that only knows find_package(pounding).
# cmake -DBUILD_DIR=... -DSOURCE_DIR=... -DWORK_DIR=... -DCONFIG=... -DGENERATOR=... -DCXX=... -DVERSION=...
#       -P run_consumer.cmake
file(REMOVE_RECURSE ${WORK_DIR})
set(prefix ${WORK_DIR}/prefix)

function(run what)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "${what} failed (${rc}):\n${out}\n${err}")
  endif()
  set(last_output "${out}" PARENT_SCOPE)
endfunction()

set(config_args "")
if(CONFIG)
  set(config_args --config ${CONFIG})
endif()
run("install" ${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${prefix} ${config_args})

# No absolute path of the checkout or the build directory in any installed file (binaries included).
execute_process(COMMAND grep -rlF -e ${SOURCE_DIR} -e ${BUILD_DIR} ${prefix} RESULT_VARIABLE rc OUTPUT_VARIABLE leaks)
if(rc EQUAL 0)
  message(FATAL_ERROR "installed files name the source or build tree:\n${leaks}")
elseif(NOT rc EQUAL 1)
  message(FATAL_ERROR "grep over the installed tree failed (${rc})")
endif()
foreach(f include/pounding/kernel/batch.hpp include/pounding/core/version.hpp bin/pounding)
  if(NOT EXISTS ${prefix}/${f})
    message(FATAL_ERROR "not installed: ${f}")
  endif()
endforeach()

run("consumer configure" ${CMAKE_COMMAND} -S ${SOURCE_DIR}/tests/package/consumer -B ${WORK_DIR}/consumer
    -G ${GENERATOR} -DCMAKE_CXX_COMPILER=${CXX} -DCMAKE_BUILD_TYPE=Release -DCMAKE_PREFIX_PATH=${prefix}
    -DPOUNDING_EXPECTED_VERSION=${VERSION})
# the consumer enables only CXX, and find_package(pounding) must not have enabled C behind its back
file(STRINGS ${WORK_DIR}/consumer/CMakeCache.txt c_compiler REGEX "^CMAKE_C_COMPILER:")
if(c_compiler)
  message(FATAL_ERROR "find_package(pounding) enabled the C language in a C++-only consumer: ${c_compiler}")
endif()
run("consumer build" ${CMAKE_COMMAND} --build ${WORK_DIR}/consumer)
execute_process(COMMAND ${WORK_DIR}/consumer/consumer WORKING_DIRECTORY ${WORK_DIR} RESULT_VARIABLE rc
                OUTPUT_VARIABLE last_output ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "consumer run failed (${rc}):\n${last_output}\n${err}")
endif()
message("${last_output}")
if(NOT last_output MATCHES "peak closing [0-9.e+-]+ m" OR NOT last_output MATCHES "HDF5 round trip: ok")
  message(FATAL_ERROR "the consumer printed no peak closing or no HDF5 round trip")
endif()
file(REMOVE_RECURSE ${WORK_DIR})
