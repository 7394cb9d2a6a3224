# SPDX-License-Identifier: MIT
# sewerplan's modules (sewerplan/modules/module.h, modules/): parts built as shared objects of their
# own that a program loads with dlopen the first time it needs them.
#
# In the build tree every module is lib/sewerplan/sewerplan_NAME.so, one level up from bin/, tests/
# and bench/. Installed, it is in CMAKE_INSTALL_LIBDIR/sewerplan. The loader (modules/src/module_loader.cc)
# looks from the directory of the binary it is linked into: first where an install puts the
# modules relative to CMAKE_INSTALL_BINDIR, then where the build tree does, then the install's
# absolute directory.
#
#   sewerplan_module(NAME ompl SOURCES modules/ompl/ompl_module.cc LIBS sewerplan::motion sewerplan::modules)
#   sewerplan_uses_modules(my_program)   # builds every module before my_program

set(SEWERPLAN_MODULE_BUILD_DIR ${PROJECT_BINARY_DIR}/lib/sewerplan CACHE INTERNAL "")
# The Debian package installs under /usr whatever prefix the tree was configured for
# (cmake/SewerplanPackage.cmake): the loader's last place to look, for a program built against the
# package's libraries.
set(SEWERPLAN_PACKAGE_PREFIX /usr)
if(IS_ABSOLUTE "${CMAKE_INSTALL_LIBDIR}")
  set(SEWERPLAN_MODULE_PACKAGE_DIR "${CMAKE_INSTALL_LIBDIR}/sewerplan")
else()
  set(SEWERPLAN_MODULE_PACKAGE_DIR "${SEWERPLAN_PACKAGE_PREFIX}/${CMAKE_INSTALL_LIBDIR}/sewerplan")
endif()

# sewerplan_module_install_relative(OUT PREFIX BINDIR LIBDIR): the modules' directory relative to
# the command's directory in an install with that prefix and those directories (relative to PREFIX
# or absolute), e.g. ../lib/sewerplan for bin and lib.
function(sewerplan_module_install_relative out prefix bindir libdir)
  foreach(dir IN ITEMS bindir libdir)
    if(IS_ABSOLUTE "${${dir}}")
      set(full_${dir} "${${dir}}")
    else()
      set(full_${dir} "${prefix}/${${dir}}")
    endif()
  endforeach()
  cmake_path(SET modules NORMALIZE "${full_libdir}/sewerplan")
  cmake_path(SET from NORMALIZE "${full_bindir}")
  cmake_path(RELATIVE_PATH modules BASE_DIRECTORY "${from}" OUTPUT_VARIABLE relative)
  set(${out} "${relative}" PARENT_SCOPE)
endfunction()

# The build id in every module's ABI stamp, the same for a program and the modules of one build: a
# hash of the libraries' headers, public and private (a table may pass a type from a library's
# src/), and of the compiler and flags, regenerated when a header changes
# (cmake/module_build_id.cmake), as SEWERPLAN_MODULE_BUILD_ID in sewerplan_module_build_id.h
# (included by modules/src/module_stamp.cc only). Call once, before the libraries.
function(sewerplan_module_build_id)
  set(headers)
  foreach(lib IN ITEMS core domain search fusion motion localisation hal executor campaign render server gis
                      modules)
    file(GLOB_RECURSE lib_headers CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/${lib}/*.h)
    list(APPEND headers ${lib_headers})
  endforeach()
  string(TOUPPER "${CMAKE_BUILD_TYPE}" build_type)
  # The flags without the path maps (dpkg-buildflags adds -ffile-prefix-map=<build dir>=.): they
  # change file names in debug information, never a type's layout, and would give the same sources
  # built in two directories two ids.
  string(REGEX REPLACE "-f(file|debug|macro)-prefix-map=[^ ]*" "" flags
         "${CMAKE_CXX_FLAGS} ${CMAKE_CXX_FLAGS_${build_type}}")
  string(REGEX REPLACE " +" " " flags "${flags}")
  string(STRIP "${flags}" flags)
  string(JOIN " " config ${PROJECT_VERSION} ${CMAKE_CXX_COMPILER_ID} ${CMAKE_CXX_COMPILER_VERSION}
         ${CMAKE_CXX_STANDARD} "${flags}" sanitize=${SEWERPLAN_SANITIZE})
  set(dir ${PROJECT_BINARY_DIR}/generated/module_build_id)
  string(JOIN "\n" header_list ${headers})
  file(CONFIGURE OUTPUT ${dir}/headers.txt CONTENT "${header_list}")
  add_custom_command(OUTPUT ${dir}/sewerplan_module_build_id.h
    COMMAND ${CMAKE_COMMAND} -DSOURCE_DIR=${PROJECT_SOURCE_DIR} -DHEADERS=${dir}/headers.txt
            "-DCONFIG=${config}" -DVERSION=${PROJECT_VERSION}
            -DOUT=${dir}/sewerplan_module_build_id.h
            -P ${PROJECT_SOURCE_DIR}/cmake/module_build_id.cmake
    DEPENDS ${headers} ${dir}/headers.txt ${PROJECT_SOURCE_DIR}/cmake/module_build_id.cmake
    COMMENT "Hashing the modules' build id")
  add_custom_target(sewerplan_module_build_id DEPENDS ${dir}/sewerplan_module_build_id.h)
  set(SEWERPLAN_MODULE_BUILD_ID_DIR ${dir} CACHE INTERNAL "")
endfunction()

# sewerplan_module(NAME <name> SOURCES ... [LIBS ...]): the module sewerplan_<name>.so, target
# sewerplan_<name>_module. Its sources define the two entry symbols (sewerplan/modules/module.h); only
# they are exported: the static libraries inside stay hidden, so they never bind to the program's
# own copies.
function(sewerplan_module)
  cmake_parse_arguments(ARG "" "NAME" "SOURCES;LIBS" ${ARGN})
  set(target sewerplan_${ARG_NAME}_module)
  add_library(${target} MODULE ${ARG_SOURCES})
  target_link_libraries(${target} PRIVATE ${ARG_LIBS})
  target_link_options(${target} PRIVATE -Wl,--exclude-libs,ALL)
  # Every symbol resolved at link time, except in the sanitizer and fuzz trees: clang links its
  # runtimes into the executable only, and the module finds them there when it is loaded.
  if(NOT SEWERPLAN_SANITIZE AND NOT SEWERPLAN_FUZZ)
    target_link_options(${target} PRIVATE -Wl,--no-undefined)
  endif()
  set_target_properties(${target} PROPERTIES
    OUTPUT_NAME sewerplan_${ARG_NAME} PREFIX ""
    CXX_VISIBILITY_PRESET hidden VISIBILITY_INLINES_HIDDEN ON
    LIBRARY_OUTPUT_DIRECTORY ${SEWERPLAN_MODULE_BUILD_DIR})
  sewerplan_apply_options(${target})
  install(TARGETS ${target} LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}/sewerplan)
  set_property(GLOBAL APPEND PROPERTY SEWERPLAN_MODULES ${target})
endfunction()

# sewerplan_uses_modules(TARGET): TARGET (a program, or the Python module) loads modules, so every
# module is built before it. The target sewerplan_modules is defined once all are known
# (sewerplan_define_modules_target, at the end of the top-level CMakeLists.txt).
function(sewerplan_uses_modules target)
  add_dependencies(${target} sewerplan_modules)
endfunction()

function(sewerplan_define_modules_target)
  add_custom_target(sewerplan_modules)
  get_property(modules GLOBAL PROPERTY SEWERPLAN_MODULES)
  if(modules)
    add_dependencies(sewerplan_modules ${modules})
  endif()
endfunction()
