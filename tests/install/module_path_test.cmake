# SPDX-License-Identifier: MIT
# Where an installed sewerplan command looks for its modules (cmake/SewerplanModule.cmake): the
# path from the install's bin directory to LIBDIR/sewerplan, for the default
# layout, Debian's multiarch libdir, a non-default relative libdir, and absolute bindirs and
# libdirs (which used to give a path into the build tree's copy of the absolute directory).
# Usage: cmake -DSOURCE_DIR=... -P module_path_test.cmake
include(${SOURCE_DIR}/cmake/SewerplanModule.cmake)

function(expect prefix bindir libdir want)
  sewerplan_module_install_relative(got "${prefix}" "${bindir}" "${libdir}")
  if(NOT got STREQUAL want)
    message(FATAL_ERROR "prefix ${prefix}, bindir ${bindir}, libdir ${libdir}: got '${got}', want '${want}'")
  endif()
  # The path leads from the bin directory to the module's install destination.
  if(IS_ABSOLUTE "${bindir}")
    set(from "${bindir}")
  else()
    set(from "${prefix}/${bindir}")
  endif()
  if(IS_ABSOLUTE "${libdir}")
    set(dest "${libdir}/sewerplan")
  else()
    set(dest "${prefix}/${libdir}/sewerplan")
  endif()
  cmake_path(SET reached NORMALIZE "${from}/${got}")
  cmake_path(SET dest NORMALIZE "${dest}")
  if(NOT reached STREQUAL dest)
    message(FATAL_ERROR "${from} + ${got} is ${reached}, not ${dest}")
  endif()
endfunction()

expect(/usr/local bin lib ../lib/sewerplan)
expect(/usr bin lib/x86_64-linux-gnu ../lib/x86_64-linux-gnu/sewerplan)
expect(/opt/sp bin lib64/private ../lib64/private/sewerplan)
expect(/opt/sp tools/bin lib ../../lib/sewerplan)
expect(/opt/sp bin /srv/sp-modules ../../../srv/sp-modules/sewerplan)
expect(/opt/sp /usr/local/bin lib ../../../opt/sp/lib/sewerplan)
expect(/opt/sp /opt/sp/bin /opt/sp/lib ../lib/sewerplan)
expect(/opt/sp/ bin/ lib/ ../lib/sewerplan)
message(STATUS "module install paths: ok")
