#!/usr/bin/env bash
# The test command: installs what is missing, builds, runs every test (gtest, rostest, launch
# checks) and ends with a line 'N passed, N failed'. Exits non-zero on any failure.
#   ./test.sh            the suite
#   ./test.sh --load[=N] the suite with N CPU hogs alongside (stress-ng; default one per core),
#                        from the build of the tests to the last test: the load check
set -uo pipefail
REPO="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
WS="$REPO/.build"

HOGS=0
for arg in "$@"; do
  case "$arg" in
    --load) HOGS="$(nproc)" ;;
    --load=*) HOGS="${arg#--load=}" ;;
    *) echo "usage: $0 [--load[=N]]" >&2; exit 2 ;;
  esac
done
if ! [[ "$HOGS" =~ ^[0-9]+$ ]]; then
  echo "ERROR [test] --load=N: N must be a number of CPU hogs, got '$HOGS'" >&2
  exit 2
fi

bash "$REPO/scripts/setup.sh" || exit 1

export PATH="/usr/bin:$PATH"                  # ROS's Python first (TOOLCHAIN.md)
export ROS_HOSTNAME=localhost                 # nodes must reach each other in containers
unset ROS_IP
export ROS_MASTER_URI="http://localhost:$((20000 + RANDOM % 20000))"  # rostest picks its own
export ROS_LOG_DIR="$WS/ros_logs"
set +u  # ROS's setup scripts read unset variables
# shellcheck disable=SC1091
source "$WS/devel/setup.bash"
set -u

rm -rf "$WS/build/test_results"
if ((HOGS > 0)); then
  command -v stress-ng >/dev/null || { echo "ERROR [test] --load needs stress-ng (scripts/setup.sh installs it)" >&2; exit 1; }
  # Busy loops on every core, as on a machine shared with other work; ended with this script.
  stress-ng --cpu "$HOGS" --cpu-method loop --timeout 0 >/dev/null 2>&1 &
  hog=$!
  trap 'kill "$hog" 2>/dev/null; wait "$hog" 2>/dev/null' EXIT
  echo "==> [test] load check: $HOGS CPU hog(s) alongside (stress-ng --cpu $HOGS, pid $hog)"
fi
echo "==> [test] building and running all tests (log: $WS/logs/test.log)"
start=$(date +%s)
# The workspace's generator (make or Ninja: scripts/catkin_generator.sh), as setup.sh built it.
# shellcheck source=scripts/catkin_generator.sh
source "$REPO/scripts/catkin_generator.sh"
mapfile -t generator < <(catkin_generator "$WS")
# The test executables first (timed apart: on a fresh clone compiling them is much of the time).
catkin_make "${generator[@]}" -C "$WS" --source "$REPO" -DPYTHON_EXECUTABLE=/usr/bin/python3 -j"$(nproc)" \
  tests >"$WS/logs/test.log" 2>&1
build_rc=$?
built=$(date +%s)
# catkin_make run_tests exits 0 even when tests fail: the verdict comes from the result files.
if ((build_rc == 0)); then
  catkin_make "${generator[@]}" -C "$WS" --source "$REPO" -DPYTHON_EXECUTABLE=/usr/bin/python3 -j"$(nproc)" \
    run_tests >>"$WS/logs/test.log" 2>&1
  build_rc=$?
fi
end=$(date +%s)
echo "==> [test] ran in $((end - start)) s (tests built in $((built - start)) s, run in $((end - built)) s;" \
  "load average at the end: $(cut -d' ' -f1-3 /proc/loadavg))"

# The verdict comes from the result files: every test case counted once, failures named.
if ((build_rc != 0)); then
  echo "ERROR [test] building or running the tests failed (exit $build_rc):" >&2
  grep -E 'error|Error|\*\*\*|^FAILED: ' "$WS/logs/test.log" | head -30 >&2
fi
summary="$(/usr/bin/python3 "$REPO/scripts/count_test_results.py" "$WS/build/test_results")"
counted_rc=$?
echo "$summary" | sed '$d'
line="$(echo "$summary" | tail -n 1)"
if ((build_rc != 0)); then
  # A build failure is one more failure on the closing line.
  line="$(awk -F'[ ,]+' '{printf "%d passed, %d failed", $1, $3 + 1}' <<<"$line")"
fi
echo "$line"
((build_rc == 0 && counted_rc == 0))
