# Sourced by scripts/setup.sh, test.sh and scripts/build_profile.sh: which generator catkin_make
# uses for a workspace (docs/performance.md, First build, part two). Ninja starts each compile as
# soon as its headers exist, where make builds a target's objects only after the libraries it
# links: the first build keeps both cores busy. A workspace keeps the generator it was configured
# with (CMake cannot switch one), so a workspace built with make stays a make one.
#   catkin_generator <workspace>   prints --use-ninja or nothing
catkin_generator() {
  local cache="$1/build/CMakeCache.txt"
  if [[ -f "$cache" ]]; then
    if grep -qx 'CMAKE_GENERATOR:INTERNAL=Ninja' "$cache"; then echo --use-ninja; fi
  elif command -v ninja >/dev/null; then
    echo --use-ninja
  fi
  return 0
}
