# ctest contact.registry_eighth_law (issue 25 section 1; architecture.md 2.4.5, 2.5.1): adds an eighth contact
# law to a copy of include/ as a newcomer would (its header, one entry in contact::Laws, its enumerator in
# ContactLaw) and compiles a unit that asks the resolution guard for its limit:
#   without declared resolution limits the build must FAIL, naming the missing trait (static_assert);
#   with them it must build.
# Before the limits became a law trait (physics/resolution.hpp's [scheme][law] table of law_count = 7), nothing
# refused the first: it built and read the limit past the end of the table.
# Usage: cmake -DSOURCE_DIR=.. -DWORK_DIR=.. -DCXX=.. -DARCH=<-march value or OFF> -P run.cmake
foreach(v SOURCE_DIR WORK_DIR CXX ARCH)
  if(NOT DEFINED ${v})
    message(FATAL_ERROR "run.cmake needs -D${v}=...")
  endif()
endforeach()
set(here ${SOURCE_DIR}/tests/contact/eighth_law)
file(REMOVE_RECURSE ${WORK_DIR})
file(COPY ${SOURCE_DIR}/include DESTINATION ${WORK_DIR})
set(inc ${WORK_DIR}/include/pounding)
file(COPY ${here}/eighth.hpp DESTINATION ${inc}/contact/laws)

# the newcomer's edits, wherever the lists end; a patch point that moved fails the test (it must not pass by building
# the old list)
function(edit file regex replacement)
  file(READ ${file} text)
  string(REGEX MATCH "${regex}" found "${text}")
  if(NOT found)
    message(FATAL_ERROR "FAIL: '${regex}' not found in ${file}: update tests/contact/eighth_law/run.cmake")
  endif()
  string(REGEX REPLACE "${regex}" "${replacement}" text "${text}")
  file(WRITE ${file} "${text}")
endfunction()
edit(${inc}/contact/registry.hpp "#pragma once\n" "#pragma once\n#include \"pounding/contact/laws/eighth.hpp\"\n")
edit(${inc}/contact/registry.hpp "using Laws = TypeList<([^>]*)>;" "using Laws = TypeList<\\1, Eighth>;")
edit(${inc}/contact/model.hpp "(enum class ContactLaw : std::uint8_t {[^}]*)};" "\\1  eighth,\n};")

set(flags -std=c++20 -fsyntax-only -I${WORK_DIR}/include)
if(NOT ARCH STREQUAL "OFF")
  list(APPEND flags -march=${ARCH})
endif()
function(compile out_var err_var)
  execute_process(COMMAND ${CXX} ${flags} ${ARGN} ${here}/main.cpp RESULT_VARIABLE rc ERROR_VARIABLE err
                  OUTPUT_VARIABLE out)
  set(${out_var} ${rc} PARENT_SCOPE)
  set(${err_var} "${out}${err}" PARENT_SCOPE)
endfunction()

compile(rc err)
if(rc EQUAL 0)
  message(FATAL_ERROR "FAIL: a registry with an eighth law that declares no resolution limits built; the "
                      "resolution guard would read a limit that does not exist")
endif()
string(FIND "${err}" "must declare its resolution limits" named)
if(named EQUAL -1)
  message(FATAL_ERROR "FAIL: the build failed, but without naming the missing resolution limits:\n${err}")
endif()
string(REGEX MATCH "[^\n]*static assertion failed[^\n]*" line "${err}")
message(STATUS "ok:   the eighth law without limits is refused: ${line}")

compile(rc err -DEIGHTH_DECLARES_LIMITS)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "FAIL: a registry with an eighth law that declares its limits does not build:\n${err}")
endif()
message(STATUS "ok:   the eighth law with limits builds")
