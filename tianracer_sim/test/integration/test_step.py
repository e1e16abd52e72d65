#!/usr/bin/env python3
"""rostest: step-locked control. ~step N makes exactly N steps from a paused simulation (the
data of the start go out with the first), answers with the new sim time after the messages of
the last step are published (the scan and ground truth stamped with it arrive, nothing later
does), and the simulation waits; a running one is paused first. ~step_and_wait does the same as
an action with feedback, and a cancel stops it. Sim time throughout; wall time bounds waits."""
import threading
import time
import unittest

import actionlib
import rospy
import rosservice
import rostest
from actionlib_msgs.msg import GoalStatus
from nav_msgs.msg import Odometry
from rosgraph_msgs.msg import Clock
from sensor_msgs.msg import LaserScan
from std_srvs.srv import Empty
from tianracer_sim.msg import StepAndWaitAction, StepAndWaitGoal
from tianracer_sim.srv import Step

WAIT = 60.0


class Stamps(object):
    def __init__(self, topic, cls, stamp):
        self.lock = threading.Lock()
        self.values = []
        self.sub = rospy.Subscriber(topic, cls, self.cb, callback_args=stamp, queue_size=2000,
                                    tcp_nodelay=True)

    def cb(self, msg, stamp):
        with self.lock:
            self.values.append(stamp(msg).to_sec())

    def latest(self):
        with self.lock:
            return max(self.values) if self.values else -1.0

    def has(self, t):
        with self.lock:
            return any(abs(v - t) < 1e-9 for v in self.values)

    def wait_for(self, t):
        deadline = time.time() + WAIT
        while time.time() < deadline and not self.has(t):
            time.sleep(0.01)
        return self.has(t)


class StepTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node('test_step')
        cls.clock = Stamps('/clock', Clock, lambda m: m.clock)
        cls.scan = Stamps('/scan', LaserScan, lambda m: m.header.stamp)
        cls.truth = Stamps('/tianracer/ground_truth/odom', Odometry, lambda m: m.header.stamp)
        rospy.wait_for_service('/tianracer_sim/step', WAIT)
        cls.step = rospy.ServiceProxy('/tianracer_sim/step', Step)
        cls.action = actionlib.SimpleActionClient('/tianracer_sim/step_and_wait', StepAndWaitAction)
        assert cls.action.wait_for_server(rospy.Duration(WAIT))
        deadline = time.time() + WAIT
        while time.time() < deadline and (cls.scan.sub.get_num_connections() < 1 or
                                          cls.truth.sub.get_num_connections() < 1):
            time.sleep(0.05)
        time.sleep(0.5)

    def quiet(self, t, seconds=1.0):
        """Nothing after sim time t arrives for `seconds` of wall time: the simulation waits."""
        time.sleep(seconds)
        self.assertLessEqual(self.clock.latest(), t + 1e-9)
        self.assertLessEqual(self.truth.latest(), t + 1e-9)

    def test_1_step_from_the_paused_start(self):
        # Not started with ~profile: no step profile, no ~profile service (test_profile.py).
        self.assertNotIn('/tianracer_sim/profile', rosservice.get_service_list())
        r = self.step(25)
        self.assertTrue(r.success, r.status_message)
        self.assertEqual(r.step_count, 25)
        self.assertAlmostEqual(r.sim_time.to_sec(), 0.025, places=9)
        # The data of the start and of the last step (40 Hz scan: 0 and 0.025), and the clock.
        self.assertTrue(self.scan.wait_for(0.0))
        self.assertTrue(self.scan.wait_for(0.025))
        self.assertTrue(self.truth.wait_for(0.025))
        self.assertTrue(self.clock.wait_for(0.025))
        self.quiet(0.025)
        r = self.step(5)
        self.assertTrue(r.success)
        self.assertEqual(r.step_count, 30)
        self.assertTrue(self.truth.wait_for(0.030))
        self.quiet(0.030)

    def test_2_zero_steps_is_refused(self):
        r = self.step(0)
        self.assertFalse(r.success)
        self.assertIn('steps must be at least 1', r.status_message)

    def test_3_a_running_simulation_is_paused_first(self):
        rospy.ServiceProxy('/gazebo/unpause_physics', Empty)()
        deadline = time.time() + WAIT
        start = self.clock.latest()
        while time.time() < deadline and self.clock.latest() < start + 0.2:
            time.sleep(0.01)
        r = self.step(10)
        self.assertTrue(r.success, r.status_message)
        self.assertTrue(self.truth.wait_for(r.sim_time.to_sec()))
        self.quiet(r.sim_time.to_sec())

    def test_4_step_and_wait_with_feedback(self):
        before = self.step(1).sim_time.to_sec()
        feedback = []
        # Feedback goes out while the steps run (the waiting thread reports when it wakes), on
        # a topic of its own: 50 steps took 8 ms and could finish, and their result arrive,
        # before any feedback did. 1000 steps run long enough for it.
        steps = 1000
        self.action.send_goal(StepAndWaitGoal(steps=steps), feedback_cb=feedback.append)
        self.assertTrue(self.action.wait_for_result(rospy.Duration(WAIT)))
        result = self.action.get_result()
        self.assertEqual(self.action.get_state(), GoalStatus.SUCCEEDED)
        self.assertTrue(result.success)
        self.assertEqual(result.steps_done, steps)
        self.assertAlmostEqual(result.sim_time.to_sec(), before + steps * 0.001, places=9)
        self.assertTrue(self.truth.wait_for(result.sim_time.to_sec()))
        self.assertTrue(feedback)
        self.assertTrue(all(0 < f.steps_done <= steps for f in feedback))
        self.quiet(result.sim_time.to_sec())

    def test_5_cancel_stops_the_steps(self):
        self.action.send_goal(StepAndWaitGoal(steps=10000000))
        deadline = time.time() + WAIT
        start = self.clock.latest()
        while time.time() < deadline and self.clock.latest() < start + 0.1:
            time.sleep(0.01)
        self.action.cancel_goal()
        self.assertTrue(self.action.wait_for_result(rospy.Duration(WAIT)))
        self.assertEqual(self.action.get_state(), GoalStatus.PREEMPTED)
        result = self.action.get_result()
        self.assertFalse(result.success)
        self.assertIn('cancelled after', result.status_message)
        self.assertLess(result.steps_done, 10000000)
        self.quiet(result.sim_time.to_sec())


if __name__ == '__main__':
    rostest.rosrun('tianracer_sim', 'step', StepTest)
