# SPDX-License-Identifier: MIT
# The Debian packages (docs/packaging.md): `cpack -G DEB` in a build tree writes three, one per
# install component:
#   sewerplan          (component runtime, the default: whatever names no component) the command
#                      and sewerplan-compare, the modules it loads (LIBDIR/sewerplan), the station's
#                      page, the man page, the bash completion, the docs and the AIS test
#                      environment as example data; Depends from dpkg-shlibdeps only: run-time
#                      libraries, never a -dev package or a compiler.
#   sewerplan-dev      (component dev) the static libraries, their headers, version.h, the CMake
#                      package and sewerplan.pc; Depends only on the -dev packages
#                      find_package(sewerplan) and the static libraries' links need
#                      (cmake/sewerplanConfig.cmake.in), not on sewerplan: no installed library
#                      loads a module, runs the command or reads the runtime package's files (the
#                      module loader is the programs', not installed: docs/modules.md), so a
#                      program built against -dev runs without it (tests/install/deb_test.sh
#                      builds and runs one against -dev alone).
#   python3-sewerplan  (component python, with SEWERPLAN_PYTHON) the module in python3's
#                      dist-packages and its example; Depends from dpkg-shlibdeps, python3 of the
#                      version it was built for, and sewerplan (its modules and example data).
# Each has /usr/share/doc/<package>/copyright (machine-readable, packaging/debian/copyright.in with
# LICENSE's text) and changelog.Debian.gz (packaging/debian/changelog, whose version must be the
# package's). Binaries and libraries are stripped of their debug info. scripts/build-deb.sh builds
# them with Debian's hardened flags and runs lintian; tests/install/deb_test.sh checks the split.
install(FILES ${PROJECT_SOURCE_DIR}/README.md DESTINATION ${CMAKE_INSTALL_DOCDIR})
install(DIRECTORY ${PROJECT_SOURCE_DIR}/docs/ DESTINATION ${CMAKE_INSTALL_DOCDIR})
install(DIRECTORY ${PROJECT_SOURCE_DIR}/datasets/ais-testbed
        DESTINATION ${CMAKE_INSTALL_DATADIR}/sewerplan/datasets)
# (The bash completion and the man page are written and installed by apps/CMakeLists.txt.)
if(TARGET sewerplan_python)  # finds the example data beside it: ../../datasets/ais-testbed
  install(PROGRAMS ${PROJECT_SOURCE_DIR}/examples/python/plan_ais.py
          DESTINATION ${CMAKE_INSTALL_DATADIR}/sewerplan/examples/python COMPONENT python)
endif()
if(TARGET sewerplan-compare)
  install(TARGETS sewerplan-compare RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
endif()

# CPACK_STRIP_FILES strips executables but not static libraries: strip their debug info too when
# the install strips (cpack, cmake --install --strip).
install(CODE "
  if(CMAKE_INSTALL_DO_STRIP)
    file(GLOB sewerplan_static_libs
         \"\$ENV{DESTDIR}\${CMAKE_INSTALL_PREFIX}/${CMAKE_INSTALL_LIBDIR}/libsewerplan_*.a\")
    foreach(lib IN LISTS sewerplan_static_libs)
      execute_process(COMMAND \"${CMAKE_STRIP}\" --strip-debug \"\${lib}\")
    endforeach()
  endif()" COMPONENT dev)

set(SEWERPLAN_DEB_CONTACT "sewerplan maintainers <sewerplan@example.org>")
set(SEWERPLAN_DEB_RELEASE 1)  # the Debian revision: <version>-<release>
set(deb_version ${PROJECT_VERSION}-${SEWERPLAN_DEB_RELEASE})

# The changelog's newest entry is this version, or the package would say one version and its
# changelog another.
set(deb_changelog ${PROJECT_SOURCE_DIR}/packaging/debian/changelog)
set_property(DIRECTORY APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS ${deb_changelog}
                                                               ${PROJECT_SOURCE_DIR}/LICENSE)
file(STRINGS ${deb_changelog} deb_changelog_head LIMIT_COUNT 1)
if(NOT deb_changelog_head MATCHES "^sewerplan \\(${deb_version}\\) ")
  message(FATAL_ERROR "packaging/debian/changelog: its newest entry is '${deb_changelog_head}', "
                      "not sewerplan (${deb_version}): add an entry for this version")
endif()
# debian/copyright: the License paragraph is LICENSE's text, each line indented, blank lines " .".
file(STRINGS ${PROJECT_SOURCE_DIR}/LICENSE license_lines)
set(SEWERPLAN_DEB_LICENSE_TEXT "")
foreach(line IN LISTS license_lines)
  if(line STREQUAL "")
    set(line ".")
  endif()
  string(APPEND SEWERPLAN_DEB_LICENSE_TEXT " ${line}\n")
endforeach()
string(REGEX REPLACE "\n$" "" SEWERPLAN_DEB_LICENSE_TEXT "${SEWERPLAN_DEB_LICENSE_TEXT}")
set(deb_doc_dir ${PROJECT_BINARY_DIR}/packaging)
configure_file(${PROJECT_SOURCE_DIR}/packaging/debian/copyright.in ${deb_doc_dir}/copyright @ONLY)
# Gzipped without name or time stamp (-n), as Debian's policy wants, so the same sources give the
# same package.
add_custom_command(OUTPUT ${deb_doc_dir}/changelog.Debian.gz
  COMMAND gzip -9nc ${deb_changelog} > ${deb_doc_dir}/changelog.Debian.gz
  DEPENDS ${deb_changelog}
  COMMENT "Compressing the Debian changelog")
add_custom_target(sewerplan_deb_changelog ALL DEPENDS ${deb_doc_dir}/changelog.Debian.gz)

set(deb_components runtime dev)
if(TARGET sewerplan_python)
  list(APPEND deb_components python)
endif()
set(deb_package_runtime sewerplan)
set(deb_package_dev sewerplan-dev)
set(deb_package_python python3-sewerplan)
foreach(component IN LISTS deb_components)
  install(FILES ${deb_doc_dir}/copyright ${deb_doc_dir}/changelog.Debian.gz
          DESTINATION ${CMAKE_INSTALL_DATAROOTDIR}/doc/${deb_package_${component}}
          COMPONENT ${component})
endforeach()

set(CPACK_PACKAGE_NAME sewerplan)
set(CPACK_PACKAGE_VENDOR "sewerplan")
set(CPACK_PACKAGE_CONTACT "${SEWERPLAN_DEB_CONTACT}")
# Each package's description (CPACK_DEBIAN_<COMPONENT>_DESCRIPTION) starts with its own synopsis.
# CPack puts CPACK_PACKAGE_DESCRIPTION_SUMMARY (by default project()'s DESCRIPTION) before every
# description unless it is CPack's placeholder, which would give the three packages one synopsis
# and repeat it in each: so the placeholder, which no package shows.
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY "${CMAKE_PROJECT_NAME} built using CMake")
set(CPACK_PACKAGE_VERSION ${PROJECT_VERSION})
set(CPACK_PACKAGING_INSTALL_PREFIX ${SEWERPLAN_PACKAGE_PREFIX})  # cmake/SewerplanModule.cmake
set(CPACK_STRIP_FILES ON)
set(CPACK_GENERATOR DEB)
set(CPACK_DEB_COMPONENT_INSTALL ON)
set(CPACK_COMPONENTS_ALL ${deb_components})
set(CPACK_DEBIAN_PACKAGE_RELEASE ${SEWERPLAN_DEB_RELEASE})
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)  # <package>_<version>-<release>_<arch>.deb

set(CPACK_DEBIAN_RUNTIME_PACKAGE_NAME sewerplan)
set(CPACK_DEBIAN_RUNTIME_PACKAGE_SECTION science)
set(CPACK_DEBIAN_RUNTIME_PACKAGE_SHLIBDEPS ON)
set(CPACK_DEBIAN_RUNTIME_DESCRIPTION "planning and replanning for sewer-inspection robots
The sewerplan command plans inspection missions for autonomous sewer robots
on a map of the sewer network, checks plans (its own, FF's or Fast Downward's),
simulates missions with faults and replans, runs fault campaigns, renders
networks and plans, imports and exports GIS data and serves the operator
station's page. Parts with heavy libraries (GDAL and PROJ, OMPL, cairo, the
HTTP server) are modules loaded only by the commands that need them.

This package holds the command, its modules, the man page, the bash
completion, the documentation and the MAKRO paper's AIS test environment as
example data.")

set(CPACK_DEBIAN_DEV_PACKAGE_NAME sewerplan-dev)
set(CPACK_DEBIAN_DEV_PACKAGE_SECTION libdevel)
set(deb_dev_depends "nlohmann-json3-dev (>= 3.10), libeigen3-dev (>= 3.3), libsimdjson-dev, libpugixml-dev")
# No libompl-dev, libcairo2-dev or cpp-httplib: OMPL, cairo and the HTTP server are linked by their
# modules only (docs/modules.md), which are in sewerplan.
if(SEWERPLAN_WITH_GIS)  # the static gis library links -lproj and -lgdal
  string(APPEND deb_dev_depends ", libproj-dev, libgdal-dev")
endif()
set(CPACK_DEBIAN_DEV_PACKAGE_DEPENDS "${deb_dev_depends}")
set(CPACK_DEBIAN_DEV_DESCRIPTION "C++ libraries of sewerplan, the sewer-inspection robot planner
sewerplan plans and replans inspection missions for autonomous sewer robots.
These static libraries (core, domain, search, fusion, executor, ...) let robot
software embed the planner and its Replanner.

This package holds the libraries, their headers (C++20), the CMake package
(find_package(sewerplan), targets sewerplan::core, ...) and the pkg-config
file sewerplan.pc.")

set(CPACK_DEBIAN_PYTHON_PACKAGE_NAME python3-sewerplan)
set(CPACK_DEBIAN_PYTHON_PACKAGE_SECTION python)
set(CPACK_DEBIAN_PYTHON_PACKAGE_SHLIBDEPS ON)
if(TARGET sewerplan_python)  # built for one python3 version (python/CMakeLists.txt)
  set(CPACK_DEBIAN_PYTHON_PACKAGE_DEPENDS "${SEWERPLAN_PYTHON_DEB_DEPENDS}, sewerplan (= ${deb_version})")
endif()
set(CPACK_DEBIAN_PYTHON_DESCRIPTION "Python 3 module of sewerplan, the sewer-inspection robot planner
sewerplan plans and replans inspection missions for autonomous sewer robots.
The module sewerplan reads maps and missions, plans, checks plans, runs the
Replanner, simulates missions and runs fault campaigns from Python.

This package holds the module and an example that plans the MAKRO paper's
mission.")
include(CPack)
