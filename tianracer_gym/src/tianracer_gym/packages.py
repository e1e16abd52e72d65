"""Where the shipped files are: ROS's package lookup (rospkg, ROS_PACKAGE_PATH), no master."""
import functools

import rospkg


@functools.lru_cache(maxsize=None)
def find_package(name):
    """The folder of ROS package `name`, or None."""
    try:
        return rospkg.RosPack().get_path(name)
    except rospkg.ResourceNotFound:
        return None


def shipped(package, *parts):
    """A file of a package; ValueError naming it when the package is not found."""
    import os
    root = find_package(package)
    if root is None:
        raise ValueError("ROS package '%s' not found on ROS_PACKAGE_PATH (source the workspace's "
                         "devel/setup.bash)" % package)
    return os.path.join(root, *parts)


def default_model():
    return shipped('tianracer_description', 'urdf', 'tianracer_description.xacro')


def default_control_config():
    return shipped('tianracer_control', 'config', 'tianracer_control.yaml')


def gym_model():
    """The tianracer with a small front camera (camera_small, 84 x 84)."""
    return shipped('tianracer_gym', 'models', 'tianracer_gym.xacro')
