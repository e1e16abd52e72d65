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
from tianracer_sim.msg import (StepAndWaitAction, StepAndWaitActionFeedback, StepAndWaitActionGoal,
                               StepAndWaitGoal)
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
        # The feedback as the server sends it, on its own subscriber: the client's feedback_cb
        # drops what comes after the result, and ROS does not order the feedback and result
        # connections (a test process starved while the steps run may read the result first).
        cls.feedback_lock = threading.Lock()
        cls.feedback = []
        cls.feedback_sub = rospy.Subscriber('/tianracer_sim/step_and_wait/feedback',
                                            StepAndWaitActionFeedback, cls.on_feedback,
                                            queue_size=5000)
        # The ids of the goals this client sends, read off the action's goal topic (the
        # client's public interface does not return them).
        cls.goal_ids = []
        cls.goal_sub = rospy.Subscriber('/tianracer_sim/step_and_wait/goal', StepAndWaitActionGoal,
                                        cls.on_goal, queue_size=100)
        assert cls.action.wait_for_server(rospy.Duration(WAIT))
        deadline = time.time() + WAIT
        while time.time() < deadline and (cls.scan.sub.get_num_connections() < 1 or
                                          cls.truth.sub.get_num_connections() < 1 or
                                          cls.feedback_sub.get_num_connections() < 1 or
                                          cls.goal_sub.get_num_connections() < 1):
            time.sleep(0.05)
        time.sleep(0.5)

    @classmethod
    def on_feedback(cls, msg):
        with cls.feedback_lock:
            cls.feedback.append((msg.status.goal_id.id, msg.feedback.steps_done))

    @classmethod
    def on_goal(cls, msg):
        with cls.feedback_lock:
            cls.goal_ids.append(msg.goal_id.id)

    def sent_goal_id(self, count_before):
        """The id of the goal sent after `count_before` goals, once the goal topic carried it."""
        deadline = time.time() + WAIT
        while time.time() < deadline:
            with self.feedback_lock:
                if len(self.goal_ids) > count_before:
                    return self.goal_ids[count_before]
            time.sleep(0.01)
        self.fail('the goal never appeared on /tianracer_sim/step_and_wait/goal')

    def feedback_of(self, goal_id):
        with self.feedback_lock:
            return [done for g, done in self.feedback if g == goal_id]

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
        # Feedback goes out while the steps run (the waiting thread reports when it wakes): 50
        # steps took 8 ms and could finish before any feedback did; 1000 steps run long enough.
        steps = 1000
        with self.feedback_lock:
            sent = len(self.goal_ids)
        self.action.send_goal(StepAndWaitGoal(steps=steps))
        goal_id = self.sent_goal_id(sent)
        self.assertTrue(self.action.wait_for_result(rospy.Duration(WAIT)))
        result = self.action.get_result()
        self.assertEqual(self.action.get_state(), GoalStatus.SUCCEEDED)
        self.assertTrue(result.success, result.status_message)
        self.assertEqual(result.steps_done, steps)
        self.assertAlmostEqual(result.sim_time.to_sec(), before + steps * 0.001, places=9)
        self.assertTrue(self.truth.wait_for(result.sim_time.to_sec()))
        deadline = time.time() + WAIT
        while time.time() < deadline and not self.feedback_of(goal_id):
            time.sleep(0.01)
        feedback = self.feedback_of(goal_id)
        self.assertTrue(feedback, 'no feedback for goal %s' % goal_id)
        self.assertTrue(all(0 < done <= steps for done in feedback), feedback[:20])
        self.assertEqual(feedback, sorted(feedback))
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
