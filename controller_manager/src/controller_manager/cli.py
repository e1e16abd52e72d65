"""The controller_manager command (ros_control's): one command and controller names, for the
controller manager of the node's namespace (ROS_NAMESPACE=/robot or __ns:=/robot)."""
from __future__ import print_function

import sys

import rospy

from controller_manager import controller_manager_interface as cm

USAGE = '''Commands:
    load <name>          - Load the controller named <name>
    unload <name>        - Unload the controller named <name>
    start <name>         - Start the controller named <name>
    stop <name>          - Stop the controller named <name>
    spawn <name>         - Load and start the controller named <name>
    kill <name>          - Stop and unload the controller named <name>
    list                 - List active controllers
    list-types           - List controller Types
    reload-libraries     - Reloads all plugin controller libraries'''


def run(args):
    """args: [command, name...]. Returns the exit status (1 for an unknown command, or when a
    command on a controller failed)."""
    if not args:
        print(USAGE)
        return 0
    command, names = args[0], args[1:]
    ok = True
    if command in ('lt', 'list-types'):
        cm.list_controller_types()
    elif command in ('lc', 'list'):
        cm.list_controllers()
    elif command == 'reload-libraries':
        ok = cm.reload_libraries(True, restore='--restore' in names)
    elif command == 'load':
        ok = all([cm.load_controller(n) for n in names])
    elif command == 'unload':
        ok = all([cm.unload_controller(n) for n in names])
    elif command == 'start':
        ok = all([cm.start_controller(n) for n in names])
    elif command == 'stop':
        ok = all([cm.stop_controller(n) for n in names])
    elif command in ('sp', 'spawn'):
        # As ros_control's script: every load, then every start, each on its own, so that one
        # controller that cannot load (an unknown type) does not keep the others from starting.
        loaded = [cm.load_controller(n) for n in names]
        started = [cm.start_controller(n) for n in names]
        ok = all(loaded) and all(started)
    elif command in ('kl', 'kill'):
        stopped = [cm.stop_controller(n) for n in names]
        unloaded = [cm.unload_controller(n) for n in names]
        ok = all(stopped) and all(unloaded)
    else:
        print(USAGE)
        return 1
    return 0 if ok else 1


def main():
    args = rospy.myargv()[1:]
    rospy.init_node('controller_manager', anonymous=True)
    try:
        return run(args)
    except rospy.ROSInterruptException:
        return 1
