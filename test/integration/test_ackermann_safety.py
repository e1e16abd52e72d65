#!/usr/bin/env python3
"""rostest: cmd_vel_node with its default parameters (control.launch) stops the car when the
commands stop, and survives NaN, inf and huge commands. Issue 4 (e), (f). Sim time; see
test_ackermann_drive.py."""
import rosnode
import rospy
import rostest
from rosgraph_msgs.msg import Log

from ackermann_harness import CMD_NODE, AckermannTestCase

SPEED_TOL = 0.01       # the 1 % speed tolerance of (a): the physics' part of (f)
STOP_SPEED = 0.01      # (e) m/s
STOP_WITHIN = 1.0      # (e) s after the last command


class AckermannSafety(AckermannTestCase):
    node_name = 'test_ackermann_safety'

    # (e) ----------------------------------------------------------------------------------------
    def test_e_command_timeout_stops_the_car(self):
        h = self.h
        timeout = float(rospy.get_param(CMD_NODE + '/cmd_timeout'))
        self.assertEqual(timeout, 0.5, 'control.launch default changed?')
        h.stop_and_settle()
        # One Twist at 1 m/s, the last one, delivered at a known sim time (physics paused):
        # the car is at speed well within the 0.5 s the command lasts.
        t_last = self.send_paused(1.0, 0.0)
        h.wait_sim(2.5)
        after = h.truth_between(t_last, rospy.get_time())
        self.assertTrue(after)
        v_peak = max(p.speed for p in after)
        moving = [p for p in after if p.speed >= STOP_SPEED]
        t_stop = moving[-1].t if moving else t_last  # last sample still at or above 0.01 m/s
        cmds = h.wheel_cmds_between(t_last, rospy.get_time())
        t_drive = [c[0] for c in cmds if c[1] > 0.0]
        t_zero = [c[0] for c in cmds if c[1] == 0.0 and t_drive and c[0] > t_drive[0]]
        dt_zero = t_zero[0] - t_last if t_zero else float('nan')
        v_end = after[-1].speed
        text = self.report(
            'last /cmd_vel (1.0 m/s) at t = %.3f s (sim), car reached %.4f m/s; wheel command 0 '
            'received %.3f s later (cmd_timeout %.2f s); ground-truth speed < %.2f m/s from '
            '%.3f s after the last command on (%.5f m/s at %.1f s)', t_last, v_peak, dt_zero,
            timeout, STOP_SPEED, t_stop - t_last, v_end, after[-1].t - t_last)
        self.assertGreater(v_peak, 0.95, text)
        self.assertLess(t_stop - t_last, STOP_WITHIN, text)
        self.assertLess(v_end, STOP_SPEED, text)

    # (f) ----------------------------------------------------------------------------------------
    def test_f_non_finite_and_huge_commands(self):
        h = self.h
        h.stop_and_settle()
        with h.lock:
            n_log = len(h.rosout)
        t0 = rospy.get_time()
        # Non-finite: ignored; the car (stopped, command timed out) stays where it is.
        nan, inf = float('nan'), float('inf')
        moved = h.moved_by(h.publish_once, ((nan, 0.0), (0.0, nan), (inf, 0.0), (0.0, -inf),
                                            (-inf, inf), (nan, nan)))
        # Huge, each from rest: speed clamped to max_speed, forward and backward; the steering
        # to full lock (slowly: full lock at max_speed is not what this is about).
        phases = {}
        for name, v, w, secs in (('+1e9 m/s', 1e9, 0.0, 2.5), ('1e9 rad/s', 0.3, 1e9, 1.5),
                                 ('-1e9 m/s', -1e9, 0.0, 1.5)):
            h.stop_and_settle()
            h.drive(v, w)
            ta = rospy.get_time()
            h.wait_sim(secs)
            tb = rospy.get_time()
            h.stop_publishing()
            phases[name] = (ta, tb)
        h.stop_and_settle()
        t1 = rospy.get_time()

        samples = h.truth_between(t0, t1)
        all_finite = all(p.finite for p in samples)
        min_up = min(p.up for p in samples)
        v_max = {k: max(p.speed for p in h.truth_between(*span)) for k, span in phases.items()}
        wheel = [c[1] for c in h.wheel_cmds_between(t0, t1)]
        steer = [c[1] for c in h.steer_cmds_between(*phases['1e9 rad/s'])]
        w_max = max(abs(c) for c in wheel)
        steer_max = max(abs(c) for c in steer) if steer else float('nan')
        ping = rosnode.rosnode_ping(CMD_NODE, max_count=1)
        with h.lock:
            logs = h.rosout[n_log:]
        warns = [m.msg for m in logs if m.level >= Log.WARN]
        nonfinite = [m for m in warns if 'non-finite' in m]
        clamped = [m for m in warns if 'clamped' in m]
        text = self.report(
            'NaN/inf while stopped: car moved %.3f mm; max ground-truth speed %s (max_speed '
            '%.2f m/s); largest wheel command %.3f rad/s = %.4f m/s; largest left steering '
            'command %.4f rad; lowest up-axis z %.5f; all finite %s; cmd_vel_node alive %s; '
            'warnings from cmd_vel_node: %s', 1000.0 * moved,
            ', '.join('%.4f m/s at %s' % (v_max[k], k) for k in sorted(v_max)), self.max_speed,
            w_max, w_max * self.wheel_radius, steer_max, min_up, all_finite, ping, warns)
        self.assertLess(moved, 0.001, text)
        self.assertTrue(all_finite, text)
        self.assertTrue(ping, text)
        # The node's output is clamped exactly; the car follows it within the speed tolerance
        # of (a) (the wheel motor's step response: physics).
        self.assertLessEqual(w_max * self.wheel_radius, self.max_speed + 1e-9, text)
        self.assertLessEqual(max(v_max.values()), self.max_speed * (1.0 + SPEED_TOL), text)
        self.assertLessEqual(steer_max, 0.6 + 1e-9, text)
        self.assertGreater(min_up, 0.99, text)  # on its wheels
        self.assertTrue(nonfinite, 'no warning about the non-finite /cmd_vel: ' + text)
        self.assertTrue(clamped, 'no warning about the clamped /cmd_vel: ' + text)


if __name__ == '__main__':
    rostest.rosrun('tianracer_tests', 'ackermann_safety', AckermannSafety)
