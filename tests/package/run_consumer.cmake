# ctest package.consumer (criterion C22): install this build into a temporary prefix, check that no
# installed file names the source or build tree, then configure, build and run tests/package/consumer, a
# separate project that only knows find_package(pounding).
# cmake -DBUILD_DIR=... -DSOURCE_DIR=... -DWORK_DIR=... -DCONFIG=... -DGENERATOR=... -DCXX=... -DVERSION=...
#       -DOBJCOPY=... -DSANITIZE=ON|OFF -P run_consumer.cmake
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

# No absolute path of the checkout or the build directory in any installed file. Text files (headers, the
# CMake package) are read as installed. Archives and programs are read without their debug sections: a
# RelWithDebInfo or Debug build's DWARF names the source files and the build directory by design (that is how a
# debugger finds them; `-ffile-prefix-map` would make them relative and unfindable); what they must not hold is a
# path in code or data. A sanitizer build (SANITIZE) is an exception there too, reported as such: UBSan's source
# locations and ASan's global descriptors are absolute file names in .rodata, which GCC 12 does not remap with
# -ffile-prefix-map (checked), and its archives are for sanitized programs only.
set(stripped ${WORK_DIR}/stripped)
file(MAKE_DIRECTORY ${stripped})
file(GLOB_RECURSE installed LIST_DIRECTORIES false RELATIVE ${prefix} ${prefix}/*)
set(text_files "")
set(binaries "")
foreach(f IN LISTS installed)
  if(f MATCHES "\\.(a|so)$" OR f MATCHES "^bin/")
    list(APPEND binaries ${f})
  else()
    list(APPEND text_files ${prefix}/${f})
  endif()
endforeach()
set(scanned ${text_files})
if(SANITIZE)
  list(LENGTH binaries nb)
  message("package.consumer: sanitizer build, its ${nb} archives and programs are not scanned for tree paths "
          "(the instrumentation's source locations name the tree); the text files are")
else()
  foreach(f IN LISTS binaries)
    string(REPLACE "/" "_" flat ${f})
    run("strip --strip-debug ${f}" ${OBJCOPY} --strip-debug ${prefix}/${f} ${stripped}/${flat})
    list(APPEND scanned ${stripped}/${flat})
  endforeach()
endif()
execute_process(COMMAND grep -lF -e ${SOURCE_DIR} -e ${BUILD_DIR} ${scanned} RESULT_VARIABLE rc OUTPUT_VARIABLE leaks)
if(rc EQUAL 0)
  message(FATAL_ERROR "installed files name the source or build tree (binaries: outside their debug sections, "
                      "copies in ${stripped}):\n${leaks}")
elseif(NOT rc EQUAL 1)
  message(FATAL_ERROR "grep over the installed tree failed (${rc})")
endif()
foreach(f include/pounding/kernel/batch.hpp include/pounding/core/version.hpp bin/pounding)
  if(NOT EXISTS ${prefix}/${f})
    message(FATAL_ERROR "not installed: ${f}")
  endif()
endforeach()

# A sanitizer build's archives call the sanitizer runtimes: its consumer is a sanitized program too.
set(sanitize_args "")
if(SANITIZE)
  set(sanitize_args -DCMAKE_CXX_FLAGS=-fsanitize=address,undefined -DCMAKE_EXE_LINKER_FLAGS=-fsanitize=address,undefined)
endif()
run("consumer configure" ${CMAKE_COMMAND} -S ${SOURCE_DIR}/tests/package/consumer -B ${WORK_DIR}/consumer
    -G ${GENERATOR} -DCMAKE_CXX_COMPILER=${CXX} -DCMAKE_BUILD_TYPE=Release -DCMAKE_PREFIX_PATH=${prefix}
    -DPOUNDING_EXPECTED_VERSION=${VERSION} ${sanitize_args})
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
