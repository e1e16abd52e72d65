#!/usr/bin/env bash
# The test command: installs what is missing, builds, runs every test (gtest, rostest, launch
# checks) and ends with a line 'N passed, N failed'. Exits non-zero on any failure.
set -uo pipefail
REPO="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
WS="$REPO/.build"

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
echo "==> [test] building and running all tests (log: $WS/logs/test.log)"
start=$(date +%s)
# catkin_make run_tests exits 0 even when tests fail: the verdict comes from the result files.
catkin_make -C "$WS" --source "$REPO" -DPYTHON_EXECUTABLE=/usr/bin/python3 -j"$(nproc)" \
  run_tests >"$WS/logs/test.log" 2>&1
build_rc=$?
echo "==> [test] ran in $(( $(date +%s) - start )) s"

# Per-file verdicts, then the totals.
catkin_test_results --all "$WS/build/test_results" | grep -vE '^Skipping' | sed 's/^/    /'
summary="$(catkin_test_results "$WS/build/test_results" | grep '^Summary:')"
total=$(sed -E 's/Summary: ([0-9]+) tests.*/\1/' <<<"$summary")
errors=$(sed -E 's/.* ([0-9]+) errors.*/\1/' <<<"$summary")
failures=$(sed -E 's/.* ([0-9]+) failures.*/\1/' <<<"$summary")
skipped=$(sed -E 's/.* ([0-9]+) skipped.*/\1/' <<<"$summary")
total=${total:-0}; errors=${errors:-0}; failures=${failures:-0}; skipped=${skipped:-0}
failed=$((errors + failures))
passed=$((total - failed - skipped))
if ((build_rc != 0)); then
  echo "ERROR [test] building or running the tests failed (exit $build_rc):" >&2
  grep -E 'error|Error|\*\*\*' "$WS/logs/test.log" | head -30 >&2
  failed=$((failed + 1))
fi
if ((total == 0)); then
  echo "ERROR [test] no test results were produced" >&2
  failed=$((failed + 1))
fi
if ((skipped)); then
  echo "$passed passed, $failed failed, $skipped skipped"
else
  echo "$passed passed, $failed failed"
fi
((failed == 0))
