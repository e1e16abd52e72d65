#!/usr/bin/env python3
"""rostest: lockstep. The node under test answers every ground-truth message (50 Hz of sim time,
the reply period) on /cmd_vel after 0-20 ms of wall time. With lockstep the simulator publishes
the /clock of a reply step only after the answer, so when the answer to the message stamped t is
sent, no /clock >= t has been seen yet (without lockstep, at real_time_factor 0, the clock of t
goes out before the message and the simulator runs on). Then the answers stop: the simulator
waits one timeout (1 s wall), warns once on /rosout and runs on."""
import random
import threading
import time
import unittest

import rospy
import rostest
from geometry_msgs.msg import Twist
from nav_msgs.msg import Odometry
from rosgraph_msgs.msg import Clock, Log
from tianracer_sim.sim_time import Paused, lossless, wait_connected, wait_for

ANSWERED_UNTIL = 3.0  # s of sim time


class LockstepTest(unittest.TestCase):
    def test_lockstep(self):
        rospy.init_node('test_lockstep')
        lock = threading.Lock()
        st = {'clock': -1.0, 'answers': [], 'warnings': [], 'last_truth': 0.0}
        rng = random.Random(1)
        pub = rospy.Publisher('/cmd_vel', Twist, queue_size=10, tcp_nodelay=True)

        def on_clock(m):
            with lock:
                st['clock'] = max(st['clock'], m.clock.to_sec())

        def on_truth(m):
            t = m.header.stamp.to_sec()
            with lock:
                st['last_truth'] = t
            if t > ANSWERED_UNTIL:
                return
            time.sleep(rng.uniform(0.0, 0.02))
            with lock:
                st['answers'].append((t, st['clock']))
            pub.publish(Twist())

        def on_log(m):
            if 'lockstep: nothing on /cmd_vel' in m.msg:
                with lock:
                    st['warnings'].append(m.msg)

        # Every /clock (rospy's own clock subscription keeps only the last of a burst).
        lossless(rospy.Subscriber('/clock', Clock, on_clock, tcp_nodelay=True))
        truth = lossless(rospy.Subscriber('/tianracer/ground_truth/odom', Odometry, on_truth,
                                          tcp_nodelay=True))
        rospy.Subscriber('/rosout', Log, on_log, queue_size=100)
        rospy.wait_for_service('/gazebo/unpause_physics', 60)
        # Connected, not only registered: the answers reach the sim, the data reach us.
        wait_connected(pub)
        wait_connected(truth)
        # The sim starts paused and published its first /clock before we were connected:
        # pause_physics puts it on /clock again (this used to be a 60 s wait for a /clock
        # that a paused sim never sends).
        Paused().unpause()

        def done():
            with lock:
                return st['last_truth'] > ANSWERED_UNTIL + 2.0 and st['warnings']

        wait_for(done, 'the sim going on after the answers stopped, with a warning', 150,
                 poll=0.1)
        with lock:
            answers, warnings = list(st['answers']), list(st['warnings'])
            last = st['last_truth']
        self.assertGreater(len(answers), 0.9 * ANSWERED_UNTIL * 50, answers[-5:])
        early = [(t, c) for t, c in answers if t > 0.0 and c >= t - 1e-9]
        self.assertEqual(early, [], 'the /clock of a step went out before the answer to its data')
        # Every reply step was answered: consecutive stamps 0.02 s apart (no message skipped).
        stamps = [t for t, _ in answers if t > 0.0]
        gaps = [round(b - a, 6) for a, b in zip(stamps, stamps[1:])]
        self.assertEqual(set(gaps), {0.02}, gaps[:20])
        # The answers stopped: one timeout, one warning, and the simulator ran on.
        self.assertGreater(last, ANSWERED_UNTIL + 2.0)
        self.assertEqual(len(warnings), 1, warnings)
        self.assertIn('within 1 s (wall)', warnings[0])


if __name__ == '__main__':
    rostest.rosrun('tianracer_sim', 'lockstep', LockstepTest)
