"""What the controller_manager rostests share (test_controller_manager.py, test_gazebo_user.py):
the tianracer's controllers in /tianracer, a test case that reads /rosout and commands them, and
spawners started by the test itself.

/rosout keeps nothing for a late subscriber: a node whose errors a test checks is started by the
test once its /rosout subscription is connected to the nodes that matter, and a spawner's own
errors are read from its output (run_spawner), not from /rosout.
"""
import contextlib
import os
import subprocess
import tempfile
import threading
import time
import unittest

import rospy
from controller_manager_msgs.srv import (ListControllers, LoadController, SwitchController,
                                         SwitchControllerRequest, UnloadController)
from nav_msgs.msg import Odometry
from rosgraph_msgs.msg import Log
from sensor_msgs.msg import JointState
from std_msgs.msg import Float64

NS = '/tianracer'
CONTROLLERS = ['joint_state_controller', 'left_rear_wheel_velocity_controller',
               'right_rear_wheel_velocity_controller', 'left_steering_hinge_position_controller',
               'right_steering_hinge_position_controller']
LEFT, RIGHT = CONTROLLERS[1], CONTROLLERS[2]
STRICT, BEST_EFFORT = SwitchControllerRequest.STRICT, SwitchControllerRequest.BEST_EFFORT


def wall_wait(predicate, timeout):
    """True once `predicate` holds, False when it still does not after `timeout` s of wall
    time (a bound on a wedged node, never a measurement)."""
    end = time.time() + timeout
    while time.time() < end and not rospy.is_shutdown():
        if predicate():
            return True
        time.sleep(0.05)
    return predicate()


def sim_sleep(seconds):
    target = rospy.get_time() + seconds
    assert wall_wait(lambda: rospy.get_time() >= target, 120.0), 'sim time stood still'


class Latest(object):
    """The last message of a topic."""

    def __init__(self, topic, cls):
        self.msg = None
        rospy.Subscriber(topic, cls, self._cb, queue_size=10)

    def _cb(self, msg):
        self.msg = msg


class Output(object):
    """What a process printed so far (stdout and stderr)."""

    def __init__(self, file):
        self._file = file

    def text(self):
        self._file.seek(0)
        return self._file.read()


@contextlib.contextmanager
def run_spawner(args, ns, name):
    """controller_manager's spawner in `ns` with `args`, as a node named `name`; yields its
    Output, and interrupts it (as roslaunch does on shutdown) on leaving."""
    with tempfile.TemporaryFile('w+') as out:
        spawner = subprocess.Popen(['rosrun', 'controller_manager', 'spawner'] + args +
                                   ['__name:=' + name], env=dict(os.environ, ROS_NAMESPACE=ns),
                                   stdout=out, stderr=subprocess.STDOUT)
        try:
            yield Output(out)
        finally:
            if spawner.poll() is None:
                spawner.send_signal(2)  # SIGINT
            spawner.wait(60)


class ControllerTestCase(unittest.TestCase):
    """The robot in NS: its controller_manager services, command publishers, joint states,
    ground truth, and every /rosout message since the test started."""

    @classmethod
    def start(cls, node_name):
        rospy.init_node(node_name)
        cls.logs, cls.lock = [], threading.Lock()
        cls.rosout = rospy.Subscriber('/rosout', Log, cls.on_log, queue_size=1000)
        cls.truth = Latest(NS + '/ground_truth/odom', Odometry)
        cls.joints = Latest(NS + '/joint_states', JointState)
        cm = NS + '/controller_manager/'
        rospy.wait_for_service(cm + 'list_controllers', timeout=240.0)
        cls.list = rospy.ServiceProxy(cm + 'list_controllers', ListControllers)
        cls.load = rospy.ServiceProxy(cm + 'load_controller', LoadController)
        cls.unload = rospy.ServiceProxy(cm + 'unload_controller', UnloadController)
        cls.switch = rospy.ServiceProxy(cm + 'switch_controller', SwitchController)
        cls.pubs = {name: rospy.Publisher('%s/%s/command' % (NS, name), Float64, queue_size=1)
                    for name in CONTROLLERS[1:]}

    @classmethod
    def on_log(cls, msg):
        with cls.lock:
            cls.logs.append((msg.name, msg.level, msg.msg))

    def hears(self, node):
        """True once this test's /rosout subscription is connected to `node`."""
        return node in [getattr(c, 'callerid_pub', None) for c in self.rosout.impl.connections]

    def said(self, level=Log.DEBUG):
        with self.lock:
            return [(name, text) for name, lvl, text in self.logs if lvl >= level]

    def errors_since(self, n):
        with self.lock:
            return [text for name, level, text in self.logs[n:] if level >= Log.ERROR]

    def log_count(self):
        with self.lock:
            return len(self.logs)

    def states(self):
        return {c.name: c.state for c in self.list().controller}

    def command(self, values, seconds):
        """Publishes the commands ({controller: value}) at 20 Hz for `seconds` of sim time."""
        end = rospy.get_time() + seconds
        while rospy.get_time() < end and not rospy.is_shutdown():
            for name, value in values.items():
                self.pubs[name].publish(Float64(value))
            sim_sleep(0.05)

    def assert_stopped_left_wheel_goes_then_follows_again(self):
        """With the left wheel's controller stopped: the right wheel holds 0, the left one is
        commanded hard but no longer follows; started again, it follows."""
        self.command({LEFT: 30.0, RIGHT: 0.0}, 1.0)
        self.assertLess(abs(self.wheel_velocity('left_rear_wheel_joint')), 5.0)
        self.assertLess(abs(self.wheel_velocity('right_rear_wheel_joint')), 0.5)
        # Started again, it follows.
        self.assertTrue(self.switch([LEFT], [], STRICT, False, 0.0).ok)
        self.command({LEFT: 10.0, RIGHT: 10.0}, 1.0)
        self.assertAlmostEqual(self.wheel_velocity('left_rear_wheel_joint'), 10.0, delta=1.0)
        self.command({LEFT: 0.0, RIGHT: 0.0}, 0.5)

    def wheel_velocity(self, joint):
        msg = self.joints.msg
        return msg.velocity[msg.name.index(joint)]
