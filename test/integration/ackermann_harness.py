"""Shared pieces of the Ackermann drive rostests: what the tests observe (ground truth, wheel
odometry, the cmd_vel node's wheel commands, /rosout), a /cmd_vel publisher, the geometry read
from robot_description the way tianracer_control reads it, and a least squares circle fit.

Everything is measured in sim time: samples carry the sim's stamps (wheel and steering
commands the sim time they were received at), and waits are on sim time and on stamps
(tianracer_sim.sim_time): the samples of a span are complete once one stamped after it has
arrived. Wall time only bounds how long a wait may take, so that a wedged sim fails the test
instead of hanging it.
"""
import math
import threading
import unittest
import xml.etree.ElementTree as ET

import numpy as np
import rospy
from geometry_msgs.msg import Twist
from nav_msgs.msg import Odometry
from rosgraph_msgs.msg import Log
from std_msgs.msg import Float64
from std_srvs.srv import Empty
from tianracer_sim.rotation import yaw_from_quaternion as yaw_of
from tianracer_sim.sim_time import (Paused, connect_gazebo, lossless, messages_received,
                                    sim_sleep, wait_connected, wait_for)

CMD_NODE = '/cmd_vel_node'
WHEEL_TOPIC = '/tianracer/left_rear_wheel_velocity_controller/command'
STEER_TOPIC = '/tianracer/left_steering_hinge_position_controller/command'


def wrap(a):
    return math.atan2(math.sin(a), math.cos(a))


class Pose2(object):
    """A planar pose sample: stamp (s, sim), x, y (m), yaw (rad), forward/lateral speed (m/s,
    body frame) and yaw rate, from a nav_msgs/Odometry."""
    __slots__ = ('t', 'x', 'y', 'z', 'yaw', 'up', 'vx', 'vy', 'wz', 'finite')

    def __init__(self, msg):
        p = msg.pose.pose
        self.t = msg.header.stamp.to_sec()
        self.x, self.y, self.z = p.position.x, p.position.y, p.position.z
        self.yaw = yaw_of(p.orientation)
        q = p.orientation  # up: z component of the body's z axis (1 = upright, < 0 = on its roof)
        self.up = 1.0 - 2.0 * (q.x * q.x + q.y * q.y)
        self.vx = msg.twist.twist.linear.x
        self.vy = msg.twist.twist.linear.y
        self.wz = msg.twist.twist.angular.z
        self.finite = all(math.isfinite(v) for v in (
            p.position.x, p.position.y, p.position.z, p.orientation.x, p.orientation.y,
            p.orientation.z, p.orientation.w, msg.twist.twist.linear.x,
            msg.twist.twist.linear.y, msg.twist.twist.linear.z, msg.twist.twist.angular.z))

    @property
    def speed(self):
        return math.hypot(self.vx, self.vy)

    def point(self, bx, by):
        """World position of the body point (bx, by) (base frame)."""
        c, s = math.cos(self.yaw), math.sin(self.yaw)
        return self.x + c * bx - s * by, self.y + s * bx + c * by


# ---- geometry, as tianracer_control/src/urdf_geometry.cpp derives it -------------------------

def _rpy_matrix(r, p, y):
    cr, sr, cp, sp, cy, sy = (math.cos(r), math.sin(r), math.cos(p), math.sin(p),
                              math.cos(y), math.sin(y))
    return np.array([[cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr],
                     [sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr],
                     [-sp, cp * sr, cp * cr]])


def _origin(joint):
    o = joint.find('origin')
    X = np.eye(4)
    if o is not None:
        X[:3, 3] = [float(v) for v in o.get('xyz', '0 0 0').split()]
        X[:3, :3] = _rpy_matrix(*[float(v) for v in o.get('rpy', '0 0 0').split()])
    return X


def ackermann_geometry(urdf_xml, base='base_link'):
    """wheelbase L (mean hinge x - rear axle x), rear axle midpoint (x, y) in the base frame,
    hinge separation T: joint origins expressed in `base`, as the cmd_vel node computes them."""
    root = ET.fromstring(urdf_xml)
    joints = {j.get('name'): j for j in root.findall('joint')}
    by_child = {j.find('child').get('link'): j for j in joints.values()}

    def link_in_base(link):
        X = np.eye(4)
        while link != base:
            j = by_child[link]  # KeyError: not below base
            X = _origin(j).dot(X)
            link = j.find('parent').get('link')
        return X

    def joint_in_base(name):
        j = joints[name]
        return link_in_base(j.find('parent').get('link')).dot(_origin(j))[:3, 3]

    lh, rh = joint_in_base('left_steering_hinge_joint'), joint_in_base('right_steering_hinge_joint')
    lr, rr = joint_in_base('left_rear_wheel_joint'), joint_in_base('right_rear_wheel_joint')
    rear_x, rear_y = 0.5 * (lr[0] + rr[0]), 0.5 * (lr[1] + rr[1])
    return {'wheelbase': 0.5 * (lh[0] + rh[0]) - rear_x,
            'rear_axle_x': rear_x, 'rear_axle_y': rear_y,
            'hinge_separation': abs(lh[1] - rh[1])}


# ---- analysis ----------------------------------------------------------------------------------

def fit_circle(xs, ys):
    """Least squares circle through the points: the algebraic (Kasa) fit
    x^2 + y^2 + D x + E y + F = 0, refined by Gauss-Newton on the geometric distances
    |p - c| - R. Returns (cx, cy, R, rms residual)."""
    x, y = np.asarray(xs, float), np.asarray(ys, float)
    A = np.column_stack([x, y, np.ones_like(x)])
    D, E, F = np.linalg.lstsq(A, -(x * x + y * y), rcond=None)[0]
    cx, cy = -D / 2.0, -E / 2.0
    R = math.sqrt(max(cx * cx + cy * cy - F, 0.0))
    for _ in range(20):
        dx, dy = x - cx, y - cy
        d = np.hypot(dx, dy)
        res = d - R
        J = np.column_stack([-dx / d, -dy / d, -np.ones_like(d)])
        step = np.linalg.lstsq(J, -res, rcond=None)[0]
        cx, cy, R = cx + step[0], cy + step[1], R + step[2]
        if np.max(np.abs(step)) < 1e-12:
            break
    res = np.hypot(x - cx, y - cy) - R
    return float(cx), float(cy), float(R), float(math.sqrt(np.mean(res * res)))


def path_length(points):
    return sum(math.hypot(b[0] - a[0], b[1] - a[1]) for a, b in zip(points, points[1:]))


def relative_pose(start, end):
    """end in start's frame: (dx, dy, dyaw)."""
    c, s = math.cos(start.yaw), math.sin(start.yaw)
    dx, dy = end.x - start.x, end.y - start.y
    return c * dx + s * dy, -s * dx + c * dy, wrap(end.yaw - start.yaw)


# ---- the harness -------------------------------------------------------------------------------

class Repeater(object):
    """Publishes a message on `pub` now and then every 0.05 s of sim time (20 Hz, from a thread)
    until stopped; `last` is the sim time of the last message published, `count` how many the
    repetition has published."""

    def __init__(self, pub):
        self.pub = pub
        self.lock = threading.Lock()
        self.msg = None  # being repeated, or None
        self.last = None
        self.count = 0
        thread = threading.Thread(target=self._run, name=pub.resolved_name)
        thread.daemon = True
        thread.start()

    def start(self, msg):
        """Publishes msg now and repeats it until stop() or once()."""
        with self.lock:
            self.msg = msg
            self._publish()

    def once(self, msg):
        """Publishes msg once, not repeated (stops any repetition)."""
        with self.lock:
            self.msg = None
            self.pub.publish(msg)
            self.last = rospy.get_time()

    def stop(self):
        """Stops repeating; returns the sim time of the last message published."""
        with self.lock:
            self.msg = None
            return self.last

    def _publish(self):
        self.pub.publish(self.msg)
        self.last = rospy.get_time()
        self.count += 1

    def _run(self):
        while not rospy.is_shutdown():
            with self.lock:
                if self.msg is not None:
                    self._publish()
            try:
                rospy.sleep(0.05)
            except rospy.ROSInterruptException:
                return
            except rospy.ROSTimeMovedBackwardsException:
                pass


def twist(v, w):
    msg = Twist()
    msg.linear.x, msg.angular.z = v, w
    return msg


class Harness(object):
    """Subscribes to what the tests read and publishes /cmd_vel from a thread."""

    def __init__(self):
        self.lock = threading.Lock()       # sample lists
        self.truth = []        # Pose2 of base_link in world
        self.odom = []         # Pose2 of base_link in odom (wheel odometry)
        self.wheel_cmd = []    # (receive sim time, rad/s) of the cmd_vel node's left rear command
        self.steer_cmd = []    # (receive sim time, rad) of its left steering hinge command
        self.rosout = []       # rosgraph_msgs/Log from the cmd_vel node
        # Every message that reaches this process (sim_time.lossless).
        for topic, cls, cb in (('/tianracer/ground_truth/odom', Odometry, self._on_truth),
                               ('/tianracer/odom', Odometry, self._on_odom),
                               (WHEEL_TOPIC, Float64, self._on_wheel),
                               (STEER_TOPIC, Float64, self._on_steer),
                               ('/rosout', Log, self._on_rosout)):
            lossless(rospy.Subscriber(topic, cls, cb))
        self.pub = rospy.Publisher('/cmd_vel', Twist, queue_size=10)
        self.cmd_vel = Repeater(self.pub)

    # callbacks
    def _on_truth(self, msg):
        with self.lock:
            self.truth.append(Pose2(msg))

    def _on_odom(self, msg):
        with self.lock:
            self.odom.append(Pose2(msg))

    def _on_wheel(self, msg):
        with self.lock:
            self.wheel_cmd.append((rospy.get_time(), msg.data))

    def _on_steer(self, msg):
        with self.lock:
            self.steer_cmd.append((rospy.get_time(), msg.data))

    def _on_rosout(self, msg):
        if msg.name == CMD_NODE:
            with self.lock:
                self.rosout.append(msg)

    # waiting
    def wait_ready(self, wall_timeout=60.0):
        """Until the sim, both control nodes and our /cmd_vel link are up."""
        def ready():
            with self.lock:
                return self.truth and self.odom and self.wheel_cmd
        try:
            wait_for(ready, 'ground truth, wheel odometry and cmd_vel_node output',
                     wall_timeout)
            wait_connected(self.pub, wall_timeout)
        except AssertionError:
            return False
        return True

    def wait_sim(self, seconds, wall_timeout=None):
        """Sleeps `seconds` of sim time; fails rather than hang if the sim stops."""
        if wall_timeout is None:
            wall_timeout = 30.0 + 5.0 * seconds
        sim_sleep(seconds, wall_timeout)

    def wait_until(self, predicate, sim_timeout):
        """Until predicate() holds, or ground truth stamped `sim_timeout` s from now has
        arrived without it (so a late subscriber does not run out of sim time)."""
        target = rospy.get_time() + sim_timeout
        return wait_for(lambda: predicate() or self.latest_truth().t >= target,
                        'ground truth stamped %.3f' % target) and predicate()

    def wait_truth(self, t):
        """Until a ground truth sample stamped t or later has arrived: those of any span
        ending at t are complete."""
        wait_for(lambda: self.latest_truth().t >= t - 1e-9, 'ground truth stamped %.3f' % t)

    def wait_commands(self, t):
        """Until a wheel command received at sim time t or later has arrived (cmd_vel_node
        sends one every tick)."""
        def arrived():
            with self.lock:
                return self.wheel_cmd and self.wheel_cmd[-1][0] >= t
        wait_for(arrived, 'a wheel command received at %.3f' % t)

    # commanding
    def drive(self, v, w):
        """Publish Twist(v, w) now and then every 0.05 s of sim time until stop_publishing()."""
        self.cmd_vel.start(twist(v, w))

    def publish_once(self, v, w):
        """One Twist(v, w), not repeated (stops any repetition)."""
        self.cmd_vel.once(twist(v, w))

    def stop_publishing(self):
        """Stops repeating; returns the sim time of the last /cmd_vel published."""
        return self.cmd_vel.stop()

    def moved_by(self, send, commands):
        """Sends each command with send(*command), 0.1 s of sim time apart, then lets 0.5 s of
        sim time pass; returns how far (m, in the plane) ground truth moved meanwhile."""
        p0 = self.latest_truth()
        for command in commands:
            send(*command)
            self.wait_sim(0.1)
        self.wait_sim(0.5)
        p1 = self.latest_truth()
        return math.hypot(p1.x - p0.x, p1.y - p0.y)

    def stop_and_settle(self, max_sim=5.0):
        """Commands zero and waits until the car stands still; returns the last truth sample."""
        self.drive(0.0, 0.0)
        self.wait_until(lambda: self.latest_truth().speed < 1e-3, max_sim)
        self.wait_sim(0.3)
        self.stop_publishing()
        return self.latest_truth()

    # samples
    def latest_truth(self):
        with self.lock:
            return self.truth[-1]

    def latest_odom(self):
        with self.lock:
            return self.odom[-1]

    def odom_at(self, t):
        """The first wheel odometry sample stamped t or later. Waits for it: on a loaded machine
        the odometry node can lag the sim, and its latest sample may be from before t."""
        def arrived():
            with self.lock:
                return self.odom and self.odom[-1].t >= t - 1e-9
        wait_for(arrived, 'wheel odometry stamped %.3f' % t)
        with self.lock:
            return next(s for s in self.odom if s.t >= t - 1e-9)

    def truth_between(self, t0, t1):
        """Ground truth stamped t0..t1 (all of it: waits for a sample stamped t1 or later)."""
        self.wait_truth(t1)
        with self.lock:
            return [s for s in self.truth if t0 <= s.t <= t1]

    def wheel_cmds_between(self, t0, t1):
        self.wait_commands(t1)
        with self.lock:
            return [c for c in self.wheel_cmd if t0 <= c[0] <= t1]

    def steer_cmds_between(self, t0, t1):
        self.wait_commands(t1)
        with self.lock:
            return [c for c in self.steer_cmd if t0 <= c[0] <= t1]

    def drive_circle(self, v, angular_z, settle, duration, geometry):
        """From rest: Twist(v, angular_z) for settle + duration s of sim time, then stop. The
        ground-truth path of the rear axle midpoint (the bicycle model's reference point) over
        the last `duration` s is fitted with a circle. Returns the figures as a dict."""
        self.stop_and_settle()
        self.drive(v, angular_z)
        t_start = rospy.get_time()
        self.wait_sim(settle)
        t0 = rospy.get_time()
        self.wait_sim(duration)
        t1 = rospy.get_time()
        self.stop_and_settle()
        samples = self.truth_between(t0, t1)
        rear = [s.point(geometry['rear_axle_x'], geometry['rear_axle_y']) for s in samples]
        cx, cy, r, rms = fit_circle([p[0] for p in rear], [p[1] for p in rear])
        _, _, r_base, _ = fit_circle([s.x for s in samples], [s.y for s in samples])
        turned = sum(wrap(b.yaw - a.yaw) for a, b in zip(samples, samples[1:]))
        dt = samples[-1].t - samples[0].t
        return {'radius': r, 'rms': rms, 'radius_base_link': r_base, 'center': (cx, cy),
                'samples': len(samples), 'duration': dt, 'turned': turned,
                'yaw_rate': turned / dt, 'speed': path_length(rear) / dt,
                't_start': t_start, 't0': t0, 't1': t1}


class AckermannTestCase(unittest.TestCase):
    """Base of the rostests: a node, the harness, the geometry and the sim's pause services."""
    node_name = 'test_ackermann'

    @classmethod
    def setUpClass(cls):
        rospy.init_node(cls.node_name)
        cls.h = Harness()
        if not cls.h.wait_ready():
            raise AssertionError('no ground truth, wheel odometry or cmd_vel_node output within '
                                 '60 s of wall time')
        cls.geometry = ackermann_geometry(rospy.get_param('/robot_description'))
        cls.wheel_radius = 0.032  # what cmd_vel_node uses for the seed's mesh wheels (docs/bringup.md)
        cls.max_speed = float(rospy.get_param(CMD_NODE + '/max_speed', 3.0))
        connect_gazebo(cls, {'pause_physics': Empty, 'unpause_physics': Empty}, 30)
        rospy.loginfo('geometry from robot_description: %s', cls.geometry)

    def report(self, fmt, *args):
        """Logs a measured figure and returns it for the assertion messages."""
        text = fmt % args
        name = self.id().split('.')[-1]
        rospy.loginfo('[%s] %s', name, text)
        print('FIGURE %s: %s' % (name, text))
        return text

    def drive_lap(self, v, angular_z, r_expected, what):
        """One lap of a circle of radius r_expected at v (Twist angular.z = angular_z) after 3 s
        of settling: the radius error of the fit (Harness.drive_circle) relative to r_expected,
        and the figures of the fit for a report."""
        lap = 2.0 * math.pi * r_expected / v
        res = self.h.drive_circle(v, angular_z, settle=3.0, duration=lap, geometry=self.geometry)
        err = (res['radius'] - r_expected) / r_expected
        self.assert_no_timeout(res['t0'], res['t1'], what)
        figures = ('fitted radius of the rear axle midpoint %.4f m (%+.2f %%, rms %.2f mm, %d '
                   'samples over %.2f s, %.0f deg); base_link circle %.4f m; measured speed '
                   '%.4f m/s, yaw rate %.4f rad/s' % (
                       res['radius'], 100.0 * err, 1000.0 * res['rms'], res['samples'],
                       res['duration'], math.degrees(res['turned']), res['radius_base_link'],
                       res['speed'], res['yaw_rate']))
        return err, figures

    def assert_no_timeout(self, t0, t1, what):
        """cmd_vel_node kept driving from t0 to t1 (sim time): a zero wheel command in a
        measurement means the node timed out, i.e. the /cmd_vel stream lapsed (a process starved
        of CPU); say so rather than report a wrong figure."""
        # Half-open [t0, t1): callers read t1 and then send the stop. /clock ticks every 5 ms of
        # sim time, so when cmd_vel_node's timer fires in the same tick as the stop arrives, its
        # zero answer is received with a stamp equal to t1 (seen about once in 500 commands as
        # an "isolated zero" at the end of (b); instrumented: zero output at 23.495 s answering
        # the stop Twist received at 23.495 s).
        cmds = [c[1] for c in self.h.wheel_cmds_between(t0, t1) if c[0] < t1]
        self.assertTrue(cmds, '%s: no wheel commands seen' % what)
        # Zeros before the first drive command are the node's output from before the command
        # reached it. A lapse stops the car: a run of zero commands; a single zero sample is
        # 20 ms without drive, does not change the figures, and is logged, not failed.
        first = next((i for i, c in enumerate(cmds) if c != 0.0), len(cmds))
        run, longest, zeros = 0, 0, 0
        for c in cmds[first:]:
            run = run + 1 if c == 0.0 else 0
            longest = max(longest, run)
            zeros += c == 0.0
        if zeros:
            rospy.logwarn('%s: %d isolated zero wheel command(s) of %d', what, zeros, len(cmds))
        self.assertLess(longest, 3, '%s: cmd_vel_node stopped the car during the measurement '
                        '(%d consecutive zero wheel commands of %d): the /cmd_vel stream lapsed'
                        % (what, longest, len(cmds)))

    def send_paused(self, v, w):
        """Publishes one Twist with the physics paused, so that it reaches cmd_vel_node at a
        known sim time however loaded the machine is: the paused time, which every clock has
        reached (sim_time.Paused); unpaused once cmd_vel_node has read the Twist. Returns that
        sim time."""
        with Paused() as paused:
            n = messages_received(CMD_NODE, '/cmd_vel')
            self.h.publish_once(v, w)
            wait_for(lambda: messages_received(CMD_NODE, '/cmd_vel') > n,
                     'cmd_vel_node reading the Twist')
        return paused.t
