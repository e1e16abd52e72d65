#!/usr/bin/env python3
"""rostest: four_wheel_steering_controller/FourWheelSteeringController on fws_control.urdf
(track 0.24, wheel base 0.3, wheel radius 0.05, all from the URDF), through its ROS interface:
  - cmd_vel (v, w): odom's twist within 3 %, ground truth within 8 %, over 2 s of sim time after
    1 s of settling;
  - cmd_four_wheel_steering, crab (front = rear steering 0.4): ground truth moves along the
    steering angle without turning, odom says so too;
  - with no command for longer than cmd_vel_timeout (0.5 s) the robot stops;
  - a controller with one rear wheel is refused with upstream's message.
Sim time throughout; wall time only bounds the waits."""
import math
import unittest

import rospy
import rostest
from controller_manager_msgs.srv import ListControllers, LoadController
from four_wheel_steering_msgs.msg import FourWheelSteering, FourWheelSteeringStamped
from geometry_msgs.msg import Twist
from nav_msgs.msg import Odometry
from rosgraph_msgs.msg import Clock, Log
from tianracer_sim.rotation import planar_motion as motion
from tianracer_sim.sim_time import Stream, clock_stamp, drive_twist, sim_sleep, wait_connected
from tianracer_sim.sim_time import wait_for

WALL_TIMEOUT = 120.0
NS = '/fwsbot'
CONTROLLER = NS + '/mobile_base_controller'


class FourWheelSteeringControllerTest(unittest.TestCase):
    def setUp(self):
        rospy.init_node('test_four_wheel_steering_controller')
        self.clock = Stream('/clock', Clock, stamp=clock_stamp, keep=1)
        self.odom = Stream(CONTROLLER + '/odom', Odometry)
        self.odom_steer = Stream(CONTROLLER + '/odom_steer', FourWheelSteeringStamped)
        self.truth = Stream(NS + '/ground_truth/odom', Odometry)
        self.log = []
        rospy.Subscriber('/rosout', Log, lambda m: self.log.append(m.msg))
        self.cmd = rospy.Publisher(CONTROLLER + '/cmd_vel', Twist, queue_size=1)
        self.cmd4 = rospy.Publisher(CONTROLLER + '/cmd_four_wheel_steering', FourWheelSteering,
                                    queue_size=1)
        wait_for(lambda: self.clock.latest(), '/clock', WALL_TIMEOUT)
        wait_connected(self.cmd)
        wait_connected(self.cmd4)

    def window(self, t0, t1):
        self.truth.first_stamped(t1)
        self.odom.first_stamped(t1)
        return self.odom.between(t0, t1), self.truth.between(t0, t1)

    def drive4(self, seconds, speed, front, rear):
        msg = FourWheelSteering(front_steering_angle=front, rear_steering_angle=rear, speed=speed)
        sim_sleep(seconds, WALL_TIMEOUT, each=lambda: self.cmd4.publish(msg), poll=0.02)

    def test_driven(self):
        rospy.wait_for_service(NS + '/controller_manager/list_controllers', timeout=WALL_TIMEOUT)
        listed = rospy.ServiceProxy(NS + '/controller_manager/list_controllers', ListControllers)()
        states = {c.name: (c.type, c.state) for c in listed.controller}
        self.assertEqual(states['mobile_base_controller'],
                         ('four_wheel_steering_controller/FourWheelSteeringController', 'running'))

        # cmd_vel: a turn
        v, w = 0.3, 0.5
        drive_twist(self.cmd, 1.0, v, w, wall_timeout=WALL_TIMEOUT)
        t0 = rospy.get_time()
        drive_twist(self.cmd, 2.0, v, w, wall_timeout=WALL_TIMEOUT)
        odom, truth = self.window(t0, rospy.get_time())
        self.assertGreater(len(odom), 95)  # 50 Hz
        twist = (sum(m.twist.twist.linear.x for m in odom) / len(odom),
                 sum(m.twist.twist.angular.z for m in odom) / len(odom))
        from_truth = motion([(m.header.stamp.to_sec(), m.pose.pose) for m in truth])
        print('4ws twist (%.2f, %.2f): odom %.4f %.4f, ground truth %.4f %.4f'
              % ((v, w) + twist + from_truth))
        self.assertAlmostEqual(twist[0], v, delta=0.03 * v)
        self.assertAlmostEqual(twist[1], w, delta=0.03 * w)
        self.assertAlmostEqual(from_truth[0], v, delta=0.08 * v)
        self.assertAlmostEqual(from_truth[1], w, delta=0.08 * w)

        # cmd_four_wheel_steering: crab at 0.4 rad
        speed, angle = 0.3, 0.4
        self.drive4(1.0, speed, angle, angle)
        t0 = rospy.get_time()
        p0 = self.truth.first_stamped(t0).pose.pose
        self.drive4(2.0, speed, angle, angle)
        t1 = rospy.get_time()
        odom, truth = self.window(t0, t1)
        p1 = truth[-1].pose.pose
        dx, dy = p1.position.x - p0.position.x, p1.position.y - p0.position.y
        yaw0 = 2 * math.atan2(p0.orientation.z, p0.orientation.w)
        yaw1 = 2 * math.atan2(p1.orientation.z, p1.orientation.w)
        heading = math.atan2(dy, dx) - yaw0
        heading = math.atan2(math.sin(heading), math.cos(heading))
        dist = math.hypot(dx, dy) / (truth[-1].header.stamp.to_sec() - t0)
        print('4ws crab: ground truth direction %.4f (body), speed %.4f, yaw change %.4f; odom '
              'linear y %.4f' % (heading, dist, yaw1 - yaw0, odom[-1].twist.twist.linear.y))
        self.assertAlmostEqual(heading, angle, delta=0.05)
        self.assertAlmostEqual(dist, speed, delta=0.08 * speed)
        self.assertLess(abs(math.atan2(math.sin(yaw1 - yaw0), math.cos(yaw1 - yaw0))), 0.05)
        self.assertAlmostEqual(odom[-1].twist.twist.linear.y, speed * math.sin(angle), delta=0.02)
        steer = self.odom_steer.between(t0, t1)
        self.assertTrue(steer)
        self.assertAlmostEqual(steer[-1].data.front_steering_angle, angle, delta=0.02)

        # timeout: no command for more than 0.5 s stops it
        sim_sleep(1.5, wall_timeout=WALL_TIMEOUT)
        t0 = rospy.get_time()
        sim_sleep(1.0, wall_timeout=WALL_TIMEOUT)
        _, truth = self.window(t0, rospy.get_time())
        still = motion([(m.header.stamp.to_sec(), m.pose.pose) for m in truth])
        print('4ws after the timeout: %.4f %.4f' % still)
        self.assertLess(abs(still[0]), 0.01)

        # bad parameters: refused with upstream's message
        rospy.set_param(NS + '/bad_controller', {
            'type': 'four_wheel_steering_controller/FourWheelSteeringController',
            'front_wheel': ['front_left_wheel_joint', 'front_right_wheel_joint'],
            'rear_wheel': 'rear_left_wheel_joint',
            'front_steering': ['front_left_steering_joint', 'front_right_steering_joint'],
            'rear_steering': ['rear_left_steering_joint', 'rear_right_steering_joint']})
        load = rospy.ServiceProxy(NS + '/controller_manager/load_controller', LoadController)
        self.assertFalse(load('bad_controller').ok)
        wait_for(lambda: any('#front wheels (2) != #rear wheels (1).' in m for m in self.log),
                 'the error about the wheel counts', WALL_TIMEOUT)


if __name__ == '__main__':
    rostest.rosrun('tianracer_sim', 'four_wheel_steering_controller',
                   FourWheelSteeringControllerTest)
