# SPDX-License-Identifier: MIT
# sewerplan_library(NAME <folder> SOURCES ... [DEPENDS <sewerplan libs>] [PUBLIC_LIBS ...] [PRIVATE_LIBS ...])
#
# Every top-level folder (core, domain, search, ...) is one library: sewerplan_<folder>, exported as
# sewerplan::<folder>. Its public headers live in <folder>/include/sewerplan/<folder>/. DEPENDS names
# the other sewerplan folders it may use; the one-way direction (core <- domain <- search, ...) is
# declared here and checked by tests/layering_test.sh.

set(SEWERPLAN_WARNINGS -Wall -Wextra -Wpedantic -Wshadow -Wconversion -Wsign-conversion
    -Wnon-virtual-dtor -Wold-style-cast -Woverloaded-virtual
    # Designated initializers leave members to their defaults on purpose.
    -Wno-missing-field-initializers
    # GCC 12 at -O3 reports std::string concatenation as overlapping memcpy (GCC PR 105651).
    $<$<CXX_COMPILER_ID:GNU>:-Wno-restrict>)

function(sewerplan_apply_options target)
  target_compile_options(${target} PRIVATE ${SEWERPLAN_WARNINGS}
    # The same seed must give the same network and plan with every compiler: no fused multiply-add
    # (clang fuses by default, GCC in ISO mode does not).
    -ffp-contract=off)
  if(SEWERPLAN_WERROR)
    target_compile_options(${target} PRIVATE -Werror)
  endif()
  if(SEWERPLAN_SANITIZE)
    target_compile_options(${target} PRIVATE -fsanitize=address,undefined -fno-omit-frame-pointer
                                             -fno-sanitize-recover=all)
    target_link_options(${target} PRIVATE -fsanitize=address,undefined)
  endif()
endfunction()

# sewerplan_precompile(<target> <header>...): the target's files are compiled with these system
# headers precompiled (SEWERPLAN_PCH). Only headers-only third-party libraries that most of the
# target's files include, never a sewerplan header: a file must still include what it uses (a
# build with -DSEWERPLAN_PCH=OFF shows a file that does not).
function(sewerplan_precompile target)
  if(SEWERPLAN_PCH)
    set(headers)
    foreach(header IN LISTS ARGN)
      list(APPEND headers "<${header}>")
    endforeach()
    target_precompile_headers(${target} PRIVATE ${headers})
  endif()
endfunction()

function(sewerplan_library)
  cmake_parse_arguments(ARG "" "NAME" "SOURCES;DEPENDS;PUBLIC_LIBS;PRIVATE_LIBS" ${ARGN})
  set(target sewerplan_${ARG_NAME})
  add_library(${target} ${ARG_SOURCES})
  add_library(sewerplan::${ARG_NAME} ALIAS ${target})
  set_target_properties(${target} PROPERTIES EXPORT_NAME ${ARG_NAME}
                                             OUTPUT_NAME sewerplan_${ARG_NAME}
                                             POSITION_INDEPENDENT_CODE ON)
  target_include_directories(${target} PUBLIC
    $<BUILD_INTERFACE:${CMAKE_CURRENT_SOURCE_DIR}/include>
    $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>)
  target_compile_features(${target} PUBLIC cxx_std_20)
  foreach(dep IN LISTS ARG_DEPENDS)
    target_link_libraries(${target} PUBLIC sewerplan::${dep})
  endforeach()
  target_link_libraries(${target} PUBLIC ${ARG_PUBLIC_LIBS} PRIVATE ${ARG_PRIVATE_LIBS})
  sewerplan_apply_options(${target})
  set_property(GLOBAL APPEND PROPERTY SEWERPLAN_LIBRARIES ${target})
endfunction()
