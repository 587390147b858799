# Helpers for the module libraries, the tests and the explicit file lists (CMakeLists.txt).
#
# pounding_add_library(<module> SOURCES <src/...cpp>... HEADERS <include/pounding/...hpp>...
#                      [PUBLIC_DEPS ...] [PRIVATE_DEPS ...])
#   A static library pounding_<module> (alias and exported name pounding::<module>): its sources, its
#   public headers as a HEADERS file set (installed, include paths through BUILD_INTERFACE/INSTALL_INTERFACE),
#   C++20 as a usage requirement, and the project's warnings (pounding_build_flags' compile options).
#   A dependency is PUBLIC only when one of the module's headers includes it.
#
# Every file named here (and by pounding_list_files) lands in a manifest, which the ctest
# build.source_lists compares with the files in src/, include/, tests/ and bench/ (cmake/check_source_lists.py).

function(pounding_list_files)
  set_property(GLOBAL APPEND PROPERTY POUNDING_LISTED_FILES ${ARGN})
endfunction()

function(pounding_add_library module)
  cmake_parse_arguments(PARSE_ARGV 1 arg "" "" "SOURCES;HEADERS;PUBLIC_DEPS;PRIVATE_DEPS")
  set(target pounding_${module})
  if(NOT arg_SOURCES)
    # A header-only module (the structure models): an INTERFACE library with its headers as a file set.
    add_library(${target} INTERFACE)
    add_library(pounding::${module} ALIAS ${target})
    target_sources(${target} INTERFACE FILE_SET HEADERS BASE_DIRS ${PROJECT_SOURCE_DIR}/include FILES ${arg_HEADERS})
    target_compile_features(${target} INTERFACE cxx_std_20)
    target_link_libraries(${target} INTERFACE ${arg_PUBLIC_DEPS})
    set_target_properties(${target} PROPERTIES EXPORT_NAME ${module})
    set_property(GLOBAL APPEND PROPERTY POUNDING_LIBRARIES ${target})
    pounding_list_files(${arg_HEADERS})
    return()
  endif()
  add_library(${target} STATIC)
  add_library(pounding::${module} ALIAS ${target})
  target_sources(${target} PRIVATE ${arg_SOURCES})
  if(arg_HEADERS)
    target_sources(${target} PUBLIC FILE_SET HEADERS BASE_DIRS ${PROJECT_SOURCE_DIR}/include FILES ${arg_HEADERS})
  endif()
  target_compile_features(${target} PUBLIC cxx_std_20)
  target_link_libraries(${target} PUBLIC ${arg_PUBLIC_DEPS} PRIVATE ${arg_PRIVATE_DEPS})
  # The shared flags as compile options only: a static library's private links are exported as LINK_ONLY
  # entries, and pounding_build_flags is a build-tree target. Executables link it (link options too).
  target_compile_options(${target} PRIVATE $<TARGET_PROPERTY:pounding_build_flags,INTERFACE_COMPILE_OPTIONS>)
  set_target_properties(${target} PROPERTIES EXPORT_NAME ${module})
  set_property(GLOBAL APPEND PROPERTY POUNDING_LIBRARIES ${target})
  pounding_list_files(${arg_SOURCES} ${arg_HEADERS})
endfunction()

# pounding_kernel_arch(<target>): POUNDING_KERNEL_ARCH as a PRIVATE compile option of <target>.
function(pounding_kernel_arch target)
  if(NOT POUNDING_KERNEL_ARCH_EFFECTIVE STREQUAL "OFF")
    target_compile_options(${target} PRIVATE -march=${POUNDING_KERNEL_ARCH_EFFECTIVE})
  endif()
endfunction()
