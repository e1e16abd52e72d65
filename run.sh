#!/usr/bin/env bash
# The run command: installs what is missing, builds, and runs the main job.
# For now the main job loads the tianracer model exactly as the simulator does and prints
# its link/joint tree, transmissions, plugins and sensors (topics and rates).
set -euo pipefail
REPO="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"

bash "$REPO/scripts/setup.sh"

export PATH="/usr/bin:$PATH"
set +u  # ROS's setup scripts read unset variables
# shellcheck disable=SC1091
source "$REPO/.build/devel/setup.bash"
set -u
echo "==> [run] tianracer model as the simulator loads it"
exec rosrun tianracer_sim model_info "$@"
