"""Shared set-up of the tianracer_gym tests: the workspace's packages on ROS_PACKAGE_PATH."""
import os

REPO = os.path.abspath(os.path.join(os.path.dirname(__file__), '..', '..'))
if REPO not in os.environ.get('ROS_PACKAGE_PATH', '').split(':'):
    os.environ['ROS_PACKAGE_PATH'] = REPO + ':' + os.environ.get('ROS_PACKAGE_PATH', '')

import numpy as np  # noqa: E402


def same(a, b):
    """Observation dicts equal bit for bit (NaN included)."""
    if set(a) != set(b):
        return False
    return all(np.asarray(a[k]).tobytes() == np.asarray(b[k]).tobytes() for k in a)
