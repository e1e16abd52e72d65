#!/usr/bin/env bash
# Builds the gtests with AddressSanitizer and UndefinedBehaviorSanitizer (CMAKE_BUILD_TYPE=
# Sanitize, defined in the top-level CMakeLists.txt) in their own build dir, runs them and ends
# with 'N passed, N failed'. Not part of CI or test.sh: a full build takes an hour at -j1.
#   scripts/sanitize.sh                  every gtest
#   scripts/sanitize.sh 'test_sim_.*'    only the gtests whose target name matches the regex
#   JOBS=2 scripts/sanitize.sh ...       make's -j (default 1: the machine is shared)
# Any sanitizer report stops the test (halt_on_error) and counts as a failure; each test's output
# is in $WS/logs/<test>.log. Suppressions (scripts/sanitize.supp) are for third-party libraries
# only, each with its reason.
set -uo pipefail
REPO="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
WS="${SANITIZE_WS:-$REPO/.build-sanitize}"
FILTER="${1:-.*}"
JOBS="${JOBS:-1}"
say() { printf '==> [sanitize] %s\n' "$*"; }

export PATH="/usr/bin:$PATH"
CCACHE=$(command -v ccache || true)
mkdir -p "$WS/logs"
bash "$REPO/scripts/stand_in_packages.sh" "$REPO" >/dev/null
say "configuring $WS (log $WS/logs/configure.log)"
catkin_make -C "$WS" --source "$REPO" -DPYTHON_EXECUTABLE=/usr/bin/python3 \
  -DCMAKE_BUILD_TYPE=Sanitize -DCATKIN_ENABLE_TESTING=ON \
  ${CCACHE:+-DCMAKE_CXX_COMPILER_LAUNCHER=ccache} cmake_check_build_system \
  >"$WS/logs/configure.log" 2>&1 || { tail -20 "$WS/logs/configure.log" >&2; exit 1; }

# The gtest targets: catkin_add_gtest's, named test_<area>_<what> (and tianracer_control's).
mapfile -t targets < <(make -C "$WS/build" help | sed -n 's/^\.\.\. \(test_[A-Za-z0-9_]*\)$/\1/p' |
  grep -E "^(${FILTER})$" | sort -u)
((${#targets[@]})) || { echo "ERROR [sanitize] no gtest target matches '$FILTER'" >&2; exit 1; }
say "building ${#targets[@]} gtest(s) with make -j$JOBS under nice -n 19 (log $WS/logs/build.log)"
nice -n 19 make -C "$WS/build" -j"$JOBS" "${targets[@]}" >"$WS/logs/build.log" 2>&1 ||
  { grep -m10 -E 'error|Error' "$WS/logs/build.log" >&2; exit 1; }

export ASAN_OPTIONS="halt_on_error=1:abort_on_error=0:detect_leaks=1:strict_string_checks=1:detect_stack_use_after_return=1${ASAN_OPTIONS:+:$ASAN_OPTIONS}"
export UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1${UBSAN_OPTIONS:+:$UBSAN_OPTIONS}"
export LSAN_OPTIONS="suppressions=$REPO/scripts/sanitize.supp:print_suppressions=0"
export ROS_HOSTNAME=localhost ROS_MASTER_URI="http://localhost:$((20000 + RANDOM % 20000))"
set +u
# shellcheck disable=SC1091
source "$WS/devel/setup.bash"
set -u
# Some gtests are rostest nodes (test_node_core, tianracer_control's test_nodes_wiring): they
# need a master, or they wait for one until the timeout. One roscore serves the whole run.
port="${ROS_MASTER_URI##*:}"
roscore -p "$port" >"$WS/logs/roscore.log" 2>&1 &
ROSCORE_PID=$!
trap 'kill "$ROSCORE_PID" 2>/dev/null; wait "$ROSCORE_PID" 2>/dev/null' EXIT
for _ in $(seq 100); do rostopic list >/dev/null 2>&1 && break; sleep 0.1; done
passed=0; failed=0; failures=()
for t in "${targets[@]}"; do
  bin=$(find "$WS/devel/lib" -type f -name "$t" -perm -u+x | head -1)
  [[ -n "$bin" ]] || { failed=$((failed + 1)); failures+=("$t (not built)"); continue; }
  pkg=$(basename "$(dirname "$bin")")
  dir="$REPO/$pkg/test"; [[ -d "$dir" ]] || dir="$REPO/$pkg"
  if (cd "$dir" && timeout 1800 "$bin") >"$WS/logs/$t.log" 2>&1; then
    passed=$((passed + 1))
  else
    failed=$((failed + 1)); failures+=("$t")
    grep -m3 -E 'ERROR: (Address|Leak)Sanitizer|runtime error|\[  FAILED  \]' "$WS/logs/$t.log" | sed "s/^/    $t: /" >&2
  fi
done
((failed)) && say "failed: ${failures[*]}"
echo "$passed passed, $failed failed"
((failed == 0))
