"""What the bringup rostests read from the ROS graph: TF with who published each frame,
ground truth, scans, and /cmd_vel driving. Waits are on what the sim guarantees, in sim time
(tianracer_sim.sim_time)."""
import math
import threading
import unittest
import xml.etree.ElementTree as ET

import rospy
from geometry_msgs.msg import Twist
from nav_msgs.msg import Odometry
from sensor_msgs.msg import LaserScan
from tf2_msgs.msg import TFMessage

from tianracer_sim.rotation import yaw_from_quaternion as yaw_of  # noqa: F401 (for the tests)
from tianracer_sim.sim_time import Stream, drive_twist, lossless, sim_sleep


class TfRecorder(object):
    """Every transform on /tf and /tf_static: parent of each child frame, and the set of
    nodes (callerids) that published it."""

    def __init__(self):
        self.lock = threading.Lock()
        self.parent = {}
        self.publishers = {}
        self.dynamic, self.static = set(), set()
        lossless(rospy.Subscriber('/tf', TFMessage, self._on_tf, callback_args=False))
        lossless(rospy.Subscriber('/tf_static', TFMessage, self._on_tf, callback_args=True))

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


class CarTestCase(unittest.TestCase):
    """A rostest of one car under namespace `ns`: a node named `node_name`, a TfRecorder (tf),
    the car's ground truth (truth) and the streams of streams(), each an attribute; set up once
    each of those has a message and 1 s more of sim time has passed (every node's TF at least
    once)."""
    node_name = ns = None

    @classmethod
    def streams(cls):
        """{attribute: Stream}, made once the node is up."""
        return {}

    @classmethod
    def setUpClass(cls):
        rospy.init_node(cls.node_name)
        cls.tf = TfRecorder()
        cls.truth = truth(cls.ns)
        streams = cls.streams()
        for name, stream in streams.items():
            setattr(cls, name, stream)
        for stream in [cls.truth] + list(streams.values()):
            stream.wait_count(1)
        sim_sleep(1.0)


def urdf_links(param='/robot_description'):
    root = ET.fromstring(rospy.get_param(param))
    return sorted(link.get('name') for link in root.findall('link'))


def truth(ns):
    return Stream('%s/ground_truth/odom' % ns, Odometry)


def scans(topic):
    return Stream(topic, LaserScan)


def beam(scan, degrees):
    i = int(round((math.radians(degrees) - scan.angle_min) / scan.angle_increment))
    return scan.ranges[i]


def drive(topic, linear, angular, seconds):
    """Drives with Twist(linear, angular) on `topic` (once connected) for `seconds` of sim
    time, then publishes a stop. Returns (sim time at the start, at the stop)."""
    pub = rospy.Publisher(topic, Twist, queue_size=10)
    start = drive_twist(pub, seconds, linear, angular)
    pub.publish(Twist())
    return start, rospy.get_time()
