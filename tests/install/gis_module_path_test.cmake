# SPDX-License-Identifier: MIT
# Where an installed sewerplan command looks for its GIS module (cmake/SewerplanGisModule.cmake):
# the path from the install's bin directory to LIBDIR/sewerplan/sewerplan_gis.so, for the default
# layout, Debian's multiarch libdir, a non-default relative libdir, and absolute bindirs and
# libdirs (which used to give a path into the build tree's copy of the absolute directory).
# Usage: cmake -DSOURCE_DIR=... -P gis_module_path_test.cmake
include(${SOURCE_DIR}/cmake/SewerplanGisModule.cmake)

function(expect prefix bindir libdir want)
  sewerplan_gis_module_install_relative(got "${prefix}" "${bindir}" "${libdir}")
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
    set(dest "${libdir}/sewerplan/sewerplan_gis.so")
  else()
    set(dest "${prefix}/${libdir}/sewerplan/sewerplan_gis.so")
  endif()
  cmake_path(SET reached NORMALIZE "${from}/${got}")
  cmake_path(SET dest NORMALIZE "${dest}")
  if(NOT reached STREQUAL dest)
    message(FATAL_ERROR "${from} + ${got} is ${reached}, not ${dest}")
  endif()
endfunction()

expect(/usr/local bin lib ../lib/sewerplan/sewerplan_gis.so)
expect(/usr bin lib/x86_64-linux-gnu ../lib/x86_64-linux-gnu/sewerplan/sewerplan_gis.so)
expect(/opt/sp bin lib64/private ../lib64/private/sewerplan/sewerplan_gis.so)
expect(/opt/sp tools/bin lib ../../lib/sewerplan/sewerplan_gis.so)
expect(/opt/sp bin /srv/sp-modules ../../../srv/sp-modules/sewerplan/sewerplan_gis.so)
expect(/opt/sp /usr/local/bin lib ../../../opt/sp/lib/sewerplan/sewerplan_gis.so)
expect(/opt/sp /opt/sp/bin /opt/sp/lib ../lib/sewerplan/sewerplan_gis.so)
expect(/opt/sp/ bin/ lib/ ../lib/sewerplan/sewerplan_gis.so)
message(STATUS "GIS module install paths: ok")
