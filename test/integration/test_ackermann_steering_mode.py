#!/usr/bin/env python3
"""rostest: cmd_vel_node with angular_z_is_steering_angle true (tianracer's TEB convention):
angular.z = 0.3 rad at 0.5 m/s must turn the rear axle midpoint on a circle of radius
L / tan(0.3), L the wheelbase from the URDF joint origins as the node derives it. Issue 4 (c).
Sim time throughout; see test_ackermann_drive.py."""
import math

import rospy
import rostest

from ackermann_harness import CMD_NODE, AckermannTestCase

RADIUS_TOL = 0.03


class AckermannSteeringMode(AckermannTestCase):
    node_name = 'test_ackermann_steering_mode'

    def test_c_circle_from_steering_angle(self):
        self.assertTrue(rospy.get_param(CMD_NODE + '/angular_z_is_steering_angle'),
                        'cmd_vel_node is not in steering-angle mode')
        v, delta = 0.5, 0.3
        L = self.geometry['wheelbase']
        r_exp = L / math.tan(delta)
        err, figures = self.drive_lap(v, delta, r_exp, '(c)')
        text = self.report(
            'v %.2f m/s, steering angle %.2f rad, L = %.5f m (URDF joint origins): expected '
            'R = L / tan(delta) = %.4f m; %s (bicycle: %.4f)', v, delta, L, r_exp, figures,
            v / r_exp)
        self.assertLess(abs(err), RADIUS_TOL, text)


if __name__ == '__main__':
    rostest.rosrun('tianracer_tests', 'ackermann_steering_mode', AckermannSteeringMode)
