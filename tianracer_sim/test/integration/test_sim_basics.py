#!/usr/bin/env python3
"""rostest: the sim node publishes /clock and the seed's joint_states, obeys controller
commands, and serves Gazebo's pause and reset services. Times are sim time."""
import math
import threading
import unittest

import rospy
import rostest
from nav_msgs.msg import Odometry
from rosgraph_msgs.msg import Clock
from sensor_msgs.msg import JointState
from std_msgs.msg import Float64
from std_srvs.srv import Empty

SEED_JOINTS = {'left_rear_wheel_joint', 'right_rear_wheel_joint', 'left_steering_hinge_joint',
               'right_steering_hinge_joint', 'right_front_wheel_joint', 'left_front_wheel_joint'}


class SimBasics(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node('test_sim_basics')
        cls.lock = threading.Lock()
        cls.clock = []
        cls.joint_states = []
        cls.truth = None
        rospy.Subscriber('/clock', Clock, cls.on_clock, queue_size=1000)
        rospy.Subscriber('/tianracer/joint_states', JointState, cls.on_js, queue_size=1000)
        rospy.Subscriber('/tianracer/ground_truth/odom', Odometry, cls.on_truth, queue_size=10)
        for srv in ('pause_physics', 'unpause_physics', 'reset_simulation'):
            rospy.wait_for_service('/gazebo/' + srv, timeout=30)
        cls.pause = rospy.ServiceProxy('/gazebo/pause_physics', Empty)
        cls.unpause = rospy.ServiceProxy('/gazebo/unpause_physics', Empty)
        cls.reset = rospy.ServiceProxy('/gazebo/reset_simulation', Empty)

    @classmethod
    def on_clock(cls, msg):
        with cls.lock:
            cls.clock.append(msg.clock.to_sec())

    @classmethod
    def on_js(cls, msg):
        with cls.lock:
            cls.joint_states.append(msg)

    @classmethod
    def on_truth(cls, msg):
        cls.truth = msg

    def wait_sim(self, seconds):
        """Waits `seconds` of sim time (rospy follows /clock)."""
        rospy.sleep(rospy.Duration.from_sec(seconds))

    def test_1_clock_advances(self):
        self.wait_sim(0.5)
        with self.lock:
            t = list(self.clock)
        self.assertGreater(len(t), 10)
        self.assertGreater(t[-1], t[0])
        self.assertTrue(all(b >= a for a, b in zip(t, t[1:])), 'clock went backwards')

    def test_2_joint_states_seed_joints_at_50hz(self):
        self.wait_sim(0.2)
        with self.lock:
            del self.joint_states[:]
        self.wait_sim(2.0)
        with self.lock:
            msgs = list(self.joint_states)
        self.assertTrue(msgs)
        for m in msgs:
            self.assertEqual(set(m.name), SEED_JOINTS)
            self.assertEqual(len(m.name), 6)
            self.assertEqual(len(m.position), 6)
            self.assertEqual(len(m.velocity), 6)
            self.assertTrue(all(math.isfinite(x) for x in m.position + m.velocity))
        stamps = [m.header.stamp.to_sec() for m in msgs]
        rate = (len(stamps) - 1) / (stamps[-1] - stamps[0])
        rospy.loginfo('joint_states rate %.2f Hz (sim time), %d messages', rate, len(stamps))
        self.assertAlmostEqual(rate, 50.0, delta=5.0)

    def test_3_wheel_commands_move_the_car_forward(self):
        self.wait_sim(0.2)
        x0 = self.truth.pose.pose.position.x
        pubs = [rospy.Publisher('/tianracer/%s_rear_wheel_velocity_controller/command' % s,
                                Float64, queue_size=1, latch=True) for s in ('left', 'right')]
        for p in pubs:
            p.publish(Float64(0.5 / 0.032))
        self.wait_sim(2.0)
        x1 = self.truth.pose.pose.position.x
        y1 = self.truth.pose.pose.position.y
        rospy.loginfo('ground truth moved from x %.3f to %.3f (y %.3f)', x0, x1, y1)
        self.assertGreater(x1 - x0, 0.5)  # about 0.5 m/s for ~2 s, after spin-up
        self.assertLess(abs(y1), 0.05)
        for p in pubs:
            p.publish(Float64(0.0))
        self.wait_sim(0.5)

    def test_4_pause_stops_the_clock_and_reset_returns_to_spawn(self):
        self.pause()
        rospy.rostime.wallsleep(0.2)  # let in-flight /clock messages arrive
        with self.lock:
            paused_at = self.clock[-1]
        # Sim time cannot measure a pause: this wait is wall time on purpose.
        rospy.rostime.wallsleep(1.0)
        with self.lock:
            self.assertEqual(self.clock[-1], paused_at)
        self.unpause()
        self.wait_sim(0.2)
        with self.lock:
            self.assertGreater(self.clock[-1], paused_at)
        self.assertGreater(abs(self.truth.pose.pose.position.x), 0.3)  # moved by test 3
        self.reset()
        rospy.rostime.wallsleep(0.5)
        with self.lock:
            t_after = self.clock[-1]
        self.assertLess(t_after, paused_at)
        deadline = rospy.rostime.get_rostime()  # sim time restarted near 0
        self.assertLess(deadline.to_sec(), paused_at)
        self.wait_sim(0.2)
        p = self.truth.pose.pose.position
        self.assertLess(math.hypot(p.x, p.y), 0.01)

    def test_5_non_finite_commands_are_ignored(self):
        pubs = [rospy.Publisher('/tianracer/%s' % c, Float64, queue_size=10)
                for c in ('left_rear_wheel_velocity_controller/command',
                          'left_steering_hinge_position_controller/command')]
        rospy.rostime.wallsleep(0.5)  # connections
        for value in (float('nan'), float('inf'), -float('inf')):
            for p in pubs:
                p.publish(Float64(value))
        self.wait_sim(1.0)
        with self.lock:
            js = self.joint_states[-1]
            t = self.clock[-1]
        self.wait_sim(0.2)
        with self.lock:
            self.assertGreater(self.clock[-1], t)  # still stepping
        self.assertTrue(all(math.isfinite(x) for x in js.position + js.velocity + js.effort))
        p = self.truth.pose.pose
        self.assertTrue(all(math.isfinite(v) for v in (p.position.x, p.position.y, p.position.z,
                                                        p.orientation.w)))


if __name__ == '__main__':
    rostest.rosrun('tianracer_sim', 'sim_basics', SimBasics)
