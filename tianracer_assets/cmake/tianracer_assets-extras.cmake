# The build rules every tianracer package shares, exported by the package below all others
# (catkin_package's CFG_EXTRAS): a package that finds tianracer_assets through catkin has them.

# C++17, RelWithDebInfo unless a build type is given, and the warnings every target compiles with.
macro(tianracer_cxx_defaults)
  set(CMAKE_CXX_STANDARD 17)
  set(CMAKE_CXX_STANDARD_REQUIRED ON)
  if(NOT CMAKE_BUILD_TYPE)
    set(CMAKE_BUILD_TYPE RelWithDebInfo)
  endif()
  add_compile_options(-Wall -Wextra)
endmacro()

# One gtest per pair after TESTS (test name, library): test/<name>.cpp linked with the library
# and gtest's main, with TEST_DATA_DIR (test/data), TIANRACER_DESCRIPTION_DIR and the
# DEFINITIONS given.
function(tianracer_add_unit_tests)
  cmake_parse_arguments(_ut "" "" "DEFINITIONS;TESTS" ${ARGN})
  list(LENGTH _ut_TESTS _n)
  math(EXPR _last "${_n} - 1")
  foreach(_i RANGE 0 ${_last} 2)
    math(EXPR _j "${_i} + 1")
    list(GET _ut_TESTS ${_i} _name)
    list(GET _ut_TESTS ${_j} _lib)
    catkin_add_gtest(${_name} test/${_name}.cpp)
    target_link_libraries(${_name} ${_lib} ${GMOCK_LIBRARIES} ${GTEST_MAIN_LIBRARIES})
    target_compile_definitions(${_name} PRIVATE
      TEST_DATA_DIR="${CMAKE_CURRENT_SOURCE_DIR}/test/data"
      TIANRACER_DESCRIPTION_DIR="${CMAKE_CURRENT_SOURCE_DIR}/../tianracer_description"
      ${_ut_DEFINITIONS})
  endforeach()
endfunction()

# <out>: those of the targets named in ARGN that this build has. In a catkin_make workspace
# the nodes a test launches are targets of the same build, and make run_tests builds them first.
function(tianracer_existing_targets out)
  set(_found)
  foreach(_t ${ARGN})
    if(TARGET ${_t})
      list(APPEND _found ${_t})
    endif()
  endforeach()
  set(${out} ${_found} PARENT_SCOPE)
endfunction()

# Every <dir>/*.test is a rostest (a new one needs no edit), run after the targets in ARGN.
# The caller finds rostest first.
function(tianracer_add_rostests dir)
  file(GLOB _rostests RELATIVE ${CMAKE_CURRENT_SOURCE_DIR} CONFIGURE_DEPENDS
    ${CMAKE_CURRENT_SOURCE_DIR}/${dir}/*.test)
  foreach(_t ${_rostests})
    add_rostest(${_t} DEPENDENCIES ${ARGN})
  endforeach()
endfunction()
