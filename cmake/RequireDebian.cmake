# pounding_require(<Package> "<debian packages>" [CONFIG] [COMPONENTS ...])
# find_package that fails with the Debian package to install, instead of CMake's generic message.
macro(pounding_require pkg debs)
  find_package(${pkg} ${ARGN} QUIET)
  if(NOT ${pkg}_FOUND)
    message(FATAL_ERROR "pounding: dependency '${pkg}' not found. Install it with:\n"
                        "    sudo apt-get install ${debs}\n"
                        "or run tools/setup.sh, which installs every missing package.")
  endif()
endmacro()
