#!/usr/bin/env python3
"""rostest: cmd_vel_node driven by ackermann_msgs on /ackermann_cmd (control.launch's default):
the turning radius of AckermannDriveStamped(speed 1.0, steering_angle 0.3) against the bicycle
model, the command timeout after a 20 Hz stream, bad values (NaN, inf, 1e30), the bare
AckermannDrive on the same topic, and the log line when /cmd_vel and /ackermann_cmd both
command the car. Sim time, as test_ackermann_drive.py.

The tests run in name order on one car, each from rest where the previous one left it.
"""
import math

import rosnode
import rospy
import rostest
from ackermann_msgs.msg import AckermannDrive, AckermannDriveStamped
from rosgraph_msgs.msg import Log
from std_msgs.msg import Float64
from tianracer_sim.sim_time import wait_connected

from ackermann_harness import CMD_NODE, AckermannTestCase, Repeater, fit_circle

TOPIC = '/ackermann_cmd'
RADIUS_TOL = 0.03   # 3 %
STOP_SPEED = 0.01   # m/s
STOP_WITHIN = 1.0   # s after the last command: cmd_timeout 0.5 s + braking


class AckermannStream(Repeater):
    """Publishes an Ackermann command every 0.05 s of sim time (20 Hz) until stopped."""

    def __init__(self, msg_type=AckermannDriveStamped):
        self.msg_type = msg_type
        Repeater.__init__(self, rospy.Publisher(TOPIC, msg_type, queue_size=10))

    def make(self, speed, angle, angle_rate=0.0, accel=0.0):
        drive = AckermannDrive(steering_angle=angle, steering_angle_velocity=angle_rate,
                               speed=speed, acceleration=accel)
        if self.msg_type is AckermannDrive:
            return drive
        msg = AckermannDriveStamped(drive=drive)
        msg.header.stamp = rospy.Time.now()
        return msg

    def start(self, *args):
        Repeater.start(self, self.make(*args))

    def once(self, *args):
        Repeater.once(self, self.make(*args))

    def wait_connected(self, wall_timeout=30.0):
        try:
            wait_connected(self.pub, wall_timeout)
        except AssertionError:
            return False
        return True


class AckermannInput(AckermannTestCase):
    node_name = 'test_ackermann_input'

    @classmethod
    def setUpClass(cls):
        super(AckermannInput, cls).setUpClass()
        cls.stream = AckermannStream()
        if not cls.stream.wait_connected():
            raise AssertionError('cmd_vel_node does not subscribe to ' + TOPIC)

    def settle(self):
        """Stops the car through /cmd_vel, then lets the Twist source go quiet for longer than
        the command timeout, so that only the Ackermann input is active afterwards."""
        self.h.stop_and_settle()
        self.h.wait_sim(0.7)

    def logs_since(self, n):
        with self.h.lock:
            return [m for m in self.h.rosout[n:]]

    def log_count(self):
        with self.h.lock:
            return len(self.h.rosout)

    # -------------------------------------------------------------------------------------------
    def test_a_turning_radius(self):
        """AckermannDriveStamped speed 1.0, steering_angle 0.3 at 20 Hz: the rear axle midpoint
        circles at R = L / tan(0.3)."""
        h, s = self.h, self.stream
        self.settle()
        s.start(1.0, 0.3)
        h.wait_sim(2.0)
        t0 = rospy.get_time()
        h.wait_sim(5.0)
        t1 = rospy.get_time()
        s.stop()
        h.wait_sim(1.0)
        samples = h.truth_between(t0, t1)
        g = self.geometry
        rear = [p.point(g['rear_axle_x'], g['rear_axle_y']) for p in samples]
        _, _, r, rms = fit_circle([p[0] for p in rear], [p[1] for p in rear])
        expected = g['wheelbase'] / math.tan(0.3)
        speed = sum(math.hypot(b[0] - a[0], b[1] - a[1]) for a, b in zip(rear, rear[1:])) / (
            samples[-1].t - samples[0].t)
        self.assert_no_timeout(t0, t1, 'radius')
        text = self.report('AckermannDriveStamped(1.0 m/s, 0.3 rad): radius %.4f m (rms %.2g m, '
                           '%d samples over %.2f s), L/tan(0.3) = %.4f m: %+.2f %%; rear axle '
                           'speed %.4f m/s', r, rms, len(samples), samples[-1].t - samples[0].t,
                           expected, 100.0 * (r / expected - 1.0), speed)
        # The axle's speed is reported, not checked: with both rear wheels at v / r (the
        # tutorial's locked axle) the tyres scrub in a 0.8 m turn (docs/simulator.md, known differences).
        self.assertLess(abs(r / expected - 1.0), RADIUS_TOL, text)

    def test_b_stream_then_silence_stops_after_the_timeout(self):
        h, s = self.h, self.stream
        timeout = float(rospy.get_param(CMD_NODE + '/cmd_timeout'))
        self.settle()
        sent0 = s.count
        s.start(1.0, 0.0)
        h.wait_sim(5.0)
        t_last = s.stop()
        sent = s.count - sent0
        h.wait_sim(2.5)
        during = h.truth_between(t_last - 2.0, t_last)
        after = h.truth_between(t_last, rospy.get_time())
        moving = [p for p in after if p.speed >= STOP_SPEED]
        t_stop = moving[-1].t if moving else t_last
        cmds = h.wheel_cmds_between(t_last, rospy.get_time())
        t_zero = next((c[0] for c in cmds if c[1] == 0.0), float('nan'))
        text = self.report('%d commands over 5 s of sim time; speed before silence %.4f m/s; '
                           'wheel command 0 received %.3f s after the last command (cmd_timeout '
                           '%.2f s); below %.2f m/s from %.3f s after it; %.5f m/s at the end',
                           sent, min(p.speed for p in during), t_zero - t_last, timeout,
                           STOP_SPEED, t_stop - t_last, after[-1].speed)
        self.assertGreaterEqual(sent, 95, text)  # 20 Hz for 5 s
        self.assertGreater(min(p.speed for p in during), 0.97, text)
        self.assertGreater(t_zero - t_last, timeout - 0.06, text)  # not before the timeout
        self.assertLess(t_stop - t_last, STOP_WITHIN, text)
        self.assertLess(after[-1].speed, STOP_SPEED, text)

    def test_c_bad_values(self):
        """NaN and inf are rejected with a warning (the car stays put); 1e30 is clamped to
        max_speed and the steering to the joint limit; nothing non-finite goes out."""
        h, s = self.h, self.stream
        self.settle()
        n_log = self.log_count()
        t0 = rospy.get_time()
        nan, inf = float('nan'), float('inf')
        moved = h.moved_by(s.once, ((nan, 0.0), (0.0, nan), (inf, 0.0), (0.0, -inf), (-inf, inf)))
        phases = {}
        for name, speed, angle, secs in (('speed 1e30', 1e30, 0.0, 2.5),
                                         ('angle 1e30', 0.3, 1e30, 1.5),
                                         ('speed -1e30', -1e30, 0.0, 1.5)):
            self.settle()
            s.start(speed, angle)
            ta = rospy.get_time()
            h.wait_sim(secs)
            phases[name] = (ta, rospy.get_time())
            s.stop()
        self.settle()
        t1 = rospy.get_time()
        samples = h.truth_between(t0, t1)
        wheel = [c[1] for c in h.wheel_cmds_between(t0, t1)]
        steer = [c[1] for c in h.steer_cmds_between(t0, t1)]
        logs = self.logs_since(n_log)
        warns = [m.msg for m in logs if m.level >= Log.WARN]
        v_max = max(p.speed for p in h.truth_between(*phases['speed 1e30']))
        steer_max = max(abs(c[1]) for c in h.steer_cmds_between(*phases['angle 1e30']))
        text = self.report('NaN/inf: car moved %.3f mm; 1e30 m/s: top speed %.4f m/s (max_speed '
                           '%.2f); 1e30 rad: left steering %.4f rad; wheel commands finite %s, '
                           'steering finite %s, truth finite %s; warnings %s',
                           1000.0 * moved, v_max, self.max_speed, steer_max,
                           all(map(math.isfinite, wheel)), all(map(math.isfinite, steer)),
                           all(p.finite for p in samples), warns)
        self.assertLess(moved, 0.001, text)
        self.assertTrue(wheel and all(map(math.isfinite, wheel)), text)
        self.assertTrue(steer and all(map(math.isfinite, steer)), text)
        self.assertTrue(all(p.finite for p in samples), text)
        self.assertLessEqual(max(abs(w) for w in wheel) * self.wheel_radius,
                             self.max_speed + 1e-9, text)
        self.assertLessEqual(v_max, self.max_speed * 1.01, text)
        self.assertGreater(v_max, self.max_speed * 0.9, text)
        self.assertLessEqual(steer_max, 0.6 + 1e-9, text)
        self.assertGreater(steer_max, 0.55, text)
        self.assertTrue([m for m in warns if 'non-finite' in m and TOPIC in m], text)
        self.assertTrue([m for m in warns if 'speed' in m and 'clamped' in m], text)
        self.assertTrue([m for m in warns if 'steering_angle' in m and 'clamped' in m], text)
        self.assertTrue(rosnode.rosnode_ping(CMD_NODE, max_count=1), text)

    def test_d_two_sources_latest_wins(self):
        """The line that two sources are active comes once in the whole run (the earlier
        tests switched between them too)."""
        h, s = self.h, self.stream
        self.settle()
        # Twist 0.5 m/s, then an Ackermann 1.0 m/s: the car follows the latest.
        h.drive(0.5, 0.0)
        h.wait_sim(1.0)
        h.stop_publishing()
        s.once(1.0, 0.0)
        t = rospy.get_time()
        h.wait_sim(0.3)
        cmds = [c[1] for c in h.wheel_cmds_between(t + 0.1, rospy.get_time())]
        h.stop_and_settle()
        logs = [m.msg for m in self.logs_since(0)]
        both = [m for m in logs if 'both' in m and 'latest message wins' in m]
        text = self.report('wheel commands after the Ackermann message: %s rad/s; log: %s',
                           sorted(set(round(c, 3) for c in cmds)), both)
        self.assertTrue(cmds, text)
        self.assertAlmostEqual(cmds[-1] * self.wheel_radius, 1.0, places=6, msg=text)
        self.assertEqual(len(both), 1, text)

    def test_e_bare_ackermann_drive_on_the_same_topic(self):
        h = self.h
        self.settle()
        self.stream.pub.unregister()
        bare = AckermannStream(AckermannDrive)
        self.assertTrue(bare.wait_connected(), 'no subscriber for AckermannDrive on ' + TOPIC)
        h.wait_sim(0.3)
        bare.start(0.5, 0.0)
        h.wait_sim(1.5)
        t = rospy.get_time()
        h.wait_sim(0.5)
        cmds = [c[1] for c in h.wheel_cmds_between(t, rospy.get_time())]
        v = h.latest_truth().speed
        bare.stop()
        bare.pub.unregister()
        h.stop_and_settle()
        text = self.report('AckermannDrive(0.5 m/s): wheel commands %s rad/s, car at %.4f m/s',
                           sorted(set(round(c, 3) for c in cmds)), v)
        self.assertTrue(cmds, text)
        self.assertTrue(all(abs(c * self.wheel_radius - 0.5) < 1e-6 for c in cmds), text)
        self.assertAlmostEqual(v, 0.5, delta=0.02, msg=text)

    def test_f_another_type_on_the_topic(self):
        h = self.h
        n_log = self.log_count()
        pub = rospy.Publisher(TOPIC, Float64, queue_size=10)
        wait_connected(pub, 30.0)
        for _ in range(3):
            pub.publish(Float64(1.0))
            h.wait_sim(0.1)
        h.wait_sim(0.3)
        pub.unregister()
        warns = [m.msg for m in self.logs_since(n_log) if m.level >= Log.WARN]
        text = self.report('std_msgs/Float64 on %s: warnings %s', TOPIC, warns)
        self.assertTrue([m for m in warns if 'std_msgs/Float64' in m and 'expected' in m], text)
        self.assertLess(h.latest_truth().speed, STOP_SPEED, text)
        self.assertTrue(rosnode.rosnode_ping(CMD_NODE, max_count=1), text)


if __name__ == '__main__':
    rostest.rosrun('tianracer_tests', 'ackermann_input', AckermannInput)
