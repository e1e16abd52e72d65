"""Calls to the controller_manager services of the node's namespace, one function per
command, as ros_control's controller_manager_interface offers them (same names, same printed
lines): list_controllers, list_controller_types, load/unload_controller, start/stop_controller(s),
start_stop_controllers, reload_libraries."""
from __future__ import print_function

import rospy
from controller_manager_msgs.srv import (ListControllers, ListControllersRequest,
                                         ListControllerTypes, ListControllerTypesRequest,
                                         LoadController, ReloadControllerLibraries,
                                         SwitchController, SwitchControllerRequest,
                                         UnloadController)

SERVICE = 'controller_manager/'


def _proxy(name, srv_type):
    rospy.wait_for_service(SERVICE + name)
    return rospy.ServiceProxy(SERVICE + name, srv_type)


def list_controller_types():
    for t in _proxy('list_controller_types', ListControllerTypes)(ListControllerTypesRequest()).types:
        print(t)


def list_controllers():
    controllers = _proxy('list_controllers', ListControllers)(ListControllersRequest()).controller
    if not controllers:
        print('No controllers are loaded in mechanism control')
        return
    for c in controllers:
        interfaces = sorted({r.hardware_interface for r in c.claimed_resources})
        print("'%s' - '%s' ( %s )" % (c.name, '+'.join(interfaces), c.state))


def load_controller(name):
    ok = _proxy('load_controller', LoadController)(name).ok
    print(("Loaded '%s'" if ok else "Error when loading '%s'") % name)
    return ok


def unload_controller(name):
    ok = _proxy('unload_controller', UnloadController)(name).ok
    print(("Unloaded '%s' successfully" if ok else "Error when unloading '%s'") % name)
    return ok


def start_stop_controllers(start_controllers=(), stop_controllers=()):
    start, stop = list(start_controllers), list(stop_controllers)
    switch = _proxy('switch_controller', SwitchController)
    ok = switch(SwitchControllerRequest(start, stop, SwitchControllerRequest.STRICT, False, 0.0)).ok
    if ok:
        if start:
            print('Started {} successfully'.format(start))
        if stop:
            print('Stopped {} successfully'.format(stop))
    else:
        print('Error when starting {} and stopping {}'.format(start, stop))
    return ok


def start_controller(name):
    return start_stop_controllers(start_controllers=[name])


def start_controllers(names):
    return start_stop_controllers(start_controllers=names)


def stop_controller(name):
    return start_stop_controllers(stop_controllers=[name])


def stop_controllers(names):
    return start_stop_controllers(stop_controllers=names)


def reload_libraries(force_kill, restore=False):
    """Asks the manager to reload its controller libraries (with force_kill: stopping and
    unloading every controller first); restore loads and restarts what was there before."""
    print('Restore: ' + str(restore))
    before = _proxy('list_controllers', ListControllers)(ListControllersRequest()).controller \
        if restore else []
    ok = _proxy('reload_controller_libraries', ReloadControllerLibraries)(force_kill).ok
    print('Successfully reloaded libraries' if ok else
          'Failed to reload libraries. Do you still have controllers loaded?')
    if restore:
        load = _proxy('load_controller', LoadController)
        for c in before:
            load(c.name)
        running = [c.name for c in before if c.state == 'running']
        _proxy('switch_controller', SwitchController)(
            SwitchControllerRequest(running, [], SwitchControllerRequest.BEST_EFFORT, False, 0.0))
        print('Controllers restored to original state')
    return ok
