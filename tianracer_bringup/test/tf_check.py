"""What the bringup rostests read from the ROS graph: TF with who published each frame,
ground truth, scans, and /cmd_vel driving. Waits are in sim time (rospy.sleep on /clock),
bounded in wall time so that a wedged sim fails instead of hanging."""
import math
import threading
import time
import xml.etree.ElementTree as ET

import rospy
from geometry_msgs.msg import Twist
from nav_msgs.msg import Odometry
from sensor_msgs.msg import LaserScan
from tf2_msgs.msg import TFMessage

from tianracer_bringup.ros_session import yaw_from_quaternion


yaw_of = yaw_from_quaternion


def wall_wait(predicate, wall_timeout):
    end = time.time() + wall_timeout
    while time.time() < end and not rospy.is_shutdown():
        if predicate():
            return True
        time.sleep(0.05)
    return predicate()


def sim_sleep(seconds, wall_timeout=120.0):
    """Sleep `seconds` of sim time; False when the sim clock did not get there in time."""
    target = rospy.get_time() + seconds
    return wall_wait(lambda: rospy.get_time() >= target, wall_timeout)


class TfRecorder(object):
    """Every transform on /tf and /tf_static: parent of each child frame, and the set of
    nodes (callerids) that published it."""

    def __init__(self):
        self.lock = threading.Lock()
        self.parent = {}
        self.publishers = {}
        self.dynamic, self.static = set(), set()
        rospy.Subscriber('/tf', TFMessage, self._on_tf, callback_args=False, queue_size=1000)
        rospy.Subscriber('/tf_static', TFMessage, self._on_tf, callback_args=True,
                         queue_size=1000)

    def _on_tf(self, msg, static):
        caller = msg._connection_header.get('callerid', '?')
        with self.lock:
            for t in msg.transforms:
                child = t.child_frame_id
                self.parent.setdefault(child, set()).add(t.header.frame_id)
                self.publishers.setdefault(child, set()).add(caller)
                (self.static if static else self.dynamic).add(child)

    def chain(self, frame, root):
        """Frames from `frame` up to `root` (inclusive), or None when the chain breaks."""
        with self.lock:
            out, seen = [frame], set()
            while out[-1] != root:
                parents = self.parent.get(out[-1])
                if not parents or len(parents) != 1 or out[-1] in seen:
                    return None
                seen.add(out[-1])
                out.append(next(iter(parents)))
            return out

    def duplicates(self):
        """Child frames published by more than one node, or with more than one parent, or on
        both /tf and /tf_static."""
        with self.lock:
            bad = {}
            for child, pubs in self.publishers.items():
                if len(pubs) > 1 or len(self.parent[child]) > 1 or (
                        child in self.static and child in self.dynamic):
                    bad[child] = (sorted(pubs), sorted(self.parent[child]))
            return bad


def urdf_links(param='/robot_description'):
    root = ET.fromstring(rospy.get_param(param))
    return sorted(link.get('name') for link in root.findall('link'))


class Latest(object):
    """The latest message and a count, from a topic."""

    def __init__(self, topic, cls):
        self.msg, self.count, self.all = None, 0, []
        self.lock = threading.Lock()
        rospy.Subscriber(topic, cls, self._cb, queue_size=100)

    def _cb(self, msg):
        with self.lock:
            self.msg = msg
            self.count += 1
            self.all.append(msg)


def truth(ns):
    return Latest('%s/ground_truth/odom' % ns, Odometry)


def scans(topic):
    return Latest(topic, LaserScan)


def beam(scan, degrees):
    i = int(round((math.radians(degrees) - scan.angle_min) / scan.angle_increment))
    return scan.ranges[i]


def drive(topic, linear, angular, seconds):
    """Publishes the Twist at 20 Hz (sim time) for `seconds` of sim time, then a stop."""
    pub = rospy.Publisher(topic, Twist, queue_size=10)
    wall_wait(lambda: pub.get_num_connections() > 0, 30.0)
    cmd = Twist()
    cmd.linear.x, cmd.angular.z = linear, angular
    end = rospy.get_time() + seconds
    wall_end = time.time() + 120.0
    while rospy.get_time() < end and time.time() < wall_end and not rospy.is_shutdown():
        pub.publish(cmd)
        sim_sleep(0.05)
    pub.publish(Twist())
    return pub
