#!/usr/bin/env python3
"""rostest: with DISABLE_GAZEBO_LASER=true (set for xacro by lidar_disabled.test) the robot
description has no ray sensor; the sim runs (clock, joint_states) without advertising /scan,
and neither its output nor /rosout carries an ERROR or FATAL line.

This node starts tianracer_sim_node itself, so that it reads all of the node's output: lines
logged at start-up, before the node's /rosout publisher is connected, never reach /rosout.
"""
import re
import signal
import subprocess
import tempfile
import threading
import time
import unittest

import rospy
import rostest
from rosgraph_msgs.msg import Clock, Log
from sensor_msgs.msg import JointState

from sim_node_binary import node_binary


class LidarDisabled(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node('test_lidar_disabled')
        cls.lock = threading.Lock()
        cls.clock = []
        cls.joint_states = 0
        cls.bad_logs = []
        rospy.Subscriber('/clock', Clock, cls.on_clock, queue_size=100)
        rospy.Subscriber('/tianracer/joint_states', JointState, cls.on_js, queue_size=100)
        rospy.Subscriber('/rosout_agg', Log, cls.on_log, queue_size=100)
        cls.output = tempfile.TemporaryFile()
        cls.proc = subprocess.Popen(
            [node_binary(), '__name:=tianracer_sim', '_world:=walled_room',
             '_real_time_factor:=1.0'],
            stdout=cls.output, stderr=subprocess.STDOUT)
        deadline = time.time() + 30
        while time.time() < deadline and cls.proc.poll() is None:
            with cls.lock:
                if len(cls.clock) > 20:
                    break
            time.sleep(0.05)

    @classmethod
    def tearDownClass(cls):
        if cls.proc.poll() is None:
            cls.proc.send_signal(signal.SIGINT)
            try:
                cls.proc.wait(timeout=15)
            except subprocess.TimeoutExpired:
                cls.proc.kill()
                cls.proc.wait()

    @classmethod
    def on_clock(cls, msg):
        with cls.lock:
            cls.clock.append(msg.clock.to_sec())

    @classmethod
    def on_js(cls, msg):
        with cls.lock:
            cls.joint_states += 1

    @classmethod
    def on_log(cls, msg):
        if msg.level >= Log.ERROR and 'tianracer_sim' in msg.name:
            with cls.lock:
                cls.bad_logs.append('%s: %s' % (msg.name, msg.msg))

    def node_output(self):
        self.output.seek(0)
        return self.output.read().decode(errors='replace')

    def test_1_description_has_no_lidar(self):
        urdf = rospy.get_param('/robot_description')
        self.assertIn('<robot', urdf)
        self.assertNotIn('hokuyo', urdf)
        self.assertNotIn('type="ray"', urdf)
        self.assertIn('type="camera"', urdf)  # the rest of the gazebo extensions are there

    def test_2_runs_without_scan(self):
        self.assertIsNone(self.proc.poll(), 'the sim exited:\n' + self.node_output())
        with self.lock:
            self.assertGreater(len(self.clock), 20, 'no /clock:\n' + self.node_output())
            t0, js0 = self.clock[-1], self.joint_states
        rospy.sleep(rospy.Duration.from_sec(1.0))
        with self.lock:
            t1, js1 = self.clock[-1], self.joint_states
        rospy.loginfo('clock %.3f -> %.3f, %d joint_states in between', t0, t1, js1 - js0)
        self.assertGreaterEqual(t1 - t0, 1.0 - 1e-6)  # float sum of clock stamps
        self.assertGreater(js1 - js0, 40)  # 50 Hz
        topics = [t for t, _ in rospy.get_published_topics()]
        self.assertIn('/tianracer/joint_states', topics)
        self.assertIn('/rrbot/camera1/image_raw', topics)
        self.assertNotIn('/scan', topics)
        self.assertFalse([t for t in topics if 'scan' in t], topics)

    def test_3_nothing_logs_an_error(self):
        rospy.sleep(rospy.Duration.from_sec(0.5))
        self.assertIsNone(self.proc.poll(), 'the sim exited:\n' + self.node_output())
        with self.lock:
            self.assertEqual(self.bad_logs, [])
        # Stop it: its stdout goes to a file, fully buffered until it exits.
        self.proc.send_signal(signal.SIGINT)
        code = self.proc.wait(timeout=20)
        out = self.node_output()
        self.assertEqual(code, 0, 'exit code %d after SIGINT:\n%s' % (code, out))
        self.assertIn('robot \'tianracer\'', out)  # its start-up lines are there
        bad = [line for line in out.splitlines() if re.search(r'\b(ERROR|FATAL)\b', line)]
        self.assertEqual(bad, [], 'the sim logged errors:\n' + out)
        warnings = [line for line in out.splitlines() if 'WARN' in line]
        rospy.loginfo('sim output: %d lines, %d warnings, none about a lidar: %s',
                      len(out.splitlines()), len(warnings),
                      not [w for w in warnings if 'lidar' in w or 'ray' in w])
        self.assertFalse([w for w in warnings if 'hokuyo' in w or 'scan' in w], warnings)

if __name__ == '__main__':
    rostest.rosrun('tianracer_sim', 'lidar_disabled', LidarDisabled)
