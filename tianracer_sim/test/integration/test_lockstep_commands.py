#!/usr/bin/env python3
"""rostest: with ~lockstep/ticks "commands", a controller loaded at run time (controller_manager's
load_controller) puts its command topic into lockstep's tick topics, and unloading takes it out.

A tick topic added at run time is waited for from its first message on. The test publishes one
latched command: the simulator receives it as soon as it subscribes, then waits for the next tick's
message, times out after 1 s of wall time and reports it once, naming the topic. Then the
controller is stopped and unloaded and loaded again: a topic that stayed in the list would keep its
"reported" mark and stay silent; a topic that went and came back is a new one and is reported
again. Before any load nothing is waited for: sim time runs without a lockstep warning.
"""
import threading
import time
import unittest

import rospy
import rostest
from controller_manager_msgs.srv import (LoadController, SwitchController,
                                         SwitchControllerRequest, UnloadController)
from rosgraph_msgs.msg import Clock, Log
from std_msgs.msg import Float64

CM = '/tianracer/controller_manager/'
WHEEL = 'left_rear_wheel_velocity_controller'
TOPIC = '/tianracer/%s/command' % WHEEL
STRICT = SwitchControllerRequest.STRICT


def wall_wait(predicate, timeout, what):
    end = time.time() + timeout
    while time.time() < end and not rospy.is_shutdown():
        if predicate():
            return
        time.sleep(0.05)
    if not predicate():
        raise AssertionError('timed out waiting for ' + what)


class LockstepCommandsTest(unittest.TestCase):
    def test_run_time_controllers_are_tick_topics(self):
        rospy.init_node('test_lockstep_commands')
        lock = threading.Lock()
        st = {'clock': -1.0, 'warnings': []}

        def on_clock(m):
            with lock:
                st['clock'] = max(st['clock'], m.clock.to_sec())

        def on_log(m):
            if m.msg.startswith('lockstep: nothing on'):
                with lock:
                    st['warnings'].append(m.msg)

        def clock():
            with lock:
                return st['clock']

        def warnings():
            with lock:
                return list(st['warnings'])

        rospy.Subscriber('/clock', Clock, on_clock, queue_size=10)
        rospy.Subscriber('/rosout', Log, on_log, queue_size=1000)
        for name in ('load_controller', 'switch_controller', 'unload_controller'):
            rospy.wait_for_service(CM + name, timeout=240.0)
        load = rospy.ServiceProxy(CM + 'load_controller', LoadController)
        switch = rospy.ServiceProxy(CM + 'switch_controller', SwitchController)
        unload = rospy.ServiceProxy(CM + 'unload_controller', UnloadController)

        # No controller with a command topic yet: nothing is waited for.
        wall_wait(lambda: clock() >= 0.0, 120.0, '/clock')
        t0 = clock()
        wall_wait(lambda: clock() > t0 + 2.0, 120.0, '2 s of sim time')
        self.assertEqual(warnings(), [])

        # Loaded and started at run time: its command topic is waited for once it speaks.
        command = rospy.Publisher(TOPIC, Float64, queue_size=1, latch=True)
        command.publish(Float64(0.0))
        self.assertTrue(load(WHEEL).ok)
        self.assertTrue(switch([WHEEL], [], STRICT, False, 0.0).ok)
        wall_wait(lambda: len(warnings()) >= 1, 120.0, 'the lockstep timeout on ' + TOPIC)
        self.assertIn('nothing on %s within 1 s (wall)' % TOPIC, warnings()[0])
        t1 = clock()
        wall_wait(lambda: clock() > t1 + 1.0, 120.0, 'sim time to run on after the timeout')
        self.assertEqual(len(warnings()), 1, warnings())  # reported once, then not waited for

        # Unloaded, the topic leaves the list; loaded again, it is a new tick topic (reported
        # anew when it times out). Had it stayed, its timeout would not be reported again.
        self.assertTrue(switch([], [WHEEL], STRICT, False, 0.0).ok)
        self.assertTrue(unload(WHEEL).ok)
        t2 = clock()
        wall_wait(lambda: clock() > t2 + 1.0, 120.0, 'sim time to run after the unload')
        self.assertTrue(load(WHEEL).ok)
        self.assertTrue(switch([WHEEL], [], STRICT, False, 0.0).ok)
        wall_wait(lambda: len(warnings()) >= 2, 120.0, 'the second lockstep timeout on ' + TOPIC)
        self.assertIn('nothing on %s within 1 s (wall)' % TOPIC, warnings()[1])


if __name__ == '__main__':
    rostest.rosrun('tianracer_sim', 'lockstep_commands', LockstepCommandsTest)
