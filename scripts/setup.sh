#!/usr/bin/env bash
# Installs what tianracer sim needs on Debian 12 (apt + pip), then builds the catkin workspace.
#   scripts/setup.sh            install missing dependencies, build (RelWithDebInfo: -O2 -g)
#   scripts/setup.sh --no-build install only
#   scripts/setup.sh --release  build without debug info (-O2, the same machine code), a
#                               third less compile time.
#   scripts/setup.sh --demo     what ./run.sh uses: --release, and on a new workspace only
#                               what the demo runs (no Python bindings, benchmarks, corpus
#                               tools; TIANRACER_EXTRAS=OFF), without the benchmark's venv.
#   A new workspace is built with Ninja (ninja-build), one already built keeps its generator
#   (scripts/catkin_generator.sh; one target: cmake --build .build/build --target X).
#   A workspace already built keeps its build type either way, so nothing is compiled again;
#   without --demo the extras are built (./test.sh after ./run.sh compiles only those and the
#   tests; docs/performance.md, First build).
# Idempotent: installed packages are skipped; sudo is used when not root.
# Build output: <repo>/.build/{build,devel} (hidden and git-ignored).
set -euo pipefail

REPO="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
WS="$REPO/.build"
LOG_DIR="$WS/logs"
BUILD=1
RELEASE=0
DEMO=0
for arg in "$@"; do
  case "$arg" in
    --no-build) BUILD=0 ;;
    --release) RELEASE=1 ;;
    --demo) DEMO=1; RELEASE=1 ;;
    *) printf 'usage: %s [--no-build] [--release] [--demo]\n' "$0" >&2; exit 2 ;;
  esac
done

# Debian packages. The first block is shared/TOOLCHAIN.md's checked recipe; the rest are the
# libraries and tools the packages use (tinyxml2, yaml, gtest, msgs, rendering, tests).
APT_PACKAGES=(
  catkin ros-core-dev python3-rostest librostest-dev rosbash python3-rostopic
  libsensor-msgs-dev python3-sensor-msgs libgeometry-msgs-dev libnav-msgs-dev python3-nav-msgs
  libtf2-ros-dev python3-tf2-ros liburdf-dev liburdfdom-dev libbullet-dev libbullet-extras-dev
  libeigen3-dev libassimp-dev libosmesa6-dev libembree-dev libpng-dev libstb-dev ros-robot-state-publisher python3-pip g++ cmake make
  ninja-build git pkg-config libtinyxml2-dev libyaml-cpp-dev libgtest-dev libgmock-dev liburdfdom-tools
  libstd-srvs-dev python3-std-srvs libtopic-tools-dev libdiagnostic-msgs-dev python3-diagnostic-msgs
  libdynamic-reconfigure-config-init-mutex-dev python3-dynamic-reconfigure
  libros-rosgraph-msgs-dev python3-rosgraph-msgs python3-numpy python3-pil python3-yaml python3-catkin-pkg python3-nose

  # the real viewers and the tutorial's joint sliders (display.launch, the rviz check under Xvfb),
  # and the benchmark's PyBullet virtual environment
  joint-state-publisher joint-state-publisher-gui rviz xvfb xauth imagemagick python3-venv
  python3-matplotlib python3-tqdm
  # the CPU hog of the load check (./test.sh --load)
  stress-ng
  # the Python bindings of the simulation (tianracer_sim.simulator) and tianracer_gym
  pybind11-dev python3-rospkg
  # the node's ~step_and_wait action
  libactionlib-dev python3-actionlib libactionlib-msgs-dev python3-actionlib-msgs
  # our control_msgs stand-in's message dependencies (JointTrajectory), C++ and Python
  libtrajectory-msgs-dev python3-trajectory-msgs python3-geometry-msgs
)
# xacro: the ROS 1 one (2.x is the ROS 2 one, TOOLCHAIN.md); ray: scenario batches (`batch`);
# gymnasium: tianracer_gym's environments (docs/learning.md)
PIP_PACKAGES=(xacro==1.13.3 ray==2.60.0 gymnasium==1.2.2)

say()  { printf '==> [setup] %s\n' "$*"; }
fail() { printf '\nERROR [setup] %s\n' "$*" >&2; exit 1; }

SUDO=()
if [[ "$(id -u)" -ne 0 ]]; then
  command -v sudo >/dev/null || fail "step 'apt': not root and sudo is not installed"
  SUDO=(sudo)
fi

# --- apt ---------------------------------------------------------------------------------
missing=()
for pkg in "${APT_PACKAGES[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$pkg" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$pkg")
  fi
done
if ((${#missing[@]})); then
  say "apt: installing ${#missing[@]} missing package(s): ${missing[*]}"
  mkdir -p "$LOG_DIR"
  "${SUDO[@]}" apt-get update -qq >"$LOG_DIR/apt.log" 2>&1 \
    || { tail -20 "$LOG_DIR/apt.log" >&2; fail "step 'apt': apt-get update failed (log: $LOG_DIR/apt.log)"; }
  DEBIAN_FRONTEND=noninteractive "${SUDO[@]}" apt-get install -y -qq --no-install-recommends \
    "${missing[@]}" >>"$LOG_DIR/apt.log" 2>&1 \
    || { tail -20 "$LOG_DIR/apt.log" >&2; fail "step 'apt': apt-get install failed for: ${missing[*]} (log: $LOG_DIR/apt.log)"; }
else
  say "apt: all ${#APT_PACKAGES[@]} packages present"
fi

# --- pip (system Python: ROS's Python is /usr/bin/python3) ---------------------------------
for spec in "${PIP_PACKAGES[@]}"; do
  name="${spec%%==*}"; want="${spec#*==}"
  have="$(/usr/bin/python3 -m pip show "$name" 2>/dev/null | sed -n 's/^Version: //p' || true)"
  if [[ "$have" == "$want" ]]; then
    say "pip: $name $have present"
  else
    say "pip: installing $spec (found: ${have:-none})"
    "${SUDO[@]}" /usr/bin/python3 -m pip install -q --break-system-packages "$spec" \
      || fail "step 'pip': pip install $spec failed"
  fi
done
command -v xacro >/dev/null || fail "step 'pip': xacro is not on PATH after installing it"

# The benchmark's PyBullet and MuJoCo (tianracer_bringup/bench/requirements.txt, pinned) in a virtual
# environment of its own under .build/, whatever python3 is on PATH; a no-op once installed.
if ((DEMO)); then
  say "pip: the benchmark's PyBullet and MuJoCo environment is not needed by the demo (./test.sh installs it)"
elif ! /usr/bin/python3 "$REPO/tianracer_bringup/bench/run_benchmarks" --install-only 2>&1 \
     | sed 's/^/==> [setup] pip: /'; then
  fail "step 'pip': the benchmark's PyBullet and MuJoCo environment (.build/bench_venv) could not be installed"
fi

((BUILD)) || exit 0

# --- build -------------------------------------------------------------------------------
# ROS tools want the system Python first on PATH (TOOLCHAIN.md: python3 may be a pyenv).
export PATH="/usr/bin:$PATH"
mkdir -p "$LOG_DIR"
# Our stand-ins (gazebo_msgs, ackermann_msgs, xacro, controller_manager(_msgs), gazebo_ros,
# control_msgs, four_wheel_steering_msgs) only
# where the system has none: never shadow the real ones.
stand_ins="$("$REPO/scripts/stand_in_packages.sh" "$REPO")" \
  || fail "step 'build': scripts/stand_in_packages.sh failed"
while read -r line; do say "stand-ins: $line"; done <<<"$stand_ins"
# The build type: RelWithDebInfo (-O2 -g) for the tests and debugging. --release drops the
# debug info (a third of the compile time) but keeps -O2, so the machine code and every result
# are the same (Release's own default, -O3, would not be); it applies to a new workspace only.
# A workspace already built keeps its type, whichever command built it: ./test.sh after
# ./run.sh builds only the test executables, not everything again with debug info.
build_type=RelWithDebInfo
((RELEASE)) && build_type=Release
# --demo (./run.sh) on a new workspace builds only what the demo runs (TIANRACER_EXTRAS=OFF:
# no Python bindings, benchmarks or corpus tools); without it everything is built, which on a
# workspace ./run.sh built compiles only what is missing.
extras=(-DTIANRACER_EXTRAS=ON)
((DEMO)) && extras=(-DTIANRACER_EXTRAS=OFF)
if [[ -f "$WS/build/CMakeCache.txt" ]]; then
  cached="$(sed -n 's/^CMAKE_BUILD_TYPE:[A-Z]*=//p' "$WS/build/CMakeCache.txt")"
  build_type="${cached:-RelWithDebInfo}"  # none: the packages' own default
  ((DEMO)) && extras=()  # keep what the workspace has
fi
# shellcheck source=catkin_generator.sh
source "$REPO/scripts/catkin_generator.sh"
mapfile -t generator < <(catkin_generator "$WS")
say "build: catkin_make ${generator[*]:-(make)} ($build_type) in $WS (log: $LOG_DIR/build.log)"
start=$(date +%s)
if ! catkin_make "${generator[@]}" -C "$WS" --source "$REPO" -DPYTHON_EXECUTABLE=/usr/bin/python3 \
      -DCMAKE_BUILD_TYPE="$build_type" -DCMAKE_CXX_FLAGS_RELEASE="-O2 -DNDEBUG" \
      -DCMAKE_C_FLAGS_RELEASE="-O2 -DNDEBUG" "${extras[@]}" -j"$(nproc)" >"$LOG_DIR/build.log" 2>&1; then
  # Name the failing package and step: a CMake error follows the package's add_subdirectory
  # line; a compile error shows as 'make[N]: *** [<package>/CMakeFiles/...' or Ninja's
  # 'FAILED: <package>/CMakeFiles/...'.
  pkg="$(grep -oE 'make\[[0-9]+\]: \*\*\* \[[^/]+|^FAILED: [^/]+' "$LOG_DIR/build.log" | head -1 \
         | sed 's/.*\[//; s/^FAILED: //' || true)"
  step="compile/link"
  if [[ -z "$pkg" ]] && grep -q "CMake Error" "$LOG_DIR/build.log"; then
    step="configure (cmake)"
    pkg="$(sed -n '1,/CMake Error/p' "$LOG_DIR/build.log" | grep -oE 'add_subdirectory\([^)]+\)' \
           | tail -1 | sed 's/add_subdirectory(//; s/)//' || true)"
  fi
  tail -40 "$LOG_DIR/build.log" >&2
  fail "step 'build' ($step) failed in package '${pkg:-unknown}'; full log: $LOG_DIR/build.log"
fi
say "build: done in $(( $(date +%s) - start )) s"
