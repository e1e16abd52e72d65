#!/usr/bin/env python3
"""rostest: a world's dynamic model is a free body the car can push (free_box.world).

- the car drives into the box at 0.5 m/s: the box's ground truth (get_model_state) moves on;
- with car and box at rest, the lidar's 0 deg beam (mean of 20 scans, noise sd 0.01 m) reads
  the distance from the lidar to the box's near face where the box now is, within 2 cm;
- /gazebo/reset_world puts the box back at its pose in the world file.
Sim time throughout; wall time only bounds the waits.
"""
import math
import unittest

import numpy as np
import rospy
import rostest
from nav_msgs.msg import Odometry
from sensor_msgs.msg import LaserScan
from std_msgs.msg import Float64
from std_srvs.srv import Empty
from tianracer_sim.sim_time import Stream, sim_sleep, wait_connected

from gazebo_msgs.srv import GetModelState

LIDAR_IN_BASE = np.array([0.093603, -8.284e-05, 0.12377])  # the seed's lidar_joint
BOX_HALF = 0.15
BOX_START = np.array([0.8, 0.0, 0.15])


def rotation(q):
    x, y, z, w = q.x, q.y, q.z, q.w
    return np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
                     [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
                     [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]])


def ray_box(origin, direction, center, R, half):
    """Distance along the ray to a box (slab method in the box frame), or None."""
    o = R.T.dot(origin - center)
    d = R.T.dot(direction)
    t0, t1 = -math.inf, math.inf
    for i in range(3):
        if abs(d[i]) < 1e-12:
            if abs(o[i]) > half:
                return None
            continue
        a, b = (-half - o[i]) / d[i], (half - o[i]) / d[i]
        t0, t1 = max(t0, min(a, b)), min(t1, max(a, b))
    return t0 if t0 <= t1 and t0 > 0 else None


class FreeBodies(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node('test_free_bodies')
        cls.truth = Stream('/tianracer/ground_truth/odom', Odometry, keep=100)
        cls.scans = Stream('/scan', LaserScan, keep=100)
        for srv in ('get_model_state', 'reset_world'):
            rospy.wait_for_service('/gazebo/' + srv, timeout=60)
        cls.get_state = rospy.ServiceProxy('/gazebo/get_model_state', GetModelState)
        cls.reset_world = rospy.ServiceProxy('/gazebo/reset_world', Empty)
        cls.wheels = [rospy.Publisher('/tianracer/%s_rear_wheel_velocity_controller/command' % s,
                                      Float64, queue_size=1, latch=True) for s in ('left', 'right')]
        cls.truth.wait_count(1)

    def box(self):
        res = self.get_state(model_name='crate', relative_entity_name='')
        self.assertTrue(res.success, res.status_message)
        p = res.pose.position
        return np.array([p.x, p.y, p.z]), rotation(res.pose.orientation)

    def drive(self, speed):
        for p in self.wheels:
            wait_connected(p)
        for p in self.wheels:
            p.publish(Float64(speed / 0.032))

    def test_1_pushed_box_moves_and_the_lidar_sees_it_there(self):
        p0, _ = self.box()
        np.testing.assert_allclose(p0, BOX_START, atol=1e-3)
        sim_sleep(0.5)
        self.drive(0.5)
        sim_sleep(3.0)
        self.drive(0.0)
        sim_sleep(1.5)  # car and box come to rest
        p1, R1 = self.box()
        rospy.loginfo('box pushed from %s to %s', p0, p1)
        self.assertGreater(p1[0] - p0[0], 0.3, 'the car did not push the box')
        # The scans of 0.6 s of sim time (24 at 40 Hz) with box and car at rest.
        t = rospy.get_time()
        self.scans.first_stamped(t + 0.6)
        scans = self.scans.between(t, t + 0.6)
        truth = self.truth.first_stamped(t)
        self.assertGreaterEqual(len(scans), 20)
        scans = scans[-20:]
        s = scans[0]
        i = int(round((0.0 - s.angle_min) / s.angle_increment))
        measured = float(np.mean([sc.ranges[i] for sc in scans]))
        pose = truth.pose.pose
        R_car = rotation(pose.orientation)
        origin = np.array([pose.position.x, pose.position.y, pose.position.z]) + R_car.dot(LIDAR_IN_BASE)
        beam = R_car.dot([math.cos(s.angle_min + i * s.angle_increment),
                          math.sin(s.angle_min + i * s.angle_increment), 0.0])
        expected = ray_box(origin, beam, p1, R1, BOX_HALF)
        self.assertIsNotNone(expected, 'the 0 deg beam misses the box where it is')
        rospy.loginfo('lidar 0 deg beam %.4f m, box face at %.4f m (start 0.5564)', measured,
                      expected)
        self.assertAlmostEqual(measured, expected, delta=0.02)
        self.assertGreater(abs(expected - 0.5564), 0.05)  # not the distance before the push

    def test_2_reset_world_returns_the_box(self):
        self.reset_world()
        p, R = self.box()
        rospy.loginfo('box after reset_world at %s', p)
        self.assertLess(np.abs(p - BOX_START).max(), 1e-3, p)
        self.assertLess(np.abs(R - np.eye(3)).max(), 1e-3, R)


if __name__ == '__main__':
    rostest.rosrun('tianracer_sim', 'free_bodies', FreeBodies)
