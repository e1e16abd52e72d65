#!/usr/bin/env python3
"""rostest: faults from the ROS side while the car drives, through tianracer.launch
(empty world, every sensor). In every case the simulator keeps stepping and what it publishes
stays sane.

- subscriber churn: 60 subscribe/unsubscribe cycles each on the front camera's image and the
  depth camera's cloud; then the sim still steps, images come at full size and /scan at 40 Hz;
- a slow consumer (0.3 s per depth image, queue 1) does not hold back a fast one on the same
  topic: the fast one gets the depth camera's 20 Hz in sim time;
- /gazebo/reset_simulation at full speed, 100 times: after each, /clock, ground truth and
  wheel odometry restart at the spawn pose, and on /tf each (publisher, frame) steps back in
  time once per reset at most (old and new timelines never interleave, so TF listeners
  clear once instead of warning TF_OLD_DATA for every message);
- a pause/unpause storm (200 calls while driving): /clock never goes back, and the sim runs
  on after the last unpause;
- the cmd_vel node killed and restarted while the car drives: the sim runs on and the new
  node drives the car (stop, then 1 m/s).
Nothing published contains NaN (ground truth, wheel odometry, joint states, scans).
"""
import math
import os
import subprocess
import sys
import threading
import time
import unittest

import rosnode
import rospy
import rostest
from geometry_msgs.msg import Twist
from nav_msgs.msg import Odometry
from rosgraph_msgs.msg import Clock
from sensor_msgs.msg import Image, JointState, LaserScan, PointCloud2
from std_srvs.srv import Empty
from tf2_msgs.msg import TFMessage

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import tf_check  # noqa: E402

FULL_SPEED = 3.0  # the cmd_vel node's max_speed
SLOW_CONSUMER = """
import signal, sys, time
import rospy
from sensor_msgs.msg import Image
n = [0]
def slow(msg):
    n[0] += 1
    time.sleep(0.3)
rospy.init_node('slow_consumer')
rospy.Subscriber('/real_sense/depth/image_raw', Image, slow, queue_size=1, buff_size=2 ** 24)
signal.signal(signal.SIGTERM, lambda *_: rospy.signal_shutdown('done'))
rospy.spin()
print('received %d' % n[0])
"""


def finite_odometry(msg):
    p, q, v = msg.pose.pose.position, msg.pose.pose.orientation, msg.twist.twist
    return all(math.isfinite(x) for x in (p.x, p.y, p.z, q.x, q.y, q.z, q.w, v.linear.x,
                                          v.linear.y, v.linear.z, v.angular.x, v.angular.y,
                                          v.angular.z))


class Recorder(object):
    """/clock, ground truth, wheel odometry and /tf with their arrival order, and a NaN count
    over everything the sim and the control nodes publish."""

    def __init__(self):
        self.lock = threading.Lock()
        self.clock, self.truth, self.odom = [], [], []
        self.nan = {}
        self.tf_last = {}      # (publisher, child) -> last stamp
        self.tf_back = {}      # (publisher, child) -> backward steps
        rospy.Subscriber('/clock', Clock, self._on_clock, queue_size=1000)
        rospy.Subscriber('/tianracer/ground_truth/odom', Odometry, self._on_truth, queue_size=1000)
        rospy.Subscriber('/tianracer/odom', Odometry, self._on_odom, queue_size=1000)
        rospy.Subscriber('/tianracer/joint_states', JointState, self._on_joints, queue_size=1000)
        rospy.Subscriber('/scan', LaserScan, self._on_scan, queue_size=100)
        rospy.Subscriber('/tf', TFMessage, self._on_tf, queue_size=1000)

    def _bad(self, topic):
        with self.lock:
            self.nan[topic] = self.nan.get(topic, 0) + 1

    def _on_clock(self, msg):
        with self.lock:
            self.clock.append(msg.clock.to_sec())

    def _on_truth(self, msg):
        if not finite_odometry(msg):
            self._bad('ground_truth')
        with self.lock:
            self.truth.append(msg)

    def _on_odom(self, msg):
        if not finite_odometry(msg):
            self._bad('odom')
        with self.lock:
            self.odom.append(msg)

    def _on_joints(self, msg):
        if not all(math.isfinite(x) for x in list(msg.position) + list(msg.velocity) +
                   list(msg.effort)):
            self._bad('joint_states')

    def _on_scan(self, msg):
        if any(math.isnan(r) for r in msg.ranges):
            self._bad('scan')

    def _on_tf(self, msg):
        caller = msg._connection_header.get('callerid', '?')
        with self.lock:
            for t in msg.transforms:
                key = (caller, t.child_frame_id)
                stamp = t.header.stamp.to_sec()
                if key in self.tf_last and stamp < self.tf_last[key]:
                    self.tf_back[key] = self.tf_back.get(key, 0) + 1
                self.tf_last[key] = stamp

    def count(self, name):
        with self.lock:
            return len(getattr(self, name))

    def since(self, name, index):
        with self.lock:
            return list(getattr(self, name)[index:])


class CmdVel(object):
    """Repeats a Twist on /cmd_vel at 20 Hz of wall time from a thread (so that it keeps
    going while the test waits on services)."""

    def __init__(self):
        self.pub = rospy.Publisher('/cmd_vel', Twist, queue_size=10)
        self.twist = Twist()
        self.lock = threading.Lock()
        t = threading.Thread(target=self._run)
        t.daemon = True
        t.start()

    def set(self, linear, angular=0.0):
        with self.lock:
            self.twist = Twist()
            self.twist.linear.x, self.twist.angular.z = linear, angular

    def _run(self):
        while not rospy.is_shutdown():
            with self.lock:
                self.pub.publish(self.twist)
            time.sleep(0.05)


class Faults(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node('test_faults')
        cls.rec = Recorder()
        cls.cmd = CmdVel()
        for srv in ('pause_physics', 'unpause_physics', 'reset_simulation'):
            rospy.wait_for_service('/gazebo/' + srv, timeout=90)
        cls.pause = rospy.ServiceProxy('/gazebo/pause_physics', Empty)
        cls.unpause = rospy.ServiceProxy('/gazebo/unpause_physics', Empty)
        cls.reset = rospy.ServiceProxy('/gazebo/reset_simulation', Empty)
        ok = tf_check.wall_wait(lambda: cls.rec.count('truth') > 0 and cls.rec.count('odom') > 0,
                                90.0)
        assert ok, 'no ground truth or wheel odometry from tianracer.launch'
        tf_check.wall_wait(lambda: cls.cmd.pub.get_num_connections() > 0, 30.0)

    def tearDown(self):
        self.cmd.set(0.0)

    def assert_sim_steps(self, sim_seconds=0.5):
        """/clock advances by `sim_seconds` within a generous wall bound."""
        n = self.rec.count('clock')
        tf_check.wall_wait(lambda: self.rec.count('clock') > n, 60.0)
        t0 = self.rec.since('clock', -1)[0]
        ok = tf_check.wall_wait(lambda: self.rec.since('clock', -1)[0] >= t0 + sim_seconds, 120.0)
        self.assertTrue(ok, 'the sim stopped stepping at t = %.3f' % t0)

    def assert_no_nan(self):
        self.assertEqual(self.rec.nan, {})

    def test_1_subscriber_churn_on_camera_and_cloud(self):
        self.cmd.set(1.0, 0.5)
        for i in range(60):
            subs = [rospy.Subscriber('/rrbot/camera1/image_raw', Image, lambda m: None),
                    rospy.Subscriber('/real_sense/depth/points', PointCloud2, lambda m: None)]
            time.sleep(0.01 * (i % 5))  # from immediately to a few frames
            for s in subs:
                s.unregister()
        self.assert_sim_steps()
        image = rospy.wait_for_message('/rrbot/camera1/image_raw', Image, timeout=60)
        self.assertEqual((image.width, image.height, len(image.data)), (800, 800, 800 * 800 * 3))
        cloud = rospy.wait_for_message('/real_sense/depth/points', PointCloud2, timeout=60)
        self.assertEqual((cloud.width, cloud.height), (640, 480))
        scans = tf_check.scans('/scan')
        tf_check.sim_sleep(1.0)
        stamps = [s.header.stamp.to_sec() for s in scans.all]
        rate = (len(stamps) - 1) / (stamps[-1] - stamps[0])
        self.assertAlmostEqual(rate, 40.0, delta=2.0)
        self.assert_no_nan()

    def test_2_slow_consumer_does_not_hold_back_a_fast_one(self):
        # The slow consumer is its own process (one rospy process serves all its callbacks of
        # a topic in one thread): 0.3 s of wall time per depth image, queue 1. (Depth images,
        # not clouds: a Python consumer cannot read 10 MB clouds at 40 a second itself.)
        slow = subprocess.Popen([sys.executable, '-c', SLOW_CONSUMER],
                                stdout=subprocess.PIPE, stderr=subprocess.STDOUT)
        fast = []
        sub = rospy.Subscriber('/real_sense/depth/image_raw', Image,
                               lambda m: fast.append(m.header.stamp.to_sec()), queue_size=100,
                               buff_size=2 ** 26)
        try:
            self.assertTrue(tf_check.wall_wait(lambda: len(fast) > 0, 60.0))
            self.assertTrue(tf_check.wall_wait(
                lambda: rosnode.rosnode_ping('/slow_consumer', max_count=1), 60.0))
            start = len(fast)
            tf_check.sim_sleep(2.0)
            stamps = fast[start:]
            rate = (len(stamps) - 1) / (stamps[-1] - stamps[0])
        finally:
            sub.unregister()
            slow.terminate()
            out = slow.communicate(timeout=30)[0].decode(errors='replace')
        received = int(out.split('received')[-1].split()[0]) if 'received' in out else -1
        rospy.loginfo('slow consumer: %d images; fast consumer: %d images, %.1f Hz sim time',
                      received, len(stamps), rate)
        self.assertAlmostEqual(rate, 20.0, delta=1.5)
        self.assert_sim_steps()

    def test_3_reset_at_full_speed_100_times(self):
        self.cmd.set(FULL_SPEED)
        spawn = self.rec.truth[0].pose.pose.position
        resets = 100
        for i in range(resets):
            # Drive for 0.2 s of sim time at full speed, then reset.
            t0 = rospy.get_time()
            tf_check.wall_wait(lambda: rospy.get_time() >= t0 + 0.2 or rospy.get_time() < t0,
                               60.0)
            before = self.rec.since('clock', -1)[0]
            n_clock, n_truth, n_odom = (self.rec.count('clock'), self.rec.count('truth'),
                                        self.rec.count('odom'))
            self.reset()
            # Each stream resumes from the new timeline (messages already in flight before the
            # reset may still arrive first), and once it has, nothing of the old one follows.
            # New timeline: stamps from 0; every cycle drives 0.2 s before its reset.
            new = lambda name, stamp: [k for k, m in enumerate(self.rec.since(name, 0))
                                       if k >= {'clock': n_clock, 'truth': n_truth}[name] and
                                       stamp(m) < 0.1]
            ok = tf_check.wall_wait(lambda: new('clock', lambda c: c) and
                                    new('truth', lambda m: m.header.stamp.to_sec()), 60.0)
            self.assertTrue(ok, 'reset %d: the streams did not resume' % i)
            tf_check.sim_sleep(0.05)
            clock = self.rec.since('clock', new('clock', lambda c: c)[0])
            self.assertLess(clock[0], 0.1, 'reset %d: /clock resumed at %.3f (was %.3f)' %
                            (i, clock[0], before))
            self.assertLess(max(clock), before, 'reset %d: old /clock after the new one' % i)
            truth = self.rec.since('truth', new('truth', lambda m: m.header.stamp.to_sec())[0])
            self.assertLess(truth[0].header.stamp.to_sec(), 0.05, 'reset %d' % i)
            self.assertLess(max(m.header.stamp.to_sec() for m in truth), before, 'reset %d' % i)
            p = truth[0].pose.pose.position
            self.assertLess(math.hypot(p.x - spawn.x, p.y - spawn.y), 0.01, 'reset %d' % i)
            odom = tf_check.wall_wait(lambda: any(
                m.header.stamp.to_sec() < 0.1 for m in self.rec.since('odom', n_odom)), 60.0)
            self.assertTrue(odom, 'reset %d: wheel odometry did not restart' % i)
            o = next(m for m in self.rec.since('odom', n_odom)
                     if m.header.stamp.to_sec() < 0.1).pose.pose.position
            self.assertLess(math.hypot(o.x, o.y), 0.05, 'reset %d: odometry at (%.3f, %.3f)' %
                            (i, o.x, o.y))
        # The car drives on after the last reset: the cmd_vel node's timer survived 100 jumps
        # back in time.
        tf_check.sim_sleep(1.0)
        v = self.rec.since('truth', -1)[0].twist.twist.linear.x
        self.assertGreater(v, 0.9 * FULL_SPEED)
        with self.rec.lock:
            back = dict(self.rec.tf_back)
        rospy.loginfo('TF steps back per (publisher, frame) over %d resets: %s', resets, back)
        self.assertTrue(back, 'no TF stream went back in time: were the resets seen?')
        for key, n in back.items():
            self.assertLessEqual(n, resets, '%s stepped back %d times in %d resets' %
                                 (key, n, resets))
        self.assert_no_nan()

    def test_4_pause_storm(self):
        self.cmd.set(1.0)
        n = self.rec.count('clock')
        for i in range(100):
            self.pause()
            self.unpause()
        clock = self.rec.since('clock', n)
        self.assertTrue(all(b >= a for a, b in zip(clock, clock[1:])), 'clock went back')
        self.assert_sim_steps()
        self.assert_no_nan()

    def test_5_cmd_vel_node_killed_and_restarted(self):
        self.cmd.set(1.0)
        tf_check.sim_sleep(1.0)
        self.assertIn('/cmd_vel_node', rosnode.get_node_names())
        rosnode.kill_nodes(['/cmd_vel_node'])
        tf_check.wall_wait(lambda: '/cmd_vel_node' not in rosnode.get_node_names(), 30.0)
        self.assert_sim_steps()
        node = subprocess.Popen(['rosrun', 'tianracer_control', 'cmd_vel_node',
                                 '__name:=cmd_vel_node', '_robot_namespace:=/tianracer',
                                 '_cmd_vel_topic:=/cmd_vel'])
        try:
            self.assertTrue(tf_check.wall_wait(
                lambda: '/cmd_vel_node' in rosnode.get_node_names(), 60.0))
            self.cmd.set(0.0)
            tf_check.sim_sleep(1.5)
            v = self.rec.since('truth', -1)[0].twist.twist.linear.x
            self.assertLess(abs(v), 0.05, 'the restarted node did not stop the car')
            self.cmd.set(1.0)
            tf_check.sim_sleep(2.0)
            v = self.rec.since('truth', -1)[0].twist.twist.linear.x
            self.assertAlmostEqual(v, 1.0, delta=0.05)
        finally:
            self.cmd.set(0.0)
            tf_check.sim_sleep(0.5)
            node.terminate()
            node.wait(30)
        self.assert_no_nan()


if __name__ == '__main__':
    rostest.rosrun('tianracer_bringup', 'faults', Faults)
