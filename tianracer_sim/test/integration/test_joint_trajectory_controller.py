#!/usr/bin/env python3
"""rostest: joint_trajectory_controller (position_controllers/JointTrajectoryController) on
arm_control.urdf, through ROS only, with a python actionlib client: a goal SUCCEEDED and the
joints' final joint_states within its goal tolerance; a goal with a path tolerance it cannot
keep ABORTED with PATH_TOLERANCE_VIOLATED and upstream's error_string; a goal preempted by a
newer one; a cancel holding position; bad goals (NaN, unknown joints) REJECTED with upstream's
error codes while the controller goes on; a controller with a bad 'joints' refused while the
others run; the command topic; state at state_publish_rate;
query_state. Sim time throughout."""
import math
import unittest

import actionlib
import rospy
import rostest
from actionlib_msgs.msg import GoalStatus
from control_msgs.msg import (FollowJointTrajectoryAction, FollowJointTrajectoryGoal,
                              FollowJointTrajectoryResult, JointTolerance,
                              JointTrajectoryControllerState)
from control_msgs.srv import QueryTrajectoryState
from controller_manager_msgs.srv import ListControllers, LoadController
from rosgraph_msgs.msg import Clock
from sensor_msgs.msg import JointState
from trajectory_msgs.msg import JointTrajectory, JointTrajectoryPoint
from tianracer_sim.sim_time import Stream, action_finished, clock_stamp, sim_sleep, wait_connected, wait_for

WALL_TIMEOUT = 120.0
NS = '/arm'
CONTROLLER = NS + '/arm_controller'
JOINTS = ['shoulder_joint', 'elbow_joint']


def trajectory(points, joints=JOINTS):
    t = JointTrajectory()
    t.joint_names = list(joints)
    for seconds, positions in points:
        p = JointTrajectoryPoint()
        p.positions = list(positions)
        p.velocities = [0.0] * len(positions)
        p.time_from_start = rospy.Duration(seconds)
        t.points.append(p)
    return t


class JointTrajectoryControllerTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node('test_joint_trajectory_controller')
        cls.clock = Stream('/clock', Clock, stamp=clock_stamp, keep=1)
        cls.joint_states = Stream(NS + '/joint_states', JointState, keep=200)
        cls.state = Stream(CONTROLLER + '/state', JointTrajectoryControllerState, keep=400)
        wait_for(lambda: cls.clock.latest(), '/clock', WALL_TIMEOUT)
        cls.client = actionlib.SimpleActionClient(CONTROLLER + '/follow_joint_trajectory',
                                                  FollowJointTrajectoryAction)
        wait_for(lambda: cls.client.wait_for_server(rospy.Duration(0.1)), 'the action server',
                 WALL_TIMEOUT)

    def positions(self):
        self.joint_states.first_stamped(rospy.get_time())
        m = self.joint_states.latest()
        return [m.position[m.name.index(j)] for j in JOINTS]

    def send(self, goal, client=None):
        client = client or self.client
        client.send_goal(goal)
        return client

    def finished(self, client, what):
        return action_finished(client, what, WALL_TIMEOUT)

    def goal(self, points, joints=JOINTS):
        g = FollowJointTrajectoryGoal()
        g.trajectory = trajectory(points, joints)
        return g

    def test_0_loaded_with_its_claims_and_a_bad_one_refused(self):
        rospy.wait_for_service(NS + '/controller_manager/list_controllers', timeout=WALL_TIMEOUT)
        listed = rospy.ServiceProxy(NS + '/controller_manager/list_controllers', ListControllers)()
        states = {c.name: (c.type, c.state) for c in listed.controller}
        self.assertEqual(states['arm_controller'],
                         ('position_controllers/JointTrajectoryController', 'running'))
        arm = [c for c in listed.controller if c.name == 'arm_controller'][0]
        self.assertEqual(arm.claimed_resources[0].hardware_interface,
                         'hardware_interface::PositionJointInterface')
        self.assertEqual(sorted(arm.claimed_resources[0].resources), sorted(JOINTS))
        # bad input: 'joints' is no list: the load fails (upstream's message), the others run
        rospy.set_param(NS + '/bad_arm_controller',
                        {'type': 'effort_controllers/JointTrajectoryController',
                         'joints': 'shoulder_joint'})
        load = rospy.ServiceProxy(NS + '/controller_manager/load_controller', LoadController)
        self.assertFalse(load('bad_arm_controller').ok)
        listed = rospy.ServiceProxy(NS + '/controller_manager/list_controllers', ListControllers)()
        states = {c.name: c.state for c in listed.controller}
        self.assertNotIn('bad_arm_controller', states)
        self.assertEqual(states['arm_controller'], 'running')

    def test_1_goal_succeeds_and_the_joints_end_there(self):
        target = [0.8, -0.6]
        state, result = self.finished(
            self.send(self.goal([(1.0, [0.4, -0.3]), (2.0, target)])), 'goal 1')
        self.assertEqual(state, GoalStatus.SUCCEEDED)
        self.assertEqual(result.error_code, FollowJointTrajectoryResult.SUCCESSFUL)
        got = self.positions()
        print('succeeded: joint_states %s, target %s' % (got, target))
        for g, want in zip(got, target):
            self.assertAlmostEqual(g, want, delta=0.02)  # the YAML's goal tolerance
        # query_state samples the held trajectory
        rospy.wait_for_service(CONTROLLER + '/query_state', WALL_TIMEOUT)
        query = rospy.ServiceProxy(CONTROLLER + '/query_state', QueryTrajectoryState)
        answer = query(rospy.Time.now())
        self.assertEqual(list(answer.name), JOINTS)
        for g, want in zip(answer.position, target):
            self.assertAlmostEqual(g, want, delta=0.02)
        # state at state_publish_rate (25 Hz), stamped with sim time
        t0 = rospy.get_time()
        sim_sleep(1.0, wall_timeout=WALL_TIMEOUT)
        states = self.state.between(t0, t0 + 1.0)
        self.assertTrue(22 <= len(states) <= 27, len(states))
        self.assertEqual(list(states[-1].joint_names), JOINTS)

    def test_2_path_tolerance_violation_aborts(self):
        g = self.goal([(1.0, [0.0, 0.0])])
        g.path_tolerance = [JointTolerance(name='shoulder_joint', position=1e-6)]
        state, result = self.finished(self.send(g), 'goal 2')
        print('aborted: %d %s' % (result.error_code, result.error_string))
        self.assertEqual(state, GoalStatus.ABORTED)
        self.assertEqual(result.error_code, FollowJointTrajectoryResult.PATH_TOLERANCE_VIOLATED)
        self.assertTrue(result.error_string.startswith('shoulder_joint path error '),
                        result.error_string)

    def test_3_preempted_by_a_newer_goal_then_canceled_holds(self):
        first = self.send(self.goal([(3.0, [1.5, 1.0]), (6.0, [-1.5, -1.0])]))
        wait_for(lambda: first.get_state() == GoalStatus.ACTIVE, 'goal 3 active', WALL_TIMEOUT)
        sim_sleep(0.5, wall_timeout=WALL_TIMEOUT)
        second = actionlib.SimpleActionClient(CONTROLLER + '/follow_joint_trajectory',
                                              FollowJointTrajectoryAction)
        wait_for(lambda: second.wait_for_server(rospy.Duration(0.1)), 'server', WALL_TIMEOUT)
        self.send(self.goal([(3.0, [-1.0, 1.0])]), second)
        state, _ = self.finished(first, 'goal 3 preempted')
        self.assertEqual(state, GoalStatus.PREEMPTED)
        wait_for(lambda: second.get_state() == GoalStatus.ACTIVE, 'goal 4 active', WALL_TIMEOUT)
        sim_sleep(1.0, wall_timeout=WALL_TIMEOUT)
        second.cancel_goal()
        state, _ = self.finished(second, 'goal 4 canceled')
        self.assertEqual(state, GoalStatus.PREEMPTED)
        sim_sleep(0.2, wall_timeout=WALL_TIMEOUT)
        held = self.positions()
        sim_sleep(1.0, wall_timeout=WALL_TIMEOUT)
        now = self.positions()
        print('held after cancel: %s then %s' % (held, now))
        for a, b in zip(held, now):
            self.assertAlmostEqual(a, b, delta=1e-3)

    def test_4_bad_goals_are_rejected_and_the_controller_goes_on(self):
        state, result = self.finished(
            self.send(self.goal([(1.0, [0.1, float('nan')])])), 'NaN goal')
        self.assertEqual(state, GoalStatus.REJECTED)
        self.assertEqual(result.error_code, FollowJointTrajectoryResult.INVALID_GOAL)
        self.assertIn('non-finite', result.error_string)
        state, result = self.finished(
            self.send(self.goal([(1.0, [0.1, 0.2])], ['shoulder_joint', 'wrist_joint'])),
            'unknown joint')
        self.assertEqual(state, GoalStatus.REJECTED)
        self.assertEqual(result.error_code, FollowJointTrajectoryResult.INVALID_JOINTS)
        # the command topic moves it still
        pub = rospy.Publisher(CONTROLLER + '/command', JointTrajectory, queue_size=1)
        wait_connected(pub)
        pub.publish(trajectory([(0.5, [0.3, 0.3])]))
        sim_sleep(1.5, wall_timeout=WALL_TIMEOUT)
        for g in self.positions():
            self.assertAlmostEqual(g, 0.3, delta=0.02)


if __name__ == '__main__':
    rostest.rosrun('tianracer_sim', 'joint_trajectory_controller', JointTrajectoryControllerTest)
