#!/usr/bin/env python3
"""display.launch gui:=false: joint_state_publisher publishes every movable joint of
robot_description, and robot_state_publisher turns them into TF for every link."""
import sys
import time
import unittest
import xml.etree.ElementTree as ET

import rospy
import rostest
import tf2_ros
from sensor_msgs.msg import JointState

MOVABLE = ("revolute", "continuous", "prismatic", "planar", "floating")


class DisplayTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node("test_display")
        urdf = ET.fromstring(rospy.get_param("/robot_description"))
        cls.links = [l.get("name") for l in urdf.findall("link")]
        joints = urdf.findall("joint")
        cls.movable = sorted(j.get("name") for j in joints if j.get("type") in MOVABLE)
        children = {j.find("child").get("link") for j in joints}
        cls.root = [l for l in cls.links if l not in children][0]

    def test_joint_states_cover_every_movable_joint(self):
        self.assertGreater(len(self.movable), 0)
        msg = rospy.wait_for_message("/joint_states", JointState, timeout=60)
        self.assertEqual(sorted(msg.name), self.movable)
        self.assertTrue(all(p == 0.0 for p in msg.position), msg.position)

    def test_tf_of_every_link(self):
        buf = tf2_ros.Buffer()
        tf2_ros.TransformListener(buf)
        missing = list(self.links)
        deadline = time.time() + 60
        while missing and time.time() < deadline:
            missing = [l for l in missing if not buf.can_transform(self.root, l, rospy.Time(0))]
            time.sleep(0.1)
        self.assertEqual(missing, [], "no TF from %s to %s" % (self.root, missing))


if __name__ == "__main__":
    rostest.rosrun("tianracer_description", "test_display", DisplayTest, sys.argv)
