#!/usr/bin/env bash
# Builds the gtests with AddressSanitizer and UndefinedBehaviorSanitizer (CMAKE_BUILD_TYPE=
# Sanitize, defined in the top-level CMakeLists.txt) in their own build dir, runs them and ends
# with 'N passed, N failed'. Not part of CI or test.sh: a full build takes an hour at -j1.
#   scripts/sanitize.sh                  every gtest
#   scripts/sanitize.sh 'test_sim_.*'    only the gtests whose target name matches the regex
#   JOBS=2 scripts/sanitize.sh ...       make's -j (default 1: the machine is shared)
#   TIANRACER_UNITY=ON scripts/sanitize.sh   unity batches (fewer compiles; default AUTO: off with ccache)
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
  -DCMAKE_BUILD_TYPE=Sanitize -DCATKIN_ENABLE_TESTING=ON -DTIANRACER_UNITY="${TIANRACER_UNITY:-AUTO}" \
  ${CCACHE:+-DCMAKE_CXX_COMPILER_LAUNCHER=ccache} cmake_check_build_system \
  >"$WS/logs/configure.log" 2>&1 || { tail -20 "$WS/logs/configure.log" >&2; exit 1; }

# The gtest targets: catkin_add_gtest's, named test_<area>_<what> (and tianracer_control's).
mapfile -t all_targets < <(make -C "$WS/build" help | sed -n 's/^\.\.\. \([A-Za-z0-9_]*\)$/\1/p' | sort -u)
mapfile -t targets < <(printf '%s\n' "${all_targets[@]}" | grep -E '^test_' | grep -E "^(${FILTER})$")
((${#targets[@]})) || { echo "ERROR [sanitize] no gtest target matches '$FILTER'" >&2; exit 1; }

# A gtest that is a rostest node (a <test type="..."> of a .test file) runs through its .test
# files: they load the parameters and start the nodes it talks to. Those nodes (<node type>) are
# built here too, so they run sanitized as well.
rostest_files() {  # the .test files whose <test> runs the gtest $1
  grep -rlE --include='*.test' "<test [^>]*type=\"$1\"" "$REPO" 2>/dev/null | grep -v '/\.build' | sort
}
nodes=()
for t in "${targets[@]}"; do
  while read -r f; do
    [[ -n "$f" ]] || continue
    mapfile -t -O "${#nodes[@]}" nodes < <(sed -n 's/.*<node [^>]*type="\([A-Za-z0-9_]*\)".*/\1/p' "$f" |
      grep -Fx -f <(printf '%s\n' "${all_targets[@]}"))
  done < <(rostest_files "$t")
done
mapfile -t nodes < <(printf '%s\n' "${nodes[@]}" | sed '/^$/d' | sort -u)
say "building ${#targets[@]} gtest(s) and ${#nodes[@]} node(s) they test with make -j$JOBS under nice -n 19 (log $WS/logs/build.log)"
nice -n 19 make -C "$WS/build" -j"$JOBS" "${targets[@]}" "${nodes[@]}" >"$WS/logs/build.log" 2>&1 ||
  { grep -m10 -E 'error|Error' "$WS/logs/build.log" >&2; exit 1; }

export ASAN_OPTIONS="halt_on_error=1:abort_on_error=0:detect_leaks=1:strict_string_checks=1:detect_stack_use_after_return=1${ASAN_OPTIONS:+:$ASAN_OPTIONS}"
export UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1${UBSAN_OPTIONS:+:$UBSAN_OPTIONS}"
export LSAN_OPTIONS="suppressions=$REPO/scripts/sanitize.supp:print_suppressions=0"
export ROS_HOSTNAME=localhost ROS_MASTER_URI="http://localhost:$((20000 + RANDOM % 20000))"
set +u
# shellcheck disable=SC1091
source "$WS/devel/setup.bash"
set -u
# The gtests that are not rostest nodes need no master; one roscore serves the run anyway (a
# gtest that talks to ROS without a .test file). rostest starts a master of its own.
port="${ROS_MASTER_URI##*:}"
roscore -p "$port" >"$WS/logs/roscore.log" 2>&1 &
ROSCORE_PID=$!
trap 'kill "$ROSCORE_PID" 2>/dev/null; wait "$ROSCORE_PID" 2>/dev/null' EXIT
for _ in $(seq 100); do rostopic list >/dev/null 2>&1 && break; sleep 0.1; done
passed=0; failed=0; failures=()
for t in "${targets[@]}"; do
  bin=$(find "$WS/devel/lib" -type f -name "$t" -perm -u+x | head -1)
  [[ -n "$bin" ]] || { failed=$((failed + 1)); failures+=("$t (not built)"); continue; }
  # A build that is not sanitized (a stale cache; the top-level CMakeLists.txt) is not a pass.
  # (grep reads all of ldd's output: with -q it would stop early, ldd would die of SIGPIPE and
  # pipefail would count a sanitized binary as not sanitized, as 9 of 115 were once.)
  if ! ldd "$bin" | grep libasan >/dev/null; then
    failed=$((failed + 1)); failures+=("$t (not built with AddressSanitizer)"); continue
  fi
  pkg=$(basename "$(dirname "$bin")")
  dir="$REPO/$pkg/test"; [[ -d "$dir" ]] || dir="$REPO/$pkg"
  mapfile -t launch_files < <(rostest_files "$t")
  run() {
    if ((${#launch_files[@]})); then
      local f
      for f in "${launch_files[@]}"; do
        echo "== rostest $f"
        # rostest exits non-zero when a test fails or a required node dies (a sanitizer
        # report stops it: halt_on_error); the nodes' own output is in ROS_LOG_DIR.
        ROS_LOG_DIR="$WS/logs/ros_$t" timeout 1800 rostest --text "$f" || return 1
      done
    else
      (cd "$dir" && timeout 1800 "$bin")
    fi
  }
  # A report after the last test case (LeakSanitizer runs at exit) leaves gtest's XML saying
  # "passed", and rostest counts the XML: a report in the test's output (or its nodes' logs)
  # fails it whatever the exit status says.
  rm -rf "$WS/logs/ros_$t"  # this run's node logs only
  if run >"$WS/logs/$t.log" 2>&1 &&
     ! grep -rqE 'ERROR: (Address|Leak)Sanitizer|runtime error:' "$WS/logs/$t.log" \
         $( [[ -d "$WS/logs/ros_$t" ]] && echo "$WS/logs/ros_$t" ); then
    passed=$((passed + 1))
  else
    failed=$((failed + 1)); failures+=("$t")
    grep -m3 -E 'ERROR: (Address|Leak)Sanitizer|runtime error|\[  FAILED  \]' "$WS/logs/$t.log" | sed "s/^/    $t: /" >&2
  fi
done
((failed)) && say "failed: ${failures[*]}"
echo "$passed passed, $failed failed"
((failed == 0))
