#!/usr/bin/env bash
# Our stand-ins for ROS packages Debian 12 does not ship (gazebo_msgs, ackermann_msgs, xacro,
# controller_manager_msgs, controller_manager, gazebo_ros, control_msgs,
# four_wheel_steering_msgs) are built only where the system has none. Where the system has one
# (a stock Noetic in /opt/ros, or any package that rospack finds outside this workspace), ours
# gets a CATKIN_IGNORE so it never shadows it.
#   scripts/stand_in_packages.sh [SOURCE_ROOT]    (default: the repo root)
# Prints one line per package. For tests, the places looked at can be replaced:
#   TIANRACER_ROS_PREFIXES  space-separated install prefixes (default: /opt/ros/*)
#   TIANRACER_ROSPACK       the rospack command (default: rospack)
set -euo pipefail

ROOT="$(cd "${1:-$(dirname "${BASH_SOURCE[0]}")/..}" && pwd)"
PREFIXES="${TIANRACER_ROS_PREFIXES-/opt/ros/*}"
ROSPACK="${TIANRACER_ROSPACK:-rospack}"

# ROS_PACKAGE_PATH without this workspace (its sources and its .build devel space).
outside_path() {
  local out=() entry
  IFS=':' read -r -a entries <<<"${ROS_PACKAGE_PATH:-}"
  for entry in "${entries[@]}"; do
    [[ -z "$entry" || "$entry" == "$ROOT" || "$entry" == "$ROOT"/* ]] && continue
    out+=("$entry")
  done
  (IFS=':'; echo "${out[*]:-}")
}

# Prints where the system's package is, or nothing.
system_package() {
  local pkg="$1" prefix found
  for prefix in $PREFIXES; do
    if [[ -f "$prefix/share/$pkg/package.xml" ]]; then
      echo "$prefix/share/$pkg"
      return
    fi
  done
  command -v "${ROSPACK%% *}" >/dev/null 2>&1 || return 0
  found="$(ROS_PACKAGE_PATH="$(outside_path)" $ROSPACK find "$pkg" 2>/dev/null || true)"
  if [[ -n "$found" && "$found" != "$ROOT" && "$found" != "$ROOT"/* ]]; then
    echo "$found"
  fi
}

STAND_INS=(gazebo_msgs ackermann_msgs xacro controller_manager_msgs controller_manager gazebo_ros
  control_msgs four_wheel_steering_msgs)
for pkg in "${STAND_INS[@]}"; do
  dir="$ROOT/$pkg"
  [[ -f "$dir/package.xml" ]] || continue
  where="$(system_package "$pkg")"
  if [[ -n "$where" ]]; then
    touch "$dir/CATKIN_IGNORE"
    echo "$pkg: the system's ($where) is used; ours is left out of the build"
  else
    rm -f "$dir/CATKIN_IGNORE"
    echo "$pkg: none on the system; ours ($dir) is built"
  fi
done
