#!/usr/bin/env bash
# The run command: installs what is missing, builds, and runs the main job.
# The main job: the model summary as the simulator loads it, then the headless demo: the
# car drives a lap of the racetrack through /cmd_vel; pictures, a CSV and a summary go to
# ./output (or the folder given with --out).
set -euo pipefail
REPO="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"

# --demo: a new workspace is built without debug info (same code, a third less compile time)
# and without what the demo does not run (the Python bindings, benchmarks and corpus tools)
bash "$REPO/scripts/setup.sh" --demo

export PATH="/usr/bin:$PATH"
set +u  # ROS's setup scripts read unset variables
# shellcheck disable=SC1091
source "$REPO/.build/devel/setup.bash"
set -u
echo "==> [run] the tianracer as the simulator loads it"
rosrun tianracer_sim model_info
echo "==> [run] headless demo: one lap of the racetrack"
exec rosrun tianracer_bringup demo --out "$REPO/output" "$@"
