"""spawner: loads the named controllers through <ns>/controller_manager/load_controller and
starts them with one STRICT switch_controller (--stopped: loads only); when it is shut down
(roslaunch ending, rosnode kill) it stops and unloads what it loaded. The arguments and the
behaviour are ros_control's spawner's (noetic-devel controller_manager/scripts/spawner):

  spawner [--stopped] [--wait-for TOPIC] [--namespace NS] [--timeout T | --no-timeout]
          controller [controller ...]

A name that is an existing file is a controller YAML: it is loaded onto the parameter server
in the spawner's namespace and each of its top-level keys is a controller to load. The
services are waited for up to --timeout s (default 30; <= 0 or --no-timeout: forever); with
/use_sim_time and no /clock yet the wait goes on. A controller that fails to load is logged
and left out; the others are still started."""
import argparse
import os
import threading
import time

import rosparam
import rospy
from controller_manager_msgs.srv import (LoadController, SwitchController,
                                         SwitchControllerRequest, UnloadController)
from std_msgs.msg import Bool


def parse_args(argv):
    p = argparse.ArgumentParser(prog='spawner', description='Controller spawner')
    p.add_argument('--stopped', action='store_true',
                   help='loads controllers, but does not start them')
    p.add_argument('--wait-for', metavar='topic',
                   help='does not load or start controllers until it hears "True" on a topic (Bool)')
    p.add_argument('--namespace', metavar='ns',
                   help='namespace of the controller_manager services')
    p.add_argument('--timeout', metavar='T', type=float, default=30,
                   help='how long to wait for controller_manager services when starting up [s] '
                        '(default: 30). <=0 waits indefinitely.')
    p.add_argument('--no-timeout', action='store_true',
                   help='wait for controller_manager services indefinitely (same as `--timeout 0`)')
    p.add_argument('--shutdown-timeout', help='DEPRECATED: this argument has no effect.')
    p.add_argument('controllers', metavar='controller', nargs='+', help='controllers to load')
    return p.parse_args(argv)


def service_names(namespace):
    """load, switch and unload service names under `namespace` (relative: the node's)."""
    prefix = (namespace.rstrip('/') + '/') if namespace else ''
    return tuple(prefix + 'controller_manager/' + s
                 for s in ('load_controller', 'switch_controller', 'unload_controller'))


def controller_names(entries, upload=None):
    """The controllers named by the arguments: a name, or a YAML file whose top-level keys are
    controllers (`upload(params)` puts the file's content on the parameter server)."""
    names = []
    for entry in entries:
        if not os.path.isfile(entry):
            names.append(entry)
            continue
        for params, _ in rosparam.load_file(entry):
            if not isinstance(params, dict):
                raise ValueError('%s: a controller YAML maps controller names to their '
                                 'parameters' % entry)
            if upload:
                upload(params)
            names.extend(params.keys())
    return names


class Spawner:
    def __init__(self, args):
        self.args = args
        self.timeout = None if args.no_timeout or args.timeout <= 0 else args.timeout
        self.load_name, self.switch_name, self.unload_name = service_names(args.namespace or '')
        self.loaded = []

    def wait_for_services(self):
        """True once the three services are there; False (after a warning) on timeout."""
        while not rospy.is_shutdown():
            try:
                for name in (self.load_name, self.switch_name, self.unload_name):
                    rospy.loginfo('Controller Spawner: Waiting for service ' + name)
                    rospy.wait_for_service(name, timeout=self.timeout)
                return True
            except rospy.ROSException:
                if rospy.get_param('/use_sim_time', False) and rospy.get_rostime().is_zero():
                    rospy.loginfo('Waiting for /clock to be available...')
                    continue
                rospy.logwarn("Controller Spawner couldn't find the expected controller_manager "
                              "ROS interface.")
                return False
        return False

    def wait_for_topic(self):
        """Blocks until `True` is heard on --wait-for; False if the node shuts down first."""
        heard = []
        rospy.Subscriber(self.args.wait_for, Bool, lambda msg: heard.append(msg.data))
        start, warned = time.time(), False
        while not (heard and heard[-1]):
            if rospy.is_shutdown():
                return False
            if not heard and not warned and self.timeout and time.time() - start > self.timeout:
                rospy.logwarn('Controller Spawner hasn\'t heard anything from its "wait for" '
                              'topic (%s)' % self.args.wait_for)
                warned = True
            time.sleep(0.01)
        return True

    def load_and_start(self, names):
        load = rospy.ServiceProxy(self.load_name, LoadController)
        for name in names:
            rospy.loginfo('Loading controller: ' + name)
            if load(name).ok:
                self.loaded.append(name)
            else:
                time.sleep(1)  # let the manager's error reach the log first
                rospy.logerr('Failed to load %s' % name)
        rospy.loginfo('Controller Spawner: Loaded controllers: %s' % ', '.join(self.loaded))
        if rospy.is_shutdown() or self.args.stopped:
            return
        switch = rospy.ServiceProxy(self.switch_name, SwitchController)
        if switch(self.loaded, [], SwitchControllerRequest.STRICT, False, 0.0).ok:
            rospy.loginfo('Started controllers: %s' % ', '.join(self.loaded))
        else:
            rospy.logerr('Failed to start controllers: %s' % ', '.join(self.loaded))

    def shutdown(self):
        """Stops (STRICT) and unloads, last loaded first, what this spawner loaded."""
        rospy.loginfo('Shutting down spawner. Stopping and unloading controllers...')
        if not self.loaded:
            return
        try:
            switch = rospy.ServiceProxy(self.switch_name, SwitchController)
            unload = rospy.ServiceProxy(self.unload_name, UnloadController)
            rospy.loginfo('Stopping all controllers...')
            switch([], self.loaded, SwitchControllerRequest.STRICT, False, 0.0)
            rospy.loginfo('Unloading all loaded controllers...')
            for name in reversed(self.loaded):
                rospy.loginfo('Trying to unload %s' % name)
                unload(name)
                rospy.loginfo('Succeeded in unloading %s' % name)
        except (rospy.ServiceException, rospy.ROSException) as e:
            rospy.logwarn('Controller Spawner error while taking down controllers: %s' % e)


def main(argv=None):
    args = parse_args(rospy.myargv()[1:] if argv is None else argv)
    rospy.init_node('spawner', anonymous=True)
    if args.shutdown_timeout is not None:
        rospy.logwarn('DEPRECATION warning: --shutdown-timeout has no effect.')
    spawner = Spawner(args)
    failure = []

    def work():
        try:
            if not spawner.wait_for_services():
                rospy.signal_shutdown('no controller_manager')  # exits, as ros_control's
                return
            if args.wait_for and not spawner.wait_for_topic():
                return
            rospy.on_shutdown(spawner.shutdown)
            ns = rospy.get_namespace()
            names = controller_names(args.controllers,
                                     lambda params: rosparam.upload_params(ns, params))
            spawner.load_and_start(names)
        except (rospy.ROSInterruptException, rospy.ServiceException) as e:
            if not rospy.is_shutdown():
                failure.append(e)
                rospy.signal_shutdown(str(e))
        except Exception as e:  # a bad YAML file: reported as the error it is, exit code 1
            failure.append(e)
            rospy.signal_shutdown(str(e))

    # The work runs off the main thread, which only waits. rospy's SIGINT handler (Ctrl-C, or
    # roslaunch ending) runs the node's shutdown in the main thread, inside whatever that thread
    # was doing. When it was an XML-RPC call to the master (every log line reads a cached
    # parameter that way), the shutdown's own call to the master waited on the same lock
    # (rospy/core.py, _LockedServerProxy) and the spawner hung for a minute.
    threading.Thread(target=work, name='spawner', daemon=True).start()
    rospy.spin()
    if failure:
        raise failure[0]
    return 0
