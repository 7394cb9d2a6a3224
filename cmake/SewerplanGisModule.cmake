# SPDX-License-Identifier: MIT
# Where the sewerplan command finds the GIS module (sewerplan/gis/module.h).
#
# In the build tree the command is bin/sewerplan and the module lib/sewerplan/sewerplan_gis.so,
# whatever the install layout. Installed, the command is in CMAKE_INSTALL_BINDIR and the module in
# CMAKE_INSTALL_LIBDIR/sewerplan, each relative to the prefix or absolute. The command looks from
# its own directory, first where an install puts the module, then where the build tree does.

# sewerplan_gis_module_install_relative(OUT PREFIX BINDIR LIBDIR): the module's path relative to the
# command's directory in an install with that prefix and those directories (relative to PREFIX or
# absolute), e.g. ../lib/sewerplan/sewerplan_gis.so for bin and lib.
function(sewerplan_gis_module_install_relative out prefix bindir libdir)
  foreach(dir IN ITEMS bindir libdir)
    if(IS_ABSOLUTE "${${dir}}")
      set(full_${dir} "${${dir}}")
    else()
      set(full_${dir} "${prefix}/${${dir}}")
    endif()
  endforeach()
  cmake_path(SET module NORMALIZE "${full_libdir}/sewerplan/sewerplan_gis.so")
  cmake_path(SET from NORMALIZE "${full_bindir}")
  cmake_path(RELATIVE_PATH module BASE_DIRECTORY "${from}" OUTPUT_VARIABLE relative)
  set(${out} "${relative}" PARENT_SCOPE)
endfunction()
