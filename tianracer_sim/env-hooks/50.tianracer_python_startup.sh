# Sourced with the workspace's setup.sh (catkin env hook, tianracer_sim/CMakeLists.txt).
# roslaunch, rosrun'd Python nodes and the xacro stand-in import distutils (roslaunch's rosclean);
# setuptools' shim (its distutils-precedence.pth) turns that into loading all of setuptools:
# 0.15-0.4 s of every roslaunch (docs/performance.md, Start-up). Python < 3.12 has a distutils of
# its own, which serves them the same. A value the user has set is kept (SETUPTOOLS_USE_DISTUTILS=local
# before sourcing: setuptools' distutils, as before). catkin's configure then prints distutils'
# DeprecationWarning once per setup.py it interrogates; nothing else changes.
if [ -z "${SETUPTOOLS_USE_DISTUTILS:-}" ]; then
  export SETUPTOOLS_USE_DISTUTILS=stdlib
fi
