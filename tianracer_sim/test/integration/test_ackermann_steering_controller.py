#!/usr/bin/env python3
"""rostest: ackermann_steering_controller/AckermannSteeringController on steerbot_control.urdf
(rear wheel radius 0.05 m, steer joint 0.3 m ahead: both from the URDF), through ROS only: a
cmd_vel of linear.x v and angular.z = steering angle d moves it at v and v tan(d) / 0.3 (odom
within 3 %, ground truth within 8 %: the front wheel's slip), odom's pose follows ground truth
(within 2 cm and 0.03 rad),
cmd_vel_timeout stops it. Sim time throughout."""
import math
import unittest

import rospy
import rostest
from geometry_msgs.msg import Twist
from nav_msgs.msg import Odometry
from rosgraph_msgs.msg import Clock
from tianracer_sim.rotation import planar_motion as motion
from tianracer_sim.rotation import wrap_angle as wrap
from tianracer_sim.rotation import yaw_from_quaternion as yaw_of
from tianracer_sim.sim_time import Stream, clock_stamp, drive_twist, sim_sleep, wait_connected
from tianracer_sim.sim_time import wait_for

WALL_TIMEOUT = 120.0
NS = '/steerbot'
CONTROLLER = NS + '/ackermann_steering_controller'
SEPARATION_H = 0.3




class AckermannSteeringControllerTest(unittest.TestCase):
    def setUp(self):
        rospy.init_node('test_ackermann_steering_controller')
        self.clock = Stream('/clock', Clock, stamp=clock_stamp, keep=1)
        self.odom = Stream(CONTROLLER + '/odom', Odometry)
        self.truth = Stream(NS + '/ground_truth/odom', Odometry)
        self.cmd = rospy.Publisher(CONTROLLER + '/cmd_vel', Twist, queue_size=1)
        wait_for(lambda: self.clock.latest(), '/clock', WALL_TIMEOUT)
        wait_connected(self.cmd)

    def drive(self, v, steer):
        drive_twist(self.cmd, 1.5, v, steer, wall_timeout=WALL_TIMEOUT)
        t0 = rospy.get_time()
        drive_twist(self.cmd, 2.0, v, steer, wall_timeout=WALL_TIMEOUT)
        t1 = rospy.get_time()
        self.truth.first_stamped(t1)
        self.odom.first_stamped(t1)
        odom = self.odom.between(t0, t1)
        truth = self.truth.between(t0, t1)
        self.assertGreater(len(odom), 95)
        from_odom = motion([(m.header.stamp.to_sec(), m.pose.pose) for m in odom])
        from_truth = motion([(m.header.stamp.to_sec(), m.pose.pose) for m in truth])
        print('ackermann (v %.2f, steer %.2f): odom %.4f %.4f, ground truth %.4f %.4f' % (
            (v, steer) + from_odom + from_truth))
        return from_odom, from_truth

    def assert_speeds(self, measured, v, w, what, tolerance):
        for got, want, name in zip(measured, (v, w), ('speed', 'yaw rate')):
            self.assertAlmostEqual(got, want, delta=tolerance * max(abs(want), 0.3),
                                   msg='%s %s: %.4f, expected %.4f' % (what, name, got, want))

    def test_driven_through_cmd_vel(self):
        start = self.truth.first(lambda s, m: True, 'ground truth')[2].pose.pose
        for v, steer in ((0.4, 0.0), (0.3, 0.3)):
            w = v * math.tan(steer) / SEPARATION_H
            odom, truth = self.drive(v, steer)
            self.assert_speeds(odom, v, w, 'odom', 0.03)
            self.assert_speeds(truth, v, w, 'ground truth', 0.08)
        t = rospy.get_time()
        self.odom.first_stamped(t)
        odom = self.odom.latest()
        truth = min(self.truth.messages(),
                    key=lambda m: abs(m.header.stamp.to_sec() - odom.header.stamp.to_sec()))
        q = truth.pose.pose
        dx, dy = q.position.x - start.position.x, q.position.y - start.position.y
        yaw0 = yaw_of(start.orientation)
        tx, ty = math.cos(yaw0) * dx + math.sin(yaw0) * dy, -math.sin(yaw0) * dx + math.cos(yaw0) * dy
        p = odom.pose.pose
        print('odom (%.4f %.4f %.4f), ground truth from the start (%.4f %.4f %.4f)' % (
            p.position.x, p.position.y, yaw_of(p.orientation), tx, ty, wrap(yaw_of(q.orientation) - yaw0)))
        self.assertAlmostEqual(p.position.x, tx, delta=0.02)
        self.assertAlmostEqual(p.position.y, ty, delta=0.02)
        self.assertAlmostEqual(wrap(yaw_of(p.orientation) - yaw_of(q.orientation) + yaw0), 0.0,
                               delta=0.03)
        # No command for longer than cmd_vel_timeout: it stops.
        sim_sleep(1.5, wall_timeout=WALL_TIMEOUT)
        t0 = rospy.get_time()
        sim_sleep(1.0, wall_timeout=WALL_TIMEOUT)
        t1 = rospy.get_time()
        self.truth.first_stamped(t1)
        v, w = motion([(m.header.stamp.to_sec(), m.pose.pose) for m in self.truth.between(t0, t1)])
        self.assertAlmostEqual(v, 0.0, delta=0.01)


if __name__ == '__main__':
    rostest.rosrun('tianracer_sim', 'ackermann_steering_controller', AckermannSteeringControllerTest)
