#!/usr/bin/env python3
"""rostest: models spawned and deleted at run time.

- spawn_model (the launch file's node) adds car2 through /gazebo/spawn_urdf_model: its
  joint_states, scan and ground truth appear under /car2 and it drives from /car2/cmd_vel;
- delete_model removes it: nothing more on its topics in sim time, gone from model_states;
  its name can be spawned again;
- spawn_sdf_model adds a box that falls and rests on the ground, where the other car's lidar
  sees it; once deleted, the lidar no longer does;
- bad input (malformed URDF/SDF, a duplicate name, deleting an unknown model) is answered with
  success false and a message, nothing is half-spawned and the sim runs on.
Sim time throughout; wall time only bounds the waits.
"""
import math
import unittest

import rospy
import rostest
from gazebo_msgs.msg import ModelStates
from gazebo_msgs.srv import (DeleteModel, GetLinkState, GetModelState, GetWorldProperties,
                             SpawnModel)
from geometry_msgs.msg import Pose, Twist
from nav_msgs.msg import Odometry
from sensor_msgs.msg import JointState, LaserScan
from tianracer_sim.sim_time import Stream, drive_twist, sim_sleep

WALL_TIMEOUT = 120.0
BOX = """<?xml version='1.0'?>
<sdf version='1.6'>
  <model name='ignored'>
    <link name='link'>
      <inertial><mass>1.0</mass>
        <inertia><ixx>0.00667</ixx><iyy>0.00667</iyy><izz>0.00667</izz></inertia>
      </inertial>
      <collision name='c'><geometry><box><size>0.2 0.2 0.2</size></box></geometry></collision>
      <visual name='v'><geometry><box><size>0.2 0.2 0.2</size></box></geometry></visual>
    </link>
  </model>
</sdf>"""


def stamps_after(stream, t):
    """Stamps of the messages of `stream` stamped after t (sim time)."""
    return [s for s in stream.stamps() if s > t]


def pose(x, y, z):
    p = Pose()
    p.position.x, p.position.y, p.position.z = x, y, z
    p.orientation.w = 1.0
    return p


class SpawnTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node('test_spawn')
        for name in ('spawn_urdf_model', 'spawn_sdf_model', 'delete_model', 'get_model_state',
                     'get_world_properties'):
            rospy.wait_for_service('/gazebo/' + name, timeout=WALL_TIMEOUT)
        cls.spawn_urdf = rospy.ServiceProxy('/gazebo/spawn_urdf_model', SpawnModel)
        cls.spawn_sdf = rospy.ServiceProxy('/gazebo/spawn_sdf_model', SpawnModel)
        cls.delete = rospy.ServiceProxy('/gazebo/delete_model', DeleteModel)
        cls.get_state = rospy.ServiceProxy('/gazebo/get_model_state', GetModelState)
        cls.world = rospy.ServiceProxy('/gazebo/get_world_properties', GetWorldProperties)

    def wait_sim(self, seconds):
        sim_sleep(seconds)

    def sim_time(self):
        return self.world().sim_time

    def models(self):
        return sorted(self.world().model_names)

    def wait_car2(self):
        streams = (Stream('/car2/joint_states', JointState), Stream('/car2/scan', LaserScan),
                   Stream('/car2/ground_truth/odom', Odometry))
        for stream in streams:
            stream.wait_count(1, WALL_TIMEOUT)
        return streams

    def drive_car2(self, seconds):
        pub = rospy.Publisher('/car2/cmd_vel', Twist, queue_size=1)
        drive_twist(pub, seconds, 0.5)
        pub.unregister()

    def test_1_spawned_car_publishes_and_drives(self):
        joints, scans, truth = self.wait_car2()
        self.assertIn('car2', self.models())
        self.assertIn('car2', rospy.wait_for_message('/gazebo/model_states', ModelStates,
                                                     timeout=WALL_TIMEOUT).name)
        start = self.get_state('car2', 'world')
        self.assertTrue(start.success, start.status_message)
        self.assertAlmostEqual(start.pose.position.y, 1.0, delta=0.02)
        car1 = self.get_state('tianracer', 'world').pose.position
        self.drive_car2(3.0)
        end = self.get_state('car2', 'world').pose.position
        self.assertGreater(end.x - start.pose.position.x, 0.5, 'car2 did not drive forward')
        self.assertAlmostEqual(end.y, 1.0, delta=0.1)
        still = self.get_state('tianracer', 'world').pose.position
        self.assertLess(math.hypot(still.x - car1.x, still.y - car1.y), 0.01)

        # delete_model: its topics stop in sim time, it leaves model_states.
        res = self.delete('car2')
        self.assertTrue(res.success, res.status_message)
        # The sim's own time once the delete is done (our /clock lags it by a few steps).
        t_del = self.sim_time()
        self.wait_sim(1.0)
        self.assertEqual(stamps_after(joints, t_del + 1e-6), [])
        self.assertEqual(stamps_after(scans, t_del + 1e-6), [])
        self.assertEqual(stamps_after(truth, t_del + 1e-6), [])
        self.assertNotIn('car2', self.models())
        states = rospy.wait_for_message('/gazebo/model_states', ModelStates, timeout=WALL_TIMEOUT)
        self.assertNotIn('car2', states.name)
        self.assertFalse(self.get_state('car2', 'world').success)

        # The name and the topics are free again: the same car spawns once more.
        urdf = rospy.get_param('/car2/robot_description')
        res = self.spawn_urdf('car2', urdf, '/car2', pose(2.0, 1.0, 0.015), 'world')
        self.assertTrue(res.success, res.status_message)
        for stream in self.wait_car2():
            stream.unregister()
        res = self.delete('car2')
        self.assertTrue(res.success, res.status_message)

    def scan_ahead(self, after):
        """tianracer's lidar range straight ahead, from a scan stamped after `after` (sim s)."""
        scans = Stream('/scan', LaserScan)
        try:
            scan = scans.first(lambda t, m: t > after, 'a scan after %.2f s' % after,
                               wall_timeout=WALL_TIMEOUT)[2]
        finally:
            scans.unregister()
        i = int(round((0.0 - scan.angle_min) / scan.angle_increment))
        return scan.ranges[i]

    def test_2_spawned_box_falls_and_rests(self):
        # Straight ahead of tianracer (at the origin, facing +x), so its lidar sees it.
        r = self.scan_ahead(rospy.Time.now().to_sec())
        self.assertTrue(not math.isfinite(r) or r > 5.0, 'something ahead already: %g' % r)
        res = self.spawn_sdf('box', BOX, '', pose(1.0, 0.0, 1.0), '')
        self.assertTrue(res.success, res.status_message)
        self.assertIn('box', self.models())
        self.wait_sim(2.0)
        s = self.get_state('box', 'world')
        self.assertTrue(s.success, s.status_message)
        self.assertAlmostEqual(s.pose.position.x, 1.0, delta=0.01)
        self.assertAlmostEqual(s.pose.position.z, 0.1, delta=0.005)
        v = s.twist.linear
        self.assertLess(math.sqrt(v.x ** 2 + v.y ** 2 + v.z ** 2), 0.01)
        # The lidar (0.094 m ahead of base_link) sees the box's near face at x 0.9.
        lidar_x = self.get_link_x('tianracer::lidar')
        self.assertAlmostEqual(self.scan_ahead(self.sim_time()), 0.9 - lidar_x,
                               delta=0.03)
        res = self.delete('box')
        self.assertTrue(res.success, res.status_message)
        self.assertNotIn('box', self.models())
        r = self.scan_ahead(self.sim_time())
        self.assertTrue(not math.isfinite(r) or r > 5.0, 'the deleted box is still seen: %g' % r)

    def get_link_x(self, link):
        rospy.wait_for_service('/gazebo/get_link_state', timeout=WALL_TIMEOUT)
        res = rospy.ServiceProxy('/gazebo/get_link_state', GetLinkState)(link, 'world')
        self.assertTrue(res.success, res.status_message)
        return res.link_state.pose.position.x

    def test_3_bad_input(self):
        before = self.models()
        t0 = rospy.Time.now().to_sec()
        cases = [
            (self.spawn_urdf, 'bad_urdf', "<robot name='x'><link name='a'>", 'malformed'),
            (self.spawn_urdf, 'bad_urdf2', "<robot name='x'><joint name='j' type='revolute'/>"
             "</robot>", 'bad_urdf2'),
            (self.spawn_sdf, 'bad_sdf', "<sdf version='1.6'><model name='m'><link name='l'>",
             'malformed'),
            (self.spawn_sdf, 'bad_sdf2', "<sdf version='1.6'><model name='m'><link name='l'>"
             "<collision name='c'><geometry><box><size>1 x 1</size></box></geometry>"
             "</collision></link></model></sdf>", 'size'),
            (self.spawn_sdf, 'tianracer', BOX, 'exists already'),
            (self.spawn_urdf, 'ground_plane', rospy.get_param('/car2/robot_description'),
             'exists already'),
            (self.spawn_sdf, 'empty', '  ', 'empty'),
        ]
        for call, name, xml, words in cases:
            res = call(name, xml, '', pose(0.0, -1.0, 0.5), '')
            self.assertFalse(res.success, name)
            self.assertIn(words, res.status_message, name)
            self.assertIn(name, res.status_message)
        res = self.spawn_sdf('nan_box', BOX, '', pose(float('nan'), 0.0, 0.5), '')
        self.assertFalse(res.success)
        self.assertIn('not finite', res.status_message)
        res = self.spawn_sdf('far_box', BOX, '', pose(0.0, 0.0, 0.5), 'no_such_model')
        self.assertFalse(res.success)
        self.assertIn('no_such_model', res.status_message)
        res = self.delete('no_such_model')
        self.assertFalse(res.success)
        self.assertIn("no model named 'no_such_model'", res.status_message)
        res = self.delete('ground_plane')
        self.assertFalse(res.success)
        self.assertIn('ground plane', res.status_message)
        # Nothing half-spawned; the sim runs on and its states stay finite.
        self.assertEqual(self.models(), before)
        self.wait_sim(0.5)
        self.assertGreater(rospy.Time.now().to_sec(), t0)
        s = self.get_state('tianracer', 'world')
        self.assertTrue(s.success)
        self.assertTrue(all(math.isfinite(v) for v in (s.pose.position.x, s.pose.position.y,
                                                       s.pose.position.z)))


if __name__ == '__main__':
    rostest.rosrun('tianracer_sim', 'spawn', SpawnTest)
