#!/usr/bin/env python3
"""rostest: the drive plugins (libgazebo_ros_diff_drive, libgazebo_ros_skid_steer_drive,
libgazebo_ros_planar_move) driven through their cmd_vel, measured from their odometry and from
ground truth (libgazebo_ros_p3d), with their TF; one case per .test file (~case):
  diff_drive   diff_drive.test   robot diff_bot (test/data/urdf/diff_drive.urdf)
  skid_steer   skid_steer.test   robot skid_bot (test/data/urdf/skid_steer.urdf), namespace /skid
  planar_move  planar_move.test  world model 'mover' (test/data/worlds/planar_move.world)
Speeds are averages over 2 s of sim time after 1 s of settling; sim time throughout, wall time
only bounds the waits.
"""
import math
import os
import unittest

import rospkg
import rospy
import rostest
from gazebo_msgs.srv import SpawnModel
from geometry_msgs.msg import Pose, Twist
from nav_msgs.msg import Odometry
from rosgraph_msgs.msg import Clock, Log
from sensor_msgs.msg import JointState
from tf2_msgs.msg import TFMessage
from tianracer_sim.rotation import planar_motion as motion
from tianracer_sim.sim_time import Stream, clock_stamp, drive_twist, sim_sleep, wait_connected
from tianracer_sim.sim_time import wait_for

WALL_TIMEOUT = 120.0
TOLERANCE = 0.03  # relative




class DrivePluginsTest(unittest.TestCase):
    def setUp(self):
        rospy.init_node('test_drive_plugins')
        self.case = rospy.get_param('~case')
        ns, truth, self.base = {
            'diff_drive': ('/diff_bot', '/ground_truth', 'base_link'),
            'skid_steer': ('/skid', '/skid/ground_truth', 'base_link'),
            'planar_move': ('', '/mover/truth', 'mover'),
        }[self.case]
        self.clock = Stream('/clock', Clock, stamp=clock_stamp, keep=1)
        self.odom = Stream(ns + '/odom', Odometry)
        self.truth = Stream(truth, Odometry)
        self.tf = {}
        self.log = []
        rospy.Subscriber('/tf', TFMessage, self.on_tf)
        rospy.Subscriber('/rosout', Log, lambda m: self.log.append(m.msg))
        self.cmd = rospy.Publisher(ns + '/cmd_vel', Twist, queue_size=1)
        wait_for(lambda: self.clock.latest(), '/clock', WALL_TIMEOUT)
        wait_connected(self.cmd)

    def on_tf(self, msg):
        for t in msg.transforms:
            self.tf[(t.header.frame_id, t.child_frame_id)] = t

    def drive(self, v, w):
        """Settles 1 s at (v, w), then measures 2 s: (odometry's twist, odometry's poses,
        ground truth's poses), each as (forward speed, yaw rate)."""
        drive_twist(self.cmd, 1.0, v, w, wall_timeout=WALL_TIMEOUT)
        t0 = rospy.get_time()
        drive_twist(self.cmd, 2.0, v, w, wall_timeout=WALL_TIMEOUT)
        t1 = rospy.get_time()
        self.truth.first_stamped(t1)
        self.odom.first_stamped(t1)
        odom = self.odom.between(t0, t1)
        truth = self.truth.between(t0, t1)
        self.assertGreater(len(odom), 20)
        self.assertGreater(len(truth), 20)
        twist = (sum(m.twist.twist.linear.x for m in odom) / len(odom),
                 sum(m.twist.twist.angular.z for m in odom) / len(odom))
        from_odom = motion([(m.header.stamp.to_sec(), m.pose.pose) for m in odom])
        from_truth = motion([(m.header.stamp.to_sec(), m.pose.pose) for m in truth])
        print('%s (v %.2f, w %.2f): odometry twist %.4f %.4f, odometry poses %.4f %.4f, '
              'ground truth %.4f %.4f' % ((self.case, v, w) + twist + from_odom + from_truth))
        return twist, from_odom, from_truth

    def assert_speeds(self, measured, v, w, what):
        for got, want, name in zip(measured, (v, w), ('speed', 'yaw rate')):
            self.assertAlmostEqual(got, want, delta=TOLERANCE * max(abs(want), 0.5),
                                   msg='%s %s: %.4f, commanded %.4f' % (what, name, got, want))

    def check_tf(self, odom_frame):
        key = (odom_frame, self.base)
        t = wait_for(lambda: self.tf.get(key), 'TF %s -> %s' % key, WALL_TIMEOUT)
        # The TF is the odometry's pose (same stamp).
        stamp = t.header.stamp.to_sec()
        msgs = [m for m in self.odom.messages() if abs(m.header.stamp.to_sec() - stamp) < 1e-6]
        if msgs:
            p = msgs[-1].pose.pose.position
            self.assertAlmostEqual(t.transform.translation.x, p.x, delta=1e-6)
            self.assertAlmostEqual(t.transform.translation.y, p.y, delta=1e-6)

    def check_nan_is_ignored(self, v, w):
        """A NaN command is refused with a warning; the last good one stays."""
        drive_twist(self.cmd, 0.5, v, w, wall_timeout=WALL_TIMEOUT)
        bad = Twist()
        bad.linear.x = float('nan')
        t0 = rospy.get_time()
        sim_sleep(1.0, each=lambda: self.cmd.publish(bad), poll=0.05)
        t1 = rospy.get_time()
        self.truth.first_stamped(t1)
        truth = self.truth.between(t0, t1)
        speed, _ = motion([(m.header.stamp.to_sec(), m.pose.pose) for m in truth])
        self.assertAlmostEqual(speed, v, delta=TOLERANCE * v)
        last = self.odom.latest()
        self.assertTrue(all(math.isfinite(x) for x in (last.pose.pose.position.x,
                                                         last.twist.twist.linear.x)))
        wait_for(lambda: any('non-finite command' in m for m in self.log),
                 'the warning about the NaN command on /rosout', WALL_TIMEOUT)

    def test_drive(self):
        getattr(self, 'case_' + self.case)()

    def assert_follows(self, commands):
        """Drives each (v, w) of `commands`: the odometry twist and poses and the ground truth
        move at v and w."""
        for v, w in commands:
            twist, odom, truth = self.drive(v, w)
            self.assert_speeds(twist, v, w, 'odometry twist')
            self.assert_speeds(odom, v, w, 'odometry poses')
            self.assert_speeds(truth, v, w, 'ground truth')

    def case_diff_drive(self):
        self.assert_follows(((0.5, 0.0), (0.0, 0.5), (0.5, 0.5)))
        msg = self.odom.latest()
        self.assertEqual((msg.header.frame_id, msg.child_frame_id), ('odom', 'base_link'))
        self.assertEqual(msg.pose.covariance[0], 0.00001)
        self.assertEqual(msg.pose.covariance[35], 0.001)
        self.assertAlmostEqual(msg.pose.pose.position.z, 0.05, delta=0.01)  # world source: z
        self.check_tf('odom')
        # publishWheelTF: each wheel in base_link, on its axle 0.12 m to the side.
        t = wait_for(lambda: self.tf.get(('base_link', 'left_wheel')), 'wheel TF', WALL_TIMEOUT)
        self.assertAlmostEqual(t.transform.translation.y, 0.12, delta=1e-6)
        # publishWheelJointState: names and positions.
        js = Stream('/diff_bot/joint_states', JointState)
        msg = js.first(lambda s, m: list(m.name) == ['left_wheel_joint', 'right_wheel_joint'],
                       'the wheels\' joint states')[2]
        self.assertEqual(len(msg.position), 2)
        self.assertEqual(len(msg.velocity), 0)
        self.check_nan_is_ignored(0.5, 0.5)
        # A robot spawned with a bad plugin: told why, and this one drives on.
        urdf_path = os.path.join(rospkg.RosPack().get_path('tianracer_sim'),
                                 'test/data/urdf/diff_drive.urdf')
        with open(urdf_path) as f:
            urdf = f.read()
        urdf = urdf.replace('<wheelDiameter>0.1</wheelDiameter>', '<wheelDiameter>0</wheelDiameter>')
        urdf = urdf[:urdf.index('<plugin name="truth"')] + urdf[urdf.index('</plugin>', urdf.index('<plugin name="truth"')) + 9:]
        rospy.wait_for_service('/gazebo/spawn_urdf_model', timeout=WALL_TIMEOUT)
        spawn = rospy.ServiceProxy('/gazebo/spawn_urdf_model', SpawnModel)
        pose = Pose()
        pose.position.x, pose.position.y, pose.orientation.w = -3.0, -3.0, 1.0
        res = spawn(model_name='bad_bot', model_xml=urdf, robot_namespace='', initial_pose=pose,
                    reference_frame='world')
        self.assertTrue(res.success, res.status_message)
        wait_for(lambda: any("diff_drive plugin 'diff_drive' of model 'bad_bot': <wheelDiameter> 0 "
                             "must be > 0" in m for m in self.log),
                 'the error about wheelDiameter', WALL_TIMEOUT)
        twist, _, truth = self.drive(0.5, 0.0)
        self.assert_speeds(truth, 0.5, 0.0, 'ground truth after the bad spawn')

    def case_skid_steer(self):
        twist, odom, truth = self.drive(0.5, 0.0)
        self.assert_speeds(twist, 0.5, 0.0, 'odometry twist')
        self.assert_speeds(odom, 0.5, 0.0, 'odometry poses')
        self.assert_speeds(truth, 0.5, 0.0, 'ground truth')
        # Turning on the spot the wheels scrub: the yaw rate is what friction leaves of the
        # command, and the odometry (world source) tells the truth.
        twist, odom, truth = self.drive(0.0, 0.5)
        self.assertGreater(truth[1], 0.25)
        self.assertAlmostEqual(odom[1], truth[1], delta=TOLERANCE * truth[1])
        msg = self.odom.latest()
        self.assertEqual((msg.header.frame_id, msg.child_frame_id), ('odom', 'base_link'))
        self.assertEqual(msg.pose.pose.position.z, 0.0)  # the skid steer leaves z out
        self.assertEqual(msg.pose.covariance[7], 0.002)
        self.assertEqual(msg.twist.covariance[35], 0.03)
        self.check_tf('odom')

    def case_planar_move(self):
        self.assert_follows(((0.5, 0.5),))
        msg = self.odom.latest()
        self.assertEqual((msg.header.frame_id, msg.child_frame_id), ('odom', 'mover'))
        self.check_tf('odom')
        self.check_nan_is_ignored(0.5, 0.5)


if __name__ == '__main__':
    rostest.rosrun('tianracer_sim', 'drive_plugins', DrivePluginsTest)
