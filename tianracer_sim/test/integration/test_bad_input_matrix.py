#!/usr/bin/env python3
"""rostest: the running-node rows of the bad-input matrix (docs/bad_input.md).

NaN, inf and 1e30 on every input topic (the controllers' command topics, /cmd_vel, the wheel
odometry's joint_states) and on every numeric field of the services (set_model_state pose and
twist), a car flipped on its roof, and (run with --in-wall) a car spawned inside a wall. In every
case the sim keeps stepping and no NaN reaches a published message: a monitor checks every
joint_states, ground-truth odometry, wheel odometry and scan message of the whole run.

Sim time throughout; wall time only bounds a wait so that a wedged sim fails instead of hanging.
"""
import math
import sys
import threading
import unittest

import rosnode
import rospy
import rostest
from geometry_msgs.msg import Pose, Twist
from nav_msgs.msg import Odometry
from rosgraph_msgs.msg import Clock, Log
from sensor_msgs.msg import JointState, LaserScan
from std_msgs.msg import Float64
from std_srvs.srv import Empty

from gazebo_msgs.msg import ModelState
from gazebo_msgs.srv import GetModelState, SetModelState
from tianracer_sim.sim_time import connect_gazebo, lossless, sim_sleep, wait_connected, wait_for

from gazebo_case import moved_in_plane

NS = '/tianracer'
MODEL = 'tianracer'
SIM_NODE = '/tianracer_sim'
BAD_VALUES = (float('nan'), float('inf'), -float('inf'), 1e30, -1e30)


def finite(*values):
    return all(math.isfinite(v) for v in values)


def odom_values(m):
    p, t = m.pose.pose, m.twist.twist
    return (p.position.x, p.position.y, p.position.z, p.orientation.x, p.orientation.y,
            p.orientation.z, p.orientation.w, t.linear.x, t.linear.y, t.linear.z, t.angular.x,
            t.angular.y, t.angular.z) + tuple(m.pose.covariance) + tuple(m.twist.covariance)


def up_of(q):
    """z component of the body's z axis: 1 upright, -1 on its roof."""
    return 1.0 - 2.0 * (q.x * q.x + q.y * q.y)


class Monitor(object):
    """Counts the messages of each published topic (every one that reaches this process), keeps
    the latest stamp of each and the first non-finite value of each (scan ranges may be +-inf,
    REP 117, but never NaN)."""

    def __init__(self):
        self.lock = threading.Lock()
        self.count = {}
        self.stamp = {}
        self.bad = {}
        self.clock = 0.0
        self.truth = None
        self.rosout = []
        self.published_by_us = 0  # joint_states we inject ourselves are not the sim's
        for topic, cls, cb in (('/clock', Clock, self.on_clock),
                               (NS + '/joint_states', JointState, self.on_js),
                               (NS + '/ground_truth/odom', Odometry, self.on_truth),
                               (NS + '/odom', Odometry, self.on_odom),
                               ('/scan', LaserScan, self.on_scan),
                               ('/rosout', Log, self.on_log)):
            lossless(rospy.Subscriber(topic, cls, cb))

    def seen(self, topic, ok, what, stamp):
        with self.lock:
            self.count[topic] = self.count.get(topic, 0) + 1
            self.stamp[topic] = stamp.to_sec()
            if not ok and topic not in self.bad:
                self.bad[topic] = what

    def on_clock(self, m):
        with self.lock:
            self.clock = m.clock.to_sec()

    def on_js(self, m):
        if m._connection_header.get('callerid') != SIM_NODE:
            return  # our own bad joint_states (test_e)
        self.seen('joint_states', finite(*(m.position + m.velocity + m.effort)), str(m),
                  m.header.stamp)

    def on_truth(self, m):
        self.truth = m
        self.seen('ground_truth/odom', finite(*odom_values(m)), str(m.pose), m.header.stamp)

    def on_odom(self, m):
        self.seen('odom', finite(*odom_values(m)), str(m.pose), m.header.stamp)

    def on_scan(self, m):
        ok = not any(math.isnan(r) for r in m.ranges + m.intensities) and finite(
            m.angle_min, m.angle_max, m.angle_increment, m.range_min, m.range_max)
        self.seen('scan', ok, 'NaN in ranges or intensities', m.header.stamp)

    def on_log(self, m):
        with self.lock:
            self.rosout.append((m.name, m.level, m.msg))

    def snapshot(self):
        with self.lock:
            return dict(self.count), dict(self.bad), self.clock


class MatrixCase(unittest.TestCase):
    node_name = 'test_bad_input_matrix'

    @classmethod
    def setUpClass(cls):
        rospy.init_node(cls.node_name)
        cls.mon = Monitor()
        connect_gazebo(cls, {'set_model_state': SetModelState, 'get_model_state': GetModelState,
                             'reset_world': Empty}, 60)
        cls.set_state = staticmethod(lambda name, pose, twist, frame: cls.set_model_state(
            ModelState(name, pose, twist, frame)))
        wait_for(lambda: cls.mon.truth is not None, 'ground truth')

    def wait_sim(self, seconds):
        """Waits `seconds` of sim time."""
        sim_sleep(seconds)

    def assert_alive_and_finite(self, context):
        _, _, t0 = self.mon.snapshot()
        self.wait_sim(0.5)
        _, bad, t1 = self.mon.snapshot()
        self.assertGreater(t1, t0, context + ': the sim stopped stepping')
        self.assertTrue(rosnode.rosnode_ping(SIM_NODE, max_count=1), context + ': sim node down')
        for topic in ('joint_states', 'ground_truth/odom'):
            # Published on after t0: a message stamped later arrives (however late it is read).
            wait_for(lambda: self.mon.stamp.get(topic, -1.0) > t0,
                     '%s: %s stamped after %.3f' % (context, topic, t0))
        self.assertEqual(self.mon.snapshot()[1], {}, context + ': non-finite values published')
        self.assertEqual(bad, {}, context + ': non-finite values published')

    def logs_since(self, n, name=None):
        with self.mon.lock:
            logs = self.mon.rosout[n:]
        return [m for (node, level, m) in logs if name is None or node == name]

    def n_logs(self):
        with self.mon.lock:
            return len(self.mon.rosout)

    def state(self):
        r = self.get_model_state(MODEL, '')
        self.assertTrue(r.success, r.status_message)
        return r


class BadInputMatrix(MatrixCase):
    def test_a_controller_commands(self):
        """NaN, +-inf, +-1e30 on every controller's command topic."""
        controllers = sorted(
            name for name, spec in rospy.get_param(NS).items()
            if isinstance(spec, dict) and 'type' in spec
            and spec['type'] != 'joint_state_controller/JointStateController')
        self.assertEqual(len(controllers), 4, controllers)
        pubs = {c: rospy.Publisher('%s/%s/command' % (NS, c), Float64, queue_size=10)
                for c in controllers}
        for p in pubs.values():
            wait_connected(p)
        n = self.n_logs()
        for value in BAD_VALUES:
            for c, p in pubs.items():
                p.publish(Float64(value))
            self.wait_sim(0.2)
            for p in pubs.values():
                p.publish(Float64(0.0))
            self.assert_alive_and_finite('command %r' % value)
        # At most one warning a second per controller: each names the first bad value, NaN.
        warnings = self.logs_since(n, SIM_NODE)
        for c in controllers:
            self.assertIn("controller '%s': ignoring command nan (not finite)" % c, warnings)
        self.reset_world()
        self.wait_sim(0.5)

    def test_b_cmd_vel(self):
        """NaN, +-inf, +-1e30 in each field of /cmd_vel (cmd_vel_node)."""
        pub = wait_connected(rospy.Publisher('/cmd_vel', Twist, queue_size=10))
        n = self.n_logs()
        fields = ('linear.x', 'linear.y', 'linear.z', 'angular.x', 'angular.y', 'angular.z')
        for value in BAD_VALUES:
            for f in fields:
                msg = Twist()
                part, axis = f.split('.')
                setattr(getattr(msg, part), axis, value)
                pub.publish(msg)
                self.wait_sim(0.05)
            pub.publish(Twist())
            self.assert_alive_and_finite('/cmd_vel %r' % value)
        self.assertTrue(rosnode.rosnode_ping('/cmd_vel_node', max_count=1))
        logs = self.logs_since(n, '/cmd_vel_node')
        self.assertTrue(any('non-finite' in m for m in logs), logs)
        self.assertTrue(any('clamped' in m for m in logs), logs)
        self.wait_sim(1.0)  # the command timeout (0.5 s) stops the car
        self.reset_world()
        self.wait_sim(0.5)

    def test_c_set_model_state_non_finite(self):
        """NaN and +-inf in each field of set_model_state's pose and twist: refused, state kept."""
        before = self.state()
        fields = ['pose.position.' + a for a in 'xyz'] + ['pose.orientation.' + a for a in 'xyzw'] \
            + ['twist.%s.%s' % (p, a) for p in ('linear', 'angular') for a in 'xyz']
        for value in BAD_VALUES[:3]:
            for f in fields:
                pose, twist = Pose(), Twist()
                pose.position.z = 0.1
                pose.orientation.w = 1.0
                obj = {'pose': pose, 'twist': twist}
                parts = f.split('.')
                target = obj[parts[0]]
                for p in parts[1:-1]:
                    target = getattr(target, p)
                setattr(target, parts[-1], value)
                r = self.set_state(MODEL, pose, twist, '')
                self.assertFalse(r.success, f)
                what = 'pose' if parts[0] == 'pose' else 'twist'
                self.assertIn("set_model_state: %s of 'tianracer' is not finite" % what,
                              r.status_message)
                self.assertIn('state unchanged', r.status_message)
        zero_q = Pose()
        r = self.set_state(MODEL, zero_q, Twist(), '')
        self.assertFalse(r.success)
        self.assertIn('zero quaternion', r.status_message)
        self.assertLess(moved_in_plane(before, self.state()), 0.01)
        self.assert_alive_and_finite('set_model_state NaN')

    def test_d_set_model_state_huge(self):
        """1e30 in the pose or twist: refused with the bound named (a finite value that big
        would make the physics produce NaN)."""
        for f, value in (('pose.position.x', 1e30), ('pose.position.z', -1e30),
                         ('twist.linear.x', 1e30), ('twist.angular.z', -1e30)):
            pose, twist = Pose(), Twist()
            pose.position.z = 0.1
            pose.orientation.w = 1.0
            obj = {'pose': pose, 'twist': twist}
            parts = f.split('.')
            setattr(getattr(obj[parts[0]], parts[1]), parts[2], value)
            r = self.set_state(MODEL, pose, twist, '')
            self.assertFalse(r.success, '%s = %g accepted' % (f, value))
            self.assertIn('out of range', r.status_message)
        self.assert_alive_and_finite('set_model_state 1e30')
        self.reset_world()
        self.wait_sim(0.5)

    def test_e_wheel_odometry_input(self):
        """NaN, inf and 1e30 in joint_states (wheel_odometry_node's input): /tianracer/odom stays
        finite."""
        pub = wait_connected(rospy.Publisher(NS + '/joint_states', JointState, queue_size=10))
        names = ['left_rear_wheel_joint', 'right_rear_wheel_joint', 'left_steering_hinge_joint',
                 'right_steering_hinge_joint']
        for value in BAD_VALUES:
            m = JointState(name=names, position=[value] * 4, velocity=[value] * 4)
            m.header.stamp = rospy.Time.now()
            pub.publish(m)
            self.wait_sim(0.1)
        self.assertTrue(rosnode.rosnode_ping('/wheel_odometry_node', max_count=1))
        self.assert_alive_and_finite('joint_states NaN')

    def test_f_flipped_on_its_roof(self):
        """set_model_state with roll = pi: the car settles on its roof without NaN; reset_world
        puts it back on its wheels at the spawn."""
        pose = Pose()
        pose.position.z = 0.3
        pose.orientation.x = 1.0  # roll = pi
        r = self.set_state(MODEL, pose, Twist(), '')
        self.assertTrue(r.success, r.status_message)
        self.wait_sim(3.0)
        s = self.state()
        self.assertLess(up_of(s.pose.orientation), -0.9, s.pose)
        self.assertLess(s.pose.position.z, 0.3)
        self.assertLess(math.hypot(s.twist.linear.x, s.twist.linear.y), 0.05, s.twist)
        self.assert_alive_and_finite('on its roof')
        self.reset_world()
        self.wait_sim(1.0)
        s = self.state()
        self.assertGreater(up_of(s.pose.orientation), 0.99, s.pose)
        self.assertLess(math.hypot(s.pose.position.x, s.pose.position.y), 0.01, s.pose)
        self.assert_alive_and_finite('reset after the roof')

    def test_z_nothing_non_finite_was_published(self):
        count, bad, _ = self.mon.snapshot()
        self.assertEqual(bad, {})
        for topic in ('joint_states', 'ground_truth/odom', 'odom', 'scan'):
            self.assertGreater(count.get(topic, 0), 0, topic)


class SpawnedInAWall(MatrixCase):
    """The launch spawns the car straddling the north wall of walled_room (y = 2.0 .. 2.1)."""
    node_name = 'test_bad_input_in_wall'

    def test_a_keeps_stepping_without_nan(self):
        self.wait_sim(5.0)
        p = self.state().pose.position
        self.assertTrue(finite(p.x, p.y, p.z))
        self.assert_alive_and_finite('spawned in a wall')
        count, bad, _ = self.mon.snapshot()
        self.assertEqual(bad, {})
        self.assertGreater(count.get('scan', 0), 0)

    # Issue 9: Bullet used to resolve the 0.1 m penetration with a huge impulse (1 km/s once,
    # 21 m/s spinning at 460 rad/s later); contacts now correct penetration at no more than
    # max_vel (0.1 m/s, physics/world.h) and the car is pushed into the room in about 2 s.
    def test_b_is_pushed_out_not_thrown_away(self):
        self.wait_sim(5.0)
        s = self.state()
        p = s.pose.position
        self.assertLess(abs(p.x), 3.5, s.pose)   # in or at the room
        self.assertLess(abs(p.y), 3.0, s.pose)
        self.assertLess(p.z, 1.0, s.pose)
        self.assertLess(p.y, 2.0, s.pose)        # base_link out of the wall, on the room's side
        self.assertLess(math.hypot(s.twist.linear.x, s.twist.linear.y, s.twist.linear.z), 0.5,
                        s.twist)  # settled (pushed out, or resting against the wall)
        self.assertLess(math.hypot(s.twist.angular.x, s.twist.angular.y, s.twist.angular.z), 0.5,
                        s.twist)  # not left spinning on its side


if __name__ == '__main__':
    if '--in-wall' in sys.argv:
        rostest.rosrun('tianracer_sim', 'bad_input_in_wall', SpawnedInAWall)
    else:
        rostest.rosrun('tianracer_sim', 'bad_input_matrix', BadInputMatrix)
