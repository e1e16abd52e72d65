#!/usr/bin/env python3
"""rostest: cmd_vel_node with angular_z_is_steering_angle true (tianracer's TEB convention):
angular.z = 0.3 rad at 0.5 m/s must turn the rear axle midpoint on a circle of radius
L / tan(0.3), L the wheelbase from the URDF joint origins as the node derives it. Issue 4 (c).
Sim time throughout; see test_ackermann_drive.py."""
import math
import unittest

import rospy
import rostest

from ackermann_harness import Harness, ackermann_geometry

RADIUS_TOL = 0.03


class AckermannSteeringMode(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node('test_ackermann_steering_mode')
        cls.h = Harness()
        if not cls.h.wait_ready():
            raise AssertionError('no ground truth, wheel odometry or cmd_vel_node output within '
                                 '60 s of wall time')
        cls.geometry = ackermann_geometry(rospy.get_param('/robot_description'))
        rospy.loginfo('geometry from robot_description: %s', cls.geometry)

    def test_c_circle_from_steering_angle(self):
        self.assertTrue(rospy.get_param('/cmd_vel_node/angular_z_is_steering_angle'),
                        'cmd_vel_node is not in steering-angle mode')
        v, delta = 0.5, 0.3
        L = self.geometry['wheelbase']
        r_exp = L / math.tan(delta)
        lap = 2.0 * math.pi * r_exp / v
        res = self.h.drive_circle(v, delta, settle=3.0, duration=lap, geometry=self.geometry)
        err = (res['radius'] - r_exp) / r_exp
        cmds = [c[1] for c in self.h.wheel_cmds_between(res['t_start'] + 0.1, res['t_end'])]
        self.assertTrue(cmds, 'no wheel commands seen')
        self.assertNotIn(0.0, cmds, 'the cmd_vel node timed out during the measurement: the '
                         '/cmd_vel stream of this test lapsed')
        text = ('v %.2f m/s, steering angle %.2f rad, L = %.5f m (URDF joint origins): expected '
                'R = L / tan(delta) = %.4f m; fitted radius of the rear axle midpoint %.4f m '
                '(%+.2f %%, rms %.2f mm, %d samples over %.2f s, %.0f deg); base_link circle '
                '%.4f m; measured speed %.4f m/s, yaw rate %.4f rad/s (bicycle: %.4f)'
                % (v, delta, L, r_exp, res['radius'], 100.0 * err, 1000.0 * res['rms'],
                   res['samples'], res['duration'], math.degrees(res['turned']),
                   res['radius_base_link'], res['speed'], res['yaw_rate'], v / r_exp))
        rospy.loginfo('[test_c] %s', text)
        print('FIGURE test_c_circle_from_steering_angle: %s' % text)
        self.assertLess(abs(err), RADIUS_TOL, text)


if __name__ == '__main__':
    rostest.rosrun('tianracer_tests', 'ackermann_steering_mode', AckermannSteeringMode)
