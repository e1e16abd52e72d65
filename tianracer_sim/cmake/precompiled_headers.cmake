# Precompiled headers for the first build (docs/performance.md, First build): the system
# headers that most sources of a library parse again and again (Eigen's Geometry, roscpp and
# the message headers) are parsed once per library. Only headers from outside the repo go in,
# so a library's own headers stay checked (check_no_ros.cmake) and a missing #include still
# shows in a build without them.
#
# TIANRACER_PCH: AUTO (default) turns them on unless the compiler runs through ccache or the
# libraries are built in unity batches. ccache already skips the repeated work, and a
# precompiled header holds the absolute paths of its worktree, so with it every worktree sharing
# a ccache directory would miss the others' objects (and ccache caches such compiles only with
# CCACHE_SLOPPINESS=pch_defines,time_macros). A unity batch parses its headers once anyway: the
# ros area's header cost 14 s and saved as much (docs/performance.md, First build, part two),
# and it had to be built before any of the area's batches could start.
set(TIANRACER_PCH AUTO CACHE STRING "Precompiled headers: ON, OFF or AUTO (ON unless ccache or unity batches)")
set_property(CACHE TIANRACER_PCH PROPERTY STRINGS AUTO ON OFF)
if(TIANRACER_PCH STREQUAL "AUTO")
  set(_tianracer_ccache FALSE)
  set(_tianracer_unity FALSE)
  if(COMMAND tianracer_uses_ccache)  # the top-level CMakeLists.txt's
    tianracer_uses_ccache(_tianracer_ccache)
    tianracer_unity_on(_tianracer_unity)
  elseif("${CMAKE_CXX_COMPILER_LAUNCHER}" MATCHES "ccache")
    set(_tianracer_ccache TRUE)
  endif()
  if(_tianracer_ccache OR _tianracer_unity)
    set(TIANRACER_PCH_ON OFF)
  else()
    set(TIANRACER_PCH_ON ON)
  endif()
else()
  set(TIANRACER_PCH_ON ${TIANRACER_PCH})
endif()

# tianracer_precompile(<target> <header>...): <header>s are system headers (<...>).
function(tianracer_precompile target)
  if(NOT TIANRACER_PCH_ON OR CMAKE_VERSION VERSION_LESS 3.16)
    return()
  endif()
  target_precompile_headers(${target} PRIVATE ${ARGN})
endfunction()
