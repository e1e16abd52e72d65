#!/usr/bin/env python3
"""rostest: two_cars.launch.

- Two disjoint topic sets: what the simulator and each car's nodes publish and subscribe for
  car 2 is car 1's set moved under /tianracer_02 (/tianracer/x -> /tianracer_02/x,
  /scan -> /tianracer_02/scan); nothing but /clock, /tf, /tf_static, /diagnostics and /rosout is
  shared.
- Frames: car 2's links, lidar frame and odom are prefixed tianracer_02/ and chain up to
  tianracer_02/odom; car 1 keeps the single car's frames; no duplicate publishers.
- Each car's lidar sees the other: car 2 stands 0.4 m to car 1's left, so car 1's beam at
  +90 deg ends on car 2's lidar head (0.4 m less its 0.021 m radius) instead of the wall
  0.7 m away, and car 2's beam at -90 deg on car 1's.
- /tianracer_02/cmd_vel drives car 2 only.
- Car 1's depth camera sees car 2 once car 2 is moved 1 m ahead of it (set_model_state): the
  centre pixel reads the back of the other car's depth camera bar, 0.975 m away, instead of the
  far track.
"""
import math
import os
import sys
import unittest

import numpy as np
import rosgraph
import rospy
import rostest
from geometry_msgs.msg import Pose, Twist
from sensor_msgs.msg import Image
from gazebo_msgs.msg import ModelState
from gazebo_msgs.srv import SetModelState
from tianracer_sim.sim_time import Stream, sim_sleep

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import tf_check  # noqa: E402

CAR2 = '/tianracer_02'
# World-wide topics: one for both cars (the Gazebo interface's are the world's, as in Gazebo).
SHARED = {'/clock', '/tf', '/tf_static', '/diagnostics', '/rosout', '/gazebo/model_states',
          '/gazebo/link_states', '/gazebo/set_model_state', '/gazebo/set_link_state',
          '/gazebo/parameter_descriptions', '/gazebo/parameter_updates'}
CAR1_NODES = {'/tianracer_sim', '/robot_state_publisher', '/cmd_vel_node', '/wheel_odometry_node'}


def to_car2(topic):
    """The name car 2 uses for car 1's `topic`."""
    if topic.startswith('/tianracer/'):
        return CAR2 + topic[len('/tianracer'):]
    return CAR2 + topic


class TwoCars(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node('test_two_cars')
        cls.tf = tf_check.TfRecorder()
        cls.truth1, cls.truth2 = tf_check.truth('/tianracer'), tf_check.truth(CAR2)
        cls.scan1, cls.scan2 = tf_check.scans('/scan'), tf_check.scans(CAR2 + '/scan')
        for stream in (cls.truth1, cls.truth2, cls.scan1, cls.scan2):
            stream.wait_count(1)
        sim_sleep(1.0)

    def topics(self):
        """(published, subscribed) topic sets of car 1 and car 2, from the master."""
        pubs, subs, _ = rosgraph.Master(rospy.get_name()).getSystemState()
        out = {}
        for kind, entries in (('pub', pubs), ('sub', subs)):
            car1, car2 = set(), set()
            for topic, nodes in entries:
                nodes = set(nodes) - {rospy.get_name()}
                # The sim node's own interface (~step_and_wait) is the world's, as SHARED.
                if topic in SHARED or topic.startswith('/tianracer_sim/') or not nodes:
                    continue
                if topic.startswith(CAR2 + '/'):
                    car2.add(topic)
                elif nodes & CAR1_NODES:
                    car1.add(topic)
            out[kind] = (car1, car2)
        return out

    def test_a_disjoint_topic_sets(self):
        for kind, (car1, car2) in self.topics().items():
            self.assertTrue(car1, kind)
            self.assertEqual(car1 & car2, set(), kind)
            self.assertEqual({to_car2(t) for t in car1}, car2, kind)
        car1_pub, car2_pub = self.topics()['pub']
        for t in ('/tianracer/joint_states', '/tianracer/odom', '/tianracer/ground_truth/odom',
                  '/scan'):
            self.assertIn(t, car1_pub)
        self.assertIn(CAR2 + '/scan', car2_pub)

    def test_b_frames_prefixed_and_complete(self):
        links1 = tf_check.urdf_links('/robot_description')
        links2 = tf_check.urdf_links(CAR2 + '/robot_description')
        self.assertEqual(links1, links2)
        for link in links1:
            self.assertIsNotNone(self.tf.chain(link, 'odom'), link)
            self.assertIsNotNone(self.tf.chain('tianracer_02/' + link, 'tianracer_02/odom'), link)
        self.assertEqual(self.scan1.latest().header.frame_id, 'lidar')
        self.assertEqual(self.scan2.latest().header.frame_id, 'tianracer_02/lidar')
        self.assertEqual(self.truth2.latest().child_frame_id, 'tianracer_02/base_link')
        self.assertEqual(self.tf.chain('tianracer_02/odom', 'world'), ['tianracer_02/odom', 'world'])
        self.assertEqual(self.tf.duplicates(), {})

    def test_c_each_lidar_sees_the_other_car(self):
        t = rospy.get_time()
        for scans in (self.scan1, self.scan2):
            scans.first_stamped(t + 0.5)  # 20 scans each
        left1 = [tf_check.beam(s, 90) for s in self.scan1.between(t, t + 0.5)]
        right2 = [tf_check.beam(s, -90) for s in self.scan2.between(t, t + 0.5)]
        self.assertGreaterEqual(min(len(left1), len(right2)), 10)
        p1 = self.truth1.first_stamped(t).pose.pose.position
        p2 = self.truth2.first_stamped(t).pose.pose.position
        gap = math.hypot(p2.x - p1.x, p2.y - p1.y)
        self.assertAlmostEqual(gap, 0.4, delta=0.01)
        # The other lidar head's surface: the gap less its radius; the wall would be 0.7 m.
        # Mean of >= 10 scans with 0.01 m noise: 3 sigma of the mean < 0.01 m.
        self.assertAlmostEqual(float(np.mean(left1)), gap - 0.021, delta=0.01)
        self.assertAlmostEqual(float(np.mean(right2)), gap - 0.021, delta=0.01)

    def test_d_second_cmd_vel_drives_only_the_second_car(self):
        t0, t1 = tf_check.drive(CAR2 + '/cmd_vel', 0.5, 0.0, 2.0)
        a1, a2 = [x.first_stamped(t0).pose.pose.position for x in (self.truth1, self.truth2)]
        b1, b2 = [x.first_stamped(t1 + 0.5).pose.pose.position
                  for x in (self.truth1, self.truth2)]
        self.assertGreater(b2.x - a2.x, 0.6)
        self.assertLess(math.hypot(b1.x - a1.x, b1.y - a1.y), 0.005)

    def centre_depth(self):
        """Centre pixel (m, NaN outside the camera's range) of a depth frame rendered after
        now."""
        t = rospy.get_time()
        frames = Stream('/real_sense/depth/image_raw', Image, buff_size=1 << 24)
        try:
            msg = frames.first_stamped(t + 1e-6)
        finally:
            frames.unregister()
        depth = np.frombuffer(msg.data, dtype='<f4').reshape(msg.height, msg.width)
        return float(depth[msg.height // 2, msg.width // 2])

    def test_e_depth_camera_sees_the_other_car(self):
        before = self.centre_depth()
        rospy.wait_for_service('/gazebo/set_model_state', timeout=30)
        set_state = rospy.ServiceProxy('/gazebo/set_model_state', SetModelState)
        p1 = self.truth1.latest().pose.pose
        pose = Pose()
        pose.position.x, pose.position.y, pose.position.z = p1.position.x + 1.0, p1.position.y, \
            p1.position.z
        pose.orientation = p1.orientation
        self.assertTrue(set_state(ModelState('tianracer_02', pose, Twist(), 'world')).success)
        sim_sleep(0.3)
        after = self.centre_depth()
        # Car 1's depth camera sits 0.199 m ahead of its base_link, 0.052 m up. At that height
        # the centre ray passes over car 2's low tail and ends on the back of car 2's own depth
        # camera bar, 0.174 m ahead of car 2's base_link: 1.0 + 0.174 - 0.199 = 0.975 m.
        self.assertTrue(math.isnan(before) or before > 1.5, before)
        self.assertAlmostEqual(after, 0.975, delta=0.02)


if __name__ == '__main__':
    rostest.rosrun('tianracer_bringup', 'two_cars', TwoCars)
