#!/usr/bin/env python3
"""rostest: the sim node publishes /clock and the seed's joint_states, obeys controller
commands, and serves Gazebo's pause and reset services (pause_physics puts the paused time on
/clock once more, so that a client can wait for it); a PID controller publishes its `state`
as ros_controllers' does. Times are sim time."""
import math
import unittest

import rospy
import rostest
from control_msgs.msg import JointControllerState
from gazebo_msgs.srv import GetWorldProperties
from nav_msgs.msg import Odometry
from rosgraph_msgs.msg import Clock
from sensor_msgs.msg import JointState
from std_msgs.msg import Float64
from std_srvs.srv import Empty
from tianracer_sim.sim_time import (Paused, Stream, clock_stamp, connect_gazebo,
                                    messages_received, published_rate, sim_sleep, wait_connected,
                                    wait_for)

SIM = '/tianracer_sim'

SEED_JOINTS = {'left_rear_wheel_joint', 'right_rear_wheel_joint', 'left_steering_hinge_joint',
               'right_steering_hinge_joint', 'right_front_wheel_joint', 'left_front_wheel_joint'}


class SimBasics(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node('test_sim_basics')
        cls.clock = Stream('/clock', Clock, stamp=clock_stamp)
        cls.joint_states = Stream('/tianracer/joint_states', JointState)
        cls.truth = Stream('/tianracer/ground_truth/odom', Odometry)
        connect_gazebo(cls, {'pause_physics': Empty, 'unpause_physics': Empty,
                             'reset_simulation': Empty,
                             'get_world_properties': GetWorldProperties}, 30)
        cls.truth.wait_count(1)

    def truth_at(self, t):
        """Ground truth stamped t or later."""
        return self.truth.first_stamped(t, self.truth.count() - 1)

    def test_1_clock_advances(self):
        n = self.clock.count()
        sim_sleep(0.5)
        t = self.clock.stamps(n)
        self.assertGreater(len(t), 10)
        self.assertGreater(t[-1], t[0])
        self.assertTrue(all(b >= a for a, b in zip(t, t[1:])), 'clock went backwards')

    def test_2_joint_states_seed_joints_at_50hz(self):
        t0 = self.joint_states.wait_count(self.joint_states.count() + 1).header.stamp.to_sec()
        self.joint_states.first_stamped(t0 + 2.0)
        msgs = self.joint_states.between(t0, t0 + 2.0)
        self.assertTrue(msgs)
        for m in msgs:
            self.assertEqual(set(m.name), SEED_JOINTS)
            self.assertEqual(len(m.name), 6)
            self.assertEqual(len(m.position), 6)
            self.assertEqual(len(m.velocity), 6)
            self.assertTrue(all(math.isfinite(x) for x in m.position + m.velocity))
        rate = published_rate(msgs)  # what the sim published (header.seq counts it)
        rospy.loginfo('joint_states rate %.2f Hz (sim time), %d messages', rate, len(msgs))
        self.assertAlmostEqual(rate, 50.0, delta=5.0)

    def test_3_wheel_commands_move_the_car_forward(self):
        pubs = [rospy.Publisher('/tianracer/%s_rear_wheel_velocity_controller/command' % s,
                                Float64, queue_size=1, latch=True) for s in ('left', 'right')]
        for p in pubs:
            wait_connected(p)
        # The commands apply from a known sim time: sent with the physics paused, read by the
        # sim (its getBusStats) before it steps on.
        with Paused() as paused:
            t0 = paused.t
            read = [messages_received(SIM, p.resolved_name) for p in pubs]
            for p in pubs:
                p.publish(Float64(0.5 / 0.032))
            wait_for(lambda: all(messages_received(SIM, p.resolved_name) > n
                                 for p, n in zip(pubs, read)), 'the sim reading the commands')
            x0 = self.truth.first(lambda s, m: s > t0 - 0.021, 'the ground truth at the pause',
                                  max(0, self.truth.count() - 10))[2].pose.pose.position.x
        end = self.truth_at(t0 + 2.0).pose.pose.position
        rospy.loginfo('ground truth moved from x %.3f to %.3f (y %.3f)', x0, end.x, end.y)
        self.assertGreater(end.x - x0, 0.5)  # about 0.5 m/s for ~2 s, after spin-up
        self.assertLess(abs(end.y), 0.05)
        for p in pubs:
            p.publish(Float64(0.0))
        sim_sleep(0.5)

    def test_4_pause_stops_the_clock_and_reset_returns_to_spawn(self):
        # pause_physics: the paused time (get_world_properties) comes on /clock once more, and
        # Paused waits for it.
        paused = Paused()
        paused_at = paused.t
        n = self.clock.count()
        # Sim time cannot measure a pause: this wait is wall time on purpose.
        rospy.rostime.wallsleep(1.0)
        self.assertEqual(self.get_world_properties().sim_time, paused_at)
        self.assertTrue(all(t == paused_at for t in self.clock.stamps(n)), self.clock.stamps(n))
        paused.unpause()
        self.clock.first(lambda s, m: s > paused_at, '/clock after the unpause', n)
        self.assertGreater(abs(self.truth.latest().pose.pose.position.x), 0.3)  # moved by test 3
        n, n_truth = self.clock.count(), self.truth.count()
        self.reset_simulation()
        # Sim time restarted near 0: the first /clock after the reset is below the paused time.
        _, t_after, _ = self.clock.first(lambda s, m: s < paused_at, '/clock after the reset', n)
        self.assertLess(t_after, 0.1)
        k, _, _ = self.truth.first(lambda s, m: s < paused_at, 'ground truth after the reset',
                                   n_truth)
        p = self.truth.first_stamped(t_after + 0.2, k).pose.pose.position
        self.assertLess(math.hypot(p.x, p.y), 0.01)

    def test_5_non_finite_commands_are_ignored(self):
        pubs = [rospy.Publisher('/tianracer/%s' % c, Float64, queue_size=10)
                for c in ('left_rear_wheel_velocity_controller/command',
                          'left_steering_hinge_position_controller/command')]
        for p in pubs:
            wait_connected(p)
        for value in (float('nan'), float('inf'), -float('inf')):
            for p in pubs:
                p.publish(Float64(value))
        t = rospy.get_time()
        js = self.joint_states.first_stamped(t + 1.0, self.joint_states.count())
        self.clock.first_stamped(t + 1.2, self.clock.count())  # still stepping
        self.assertTrue(all(math.isfinite(x) for x in js.position + js.velocity + js.effort))
        p = self.truth.latest().pose.pose
        self.assertTrue(all(math.isfinite(v) for v in (p.position.x, p.position.y, p.position.z,
                                                        p.orientation.w)))

    def test_6_a_pid_controller_publishes_its_state(self):
        # effort_controllers/JointPositionController's `state` (control_msgs/JointControllerState):
        # every 10th control update, the set point commanded, the error, the YAML's gains.
        name = '/tianracer/left_steering_hinge_position_controller/'
        state = Stream(name + 'state', JointControllerState)
        cmd = rospy.Publisher(name + 'command', Float64, queue_size=1)
        wait_connected(cmd)
        cmd.publish(Float64(0.2))
        _, t0, _ = state.first(lambda s, m: abs(m.set_point - 0.2) < 1e-12,
                               'a state with the new set point')
        state.first_stamped(t0 + 1.0)
        msgs = state.between(t0, t0 + 1.0)
        last = msgs[-1]
        rate = published_rate(msgs)
        rospy.loginfo('state rate %.2f Hz (sim time), time_step %g s', rate, last.time_step)
        self.assertGreater(last.time_step, 0.0)
        self.assertAlmostEqual(rate, 1.0 / (10 * last.time_step), delta=0.02 * rate)
        self.assertEqual((last.p, last.i, last.d), (20.0, 0.0, 0.2))
        self.assertAlmostEqual(last.set_point, 0.2, delta=1e-12)
        self.assertAlmostEqual(last.process_value, 0.2, delta=0.02)
        self.assertAlmostEqual(last.error, last.set_point - last.process_value, delta=1e-9)
        self.assertTrue(all(math.isfinite(x) for x in (last.command, last.process_value_dot)))
        cmd.publish(Float64(0.0))


if __name__ == '__main__':
    rostest.rosrun('tianracer_sim', 'sim_basics', SimBasics)
