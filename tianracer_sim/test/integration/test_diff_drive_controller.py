#!/usr/bin/env python3
"""rostest: diff_drive_controller/DiffDriveController on diffbot_control.urdf (wheels of 0.05 m
radius 0.24 m apart, both from the URDF), through its ROS interface only:
  - cmd_vel (v, w) moves it at v and w (through the acceleration limits of the YAML): its odom twist within 3 %, ground truth within 6 %
    (what the wheels' slip and the velocity motors leave), averaged over 2 s of sim time after
    1 s of settling;
  - odom's pose follows ground truth (within 2 cm and 0.03 rad after the manoeuvres), /tf
    odom -> base_link is odom's pose, cmd_vel_out carries the commands (publish_cmd);
  - when no command comes for longer than cmd_vel_timeout (0.5 s) the robot stops;
  - a NaN command is ignored with upstream's warning; a controller that cannot load (a wheel
    joint the URDF lacks) is refused with upstream's message, and this one drives on.
Sim time throughout; wall time only bounds the waits."""
import math
import unittest

import dynamic_reconfigure.client
import rospy
from control_msgs.msg import JointTrajectoryControllerState
import rostest
from controller_manager_msgs.srv import ListControllers, LoadController
from geometry_msgs.msg import Twist, TwistStamped
from nav_msgs.msg import Odometry
from rosgraph_msgs.msg import Clock, Log
from sensor_msgs.msg import JointState
from tf2_msgs.msg import TFMessage
from tianracer_sim.rotation import planar_motion as motion
from tianracer_sim.rotation import wrap_angle as wrap
from tianracer_sim.rotation import yaw_from_quaternion as yaw_of
from tianracer_sim.sim_time import Stream, clock_stamp, drive_twist, sim_sleep, wait_connected
from tianracer_sim.sim_time import wait_for

WALL_TIMEOUT = 120.0
NS = '/diffbot'
CONTROLLER = NS + '/mobile_base_controller'




class DiffDriveControllerTest(unittest.TestCase):
    def setUp(self):
        rospy.init_node('test_diff_drive_controller')
        self.clock = Stream('/clock', Clock, stamp=clock_stamp, keep=1)
        self.odom = Stream(CONTROLLER + '/odom', Odometry)
        self.truth = Stream(NS + '/ground_truth/odom', Odometry)
        self.cmd_out = Stream(CONTROLLER + '/cmd_vel_out', TwistStamped)
        self.wheel_state = Stream(CONTROLLER + '/wheel_joint_controller_state',
                                  JointTrajectoryControllerState, keep=10)
        self.tf = {}
        self.log = []
        rospy.Subscriber('/tf', TFMessage, self.on_tf)
        rospy.Subscriber('/rosout', Log, lambda m: self.log.append(m.msg))
        self.cmd = rospy.Publisher(CONTROLLER + '/cmd_vel', Twist, queue_size=1)
        wait_for(lambda: self.clock.latest(), '/clock', WALL_TIMEOUT)
        wait_connected(self.cmd)

    def on_tf(self, msg):
        for t in msg.transforms:
            self.tf[(t.header.frame_id, t.child_frame_id)] = t

    def drive(self, v, w, rate=50):
        """Settles 1 s at (v, w), then measures 2 s: (odom's twist, odom's poses, ground truth's
        poses), each as (forward speed, yaw rate)."""
        drive_twist(self.cmd, 1.0, v, w, wall_timeout=WALL_TIMEOUT)
        t0 = rospy.get_time()
        drive_twist(self.cmd, 2.0, v, w, wall_timeout=WALL_TIMEOUT)
        t1 = rospy.get_time()
        self.truth.first_stamped(t1)
        self.odom.first_stamped(t1)
        odom = self.odom.between(t0, t1)
        truth = self.truth.between(t0, t1)
        self.assertGreater(len(odom), 1.9 * rate)  # odom at `rate` Hz for 2 s
        self.assertGreater(len(truth), 50)
        twist = (sum(m.twist.twist.linear.x for m in odom) / len(odom),
                 sum(m.twist.twist.angular.z for m in odom) / len(odom))
        from_odom = motion([(m.header.stamp.to_sec(), m.pose.pose) for m in odom])
        from_truth = motion([(m.header.stamp.to_sec(), m.pose.pose) for m in truth])
        print('diff_drive_controller (v %.2f, w %.2f): odom twist %.4f %.4f, odom poses %.4f %.4f, '
              'ground truth %.4f %.4f' % ((v, w) + twist + from_odom + from_truth))
        return twist, from_odom, from_truth

    def assert_speeds(self, measured, v, w, what, tolerance):
        for got, want, name in zip(measured, (v, w), ('speed', 'yaw rate')):
            self.assertAlmostEqual(got, want, delta=tolerance * max(abs(want), 0.5),
                                   msg='%s %s: %.4f, commanded %.4f' % (what, name, got, want))

    def truth_speed(self, seconds):
        t0 = rospy.get_time()
        sim_sleep(seconds, wall_timeout=WALL_TIMEOUT)
        t1 = rospy.get_time()
        self.truth.first_stamped(t1)
        return motion([(m.header.stamp.to_sec(), m.pose.pose) for m in self.truth.between(t0, t1)])

    def test_driven_through_cmd_vel(self):
        # Both controllers run; the joint states come from joint_state_controller.
        rospy.wait_for_service(NS + '/controller_manager/list_controllers', timeout=WALL_TIMEOUT)
        listed = rospy.ServiceProxy(NS + '/controller_manager/list_controllers', ListControllers)()
        states = {c.name: (c.type, c.state) for c in listed.controller}
        self.assertEqual(states['mobile_base_controller'],
                         ('diff_drive_controller/DiffDriveController', 'running'))
        base = [c for c in listed.controller if c.name == 'mobile_base_controller'][0]
        self.assertEqual(base.claimed_resources[0].hardware_interface,
                         'hardware_interface::VelocityJointInterface')
        self.assertEqual(sorted(base.claimed_resources[0].resources),
                         ['left_wheel_joint', 'right_wheel_joint'])
        js = Stream(NS + '/joint_states', JointState)
        js.first(lambda s, m: 'left_wheel_joint' in m.name, 'joint_states')

        start = self.truth.first(lambda s, m: True, 'ground truth')[2].pose.pose
        for v, w in ((0.5, 0.0), (0.0, 0.8), (0.3, 0.6)):
            twist, odom, truth = self.drive(v, w)
            self.assert_speeds(twist, v, w, 'odom twist', 0.03)
            self.assert_speeds(odom, v, w, 'odom poses', 0.03)
            self.assert_speeds(truth, v, w, 'ground truth', 0.06)

        # odom's pose is ground truth's, relative to where it started (world -> odom at spawn).
        t = rospy.get_time()
        self.odom.first_stamped(t)
        odom = self.odom.latest()
        truth = min(self.truth.messages(),
                    key=lambda m: abs(m.header.stamp.to_sec() - odom.header.stamp.to_sec()))
        p, q = odom.pose.pose, truth.pose.pose
        yaw0 = yaw_of(start.orientation)
        dx, dy = q.position.x - start.position.x, q.position.y - start.position.y
        tx, ty = math.cos(yaw0) * dx + math.sin(yaw0) * dy, -math.sin(yaw0) * dx + math.cos(yaw0) * dy
        print('odom (%.4f %.4f %.4f), ground truth from the start (%.4f %.4f %.4f)' % (
            p.position.x, p.position.y, yaw_of(p.orientation), tx, ty,
            wrap(yaw_of(q.orientation) - yaw0)))
        self.assertAlmostEqual(p.position.x, tx, delta=0.02)
        self.assertAlmostEqual(p.position.y, ty, delta=0.02)
        self.assertAlmostEqual(wrap(yaw_of(p.orientation) - yaw_of(q.orientation) + yaw0), 0.0,
                               delta=0.03)
        self.assertEqual((odom.header.frame_id, odom.child_frame_id), ('odom', 'base_link'))
        self.assertEqual(odom.pose.covariance[0], 0.001)
        self.assertEqual(odom.twist.covariance[35], 1000.0)
        # /tf odom -> base_link is odom's pose at the same stamp.
        tf = wait_for(lambda: self.tf.get(('odom', 'base_link')), 'TF odom -> base_link',
                      WALL_TIMEOUT)
        same = [m for m in self.odom.messages()
                if abs(m.header.stamp.to_sec() - tf.header.stamp.to_sec()) < 1e-6]
        self.assertTrue(same)
        self.assertAlmostEqual(tf.transform.translation.x, same[-1].pose.pose.position.x, delta=1e-9)
        self.assertAlmostEqual(tf.transform.translation.y, same[-1].pose.pose.position.y, delta=1e-9)
        # cmd_vel_out: the commands after the (here absent) limits.
        last = self.cmd_out.latest()
        self.assertAlmostEqual(last.twist.linear.x, 0.3, delta=1e-9)
        self.assertAlmostEqual(last.twist.angular.z, 0.6, delta=1e-9)
        # wheel_joint_controller_state (publish_wheel_joint_controller_state): every update,
        # the wheels' desired (from the limited command), actual and error.
        ws = self.wheel_state.latest()
        self.assertEqual(list(ws.joint_names), ['left_wheel_joint', 'right_wheel_joint'])
        for point in (ws.desired, ws.actual, ws.error):
            self.assertEqual(len(point.positions), 2)
            self.assertEqual(len(point.velocities), 2)
        self.assertLess(ws.desired.velocities[0], ws.desired.velocities[1])  # turning left
        for k in range(2):
            self.assertTrue(math.isnan(ws.desired.effort[k]))
            self.assertAlmostEqual(ws.actual.velocities[k], ws.desired.velocities[k],
                                   delta=0.05 * abs(ws.desired.velocities[k]))
            self.assertAlmostEqual(ws.error.velocities[k],
                                   ws.desired.velocities[k] - ws.actual.velocities[k], delta=1e-9)

        # No command for longer than cmd_vel_timeout: it stops.
        drive_twist(self.cmd, 0.5, 0.5, 0.0, wall_timeout=WALL_TIMEOUT)
        sim_sleep(1.5, wall_timeout=WALL_TIMEOUT)  # 0.5 s timeout, then braking at 1 m/s^2
        v, w = self.truth_speed(1.0)
        print('after the timeout: ground truth %.4f %.4f' % (v, w))
        self.assertAlmostEqual(v, 0.0, delta=0.01)
        self.assertAlmostEqual(w, 0.0, delta=0.01)
        self.assertAlmostEqual(self.cmd_out.latest().twist.linear.x, 0.0)

        # A NaN command: ignored with upstream's warning; the last good command stays.
        # Measured only while the last good command is inside cmd_vel_timeout (0.5 s): that
        # command reaches the simulator at or after t0 of this process's clock, so the window
        # [t0, t0 + 0.45] ends before the timeout however late the NaN loop wakes.
        drive_twist(self.cmd, 1.0, 0.4, 0.0, wall_timeout=WALL_TIMEOUT)
        bad = Twist()
        bad.linear.x = float('nan')
        t0 = rospy.get_time()
        sim_sleep(0.3, each=lambda: self.cmd.publish(bad), poll=0.02)
        t1 = min(rospy.get_time(), t0 + 0.45)
        self.truth.first_stamped(t1)
        window = self.truth.between(t0, t1)
        self.assertGreater(len(window), 10)
        speed, _ = motion([(m.header.stamp.to_sec(), m.pose.pose) for m in window])
        self.assertAlmostEqual(speed, 0.4, delta=0.06 * 0.4)
        wait_for(lambda: any('Received NaN in velocity command. Ignoring.' in m for m in self.log),
                 'the warning about the NaN command on /rosout', WALL_TIMEOUT)

        # A second DiffDriveController whose wheel the URDF lacks: refused with upstream's
        # message; the running one drives on.
        rospy.set_param(NS + '/bad_base_controller', {
            'type': 'diff_drive_controller/DiffDriveController',
            'left_wheel': 'front_left_wheel_joint', 'right_wheel': 'right_wheel_joint'})
        load = rospy.ServiceProxy(NS + '/controller_manager/load_controller', LoadController)
        self.assertFalse(load('bad_base_controller').ok)
        wait_for(lambda: any('front_left_wheel_joint couldn\'t be retrieved from model description'
                             in m for m in self.log),
                 'the error about the missing wheel joint', WALL_TIMEOUT)
        twist, _, truth = self.drive(0.5, 0.0)
        self.assert_speeds(truth, 0.5, 0.0, 'ground truth after the refused load', 0.06)

        # dynamic_reconfigure (cfg/DiffDriveController.cfg): publish_rate 10 Hz, the wheel
        # separation taken 1.5 times as wide (a turn command then turns the wheels 1.5 times as
        # fast: the robot turns at 1.5 times the command, and its odometry, computed with the
        # same separation, says the commanded rate).
        client = dynamic_reconfigure.client.Client(CONTROLLER, timeout=WALL_TIMEOUT)
        config = client.update_configuration({'publish_rate': 10.0,
                                              'wheel_separation_multiplier': 1.5})
        self.assertEqual(config['publish_rate'], 10.0)
        t0 = rospy.get_time()
        drive_twist(self.cmd, 1.0, 0.0, 0.4, wall_timeout=WALL_TIMEOUT)
        t1 = rospy.get_time()
        self.truth.first_stamped(t1)
        n = len(self.odom.between(t0 + 0.2, t1))
        print('odom messages in 0.8 s at publish_rate 10: %d' % n)
        self.assertIn(n, (7, 8, 9))
        twist, odom, truth = self.drive(0.0, 0.4, rate=10)
        self.assert_speeds(twist, 0.0, 0.4, 'odom twist, separation x 1.5', 0.03)
        self.assert_speeds(truth, 0.0, 0.6, 'ground truth, separation x 1.5', 0.06)


if __name__ == '__main__':
    rostest.rosrun('tianracer_sim', 'diff_drive_controller', DiffDriveControllerTest)
