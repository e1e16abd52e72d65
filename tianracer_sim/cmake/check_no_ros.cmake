# Fails the build of a ROS-free core library whose sources or headers include a ROS header.
# Debian installs ROS headers in /usr/include, where every target sees them, so include
# directories alone cannot keep them out: this check runs before each link of a core library.
# Usage: cmake -DAREA=<area> -DFILE_LIST=<file holding the ;-list of files> -P check_no_ros.cmake
set(_ros_include "#[ \t]*include[ \t]*[<\"](ros|roscpp|tf2_ros|rosbag|image_transport|camera_info_manager|std_srvs|[A-Za-z0-9_]+_msgs)/")
file(READ "${FILE_LIST}" FILES)
set(_found "")
foreach(_f ${FILES})
  file(STRINGS "${_f}" _lines REGEX "${_ros_include}")
  foreach(_l ${_lines})
    string(STRIP "${_l}" _l)
    list(APPEND _found "${_f}: ${_l}")
  endforeach()
endforeach()
if(_found)
  string(REPLACE ";" "\n  " _found "${_found}")
  message(FATAL_ERROR "tianracer_sim_${AREA} is a ROS-free core library (README, Layout), but includes "
                      "ROS headers:\n  ${_found}\nMove that code to src/msgs or src/ros.")
endif()
