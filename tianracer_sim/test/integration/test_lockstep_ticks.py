#!/usr/bin/env python3
"""rostest: lockstep ticks with nodes that start mid-run and robots spawned at run time.

The simulator runs at real_time_factor 0 with tick topics /tick_a, /tick_b, /tick_c and
"commands"; nobody publishes on them at first, so nothing is waited for and nothing warned.
Three times, mid-run, the test pauses the simulation, starts a publisher and a sim-time timer
of the tick period on the next tick topic (as a node started then does), waits until the
simulator is connected to it and unpauses. The timer must tick on the 20 ms grid (/clock goes
out on tick steps only: without that the timer would start where the last /clock was, 5, 10 or
15 ms off the grid three times in four), and the simulator must wait for each tick: every tick
sleeps 30 ms of wall time before publishing, and no later /clock may have come by then.
Then a tianracer is spawned and its four controllers loaded and started (controller_manager's
services, as its spawner would): their command topics become tick topics, not waited for while
nobody publishes, and a timer publishing on them holds the simulator the same way.
"""
import threading
import time
import unittest

import rospy
import rostest
from controller_manager_msgs.srv import LoadController, SwitchController, SwitchControllerRequest
from gazebo_msgs.srv import SpawnModel
from geometry_msgs.msg import Pose
from rosgraph_msgs.msg import Clock, Log
from std_msgs.msg import Float64
from std_srvs.srv import Empty

WAIT = 90.0
PERIOD = 0.02
TICKS = 15  # per timer
CONTROLLERS = ['left_rear_wheel_velocity_controller', 'right_rear_wheel_velocity_controller',
               'left_steering_hinge_position_controller', 'right_steering_hinge_position_controller']
COMMANDS = ['/tianracer/%s/command' % c for c in CONTROLLERS]
CM = '/tianracer/controller_manager/'


class Ticker(object):
    """A sim-time timer started now that publishes on `topics` after a wall-clock delay and
    records, per tick, its time and the latest /clock seen just before publishing."""

    def __init__(self, test, topics):
        self.test = test
        self.pubs = [rospy.Publisher(t, Float64, queue_size=10, tcp_nodelay=True) for t in topics]
        self.ticks = []
        self.timer = None

    def start(self):
        self.timer = rospy.Timer(rospy.Duration(PERIOD), self.tick)

    def connected(self):
        return all(p.get_num_connections() >= 1 for p in self.pubs)

    def tick(self, event):
        t = event.current_real.to_sec()
        time.sleep(0.03)
        self.ticks.append((t, self.test.latest_clock()))
        for p in self.pubs:
            p.publish(Float64(0.0))
        if len(self.ticks) >= TICKS:  # the node ends: nothing to wait for any more
            self.timer.shutdown()
            for p in self.pubs:
                p.unregister()


class LockstepTicksTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node('test_lockstep_ticks')
        cls.lock = threading.Lock()
        cls.clock = -1.0
        cls.warnings = []
        rospy.Subscriber('/clock', Clock, cls.on_clock, queue_size=1000, tcp_nodelay=True)
        rospy.Subscriber('/rosout', Log, cls.on_log, queue_size=100)
        rospy.wait_for_service('/gazebo/pause_physics', WAIT)
        cls.pause = rospy.ServiceProxy('/gazebo/pause_physics', Empty)
        cls.unpause = rospy.ServiceProxy('/gazebo/unpause_physics', Empty)

    @classmethod
    def on_clock(cls, m):
        with cls.lock:
            cls.clock = max(cls.clock, m.clock.to_sec())

    @classmethod
    def on_log(cls, m):
        if 'lockstep: nothing on' in m.msg:
            with cls.lock:
                cls.warnings.append(m.msg)

    @classmethod
    def latest_clock(cls):
        with cls.lock:
            return cls.clock

    def wait(self, cond, what):
        deadline = time.time() + WAIT
        while time.time() < deadline and not cond():
            time.sleep(0.02)
        self.assertTrue(cond(), what)

    def check(self, ticker, name):
        self.wait(lambda: len(ticker.ticks) >= TICKS, name + ': %d ticks' % len(ticker.ticks))
        for t, seen in ticker.ticks:
            k = round(t / PERIOD)
            self.assertAlmostEqual(t, k * PERIOD, places=6, msg='%s ticked off the grid at %.4f' % (name, t))
            self.assertAlmostEqual(seen, t, places=6,
                                   msg='%s: the simulator was at %.4f before the tick of %.4f' % (name, seen, t))

    def start_mid_run(self, topics, name):
        """Pause, start a ticker as a node started now would, unpause; check its ticks."""
        self.pause()
        time.sleep(0.2)  # the last /clock is in
        ticker = Ticker(self, topics)
        ticker.start()
        self.wait(ticker.connected, name + ': the simulator subscribes')
        time.sleep(0.2)
        self.unpause()
        self.check(ticker, name)

    def test_1_timers_started_mid_run_tick_on_the_grid(self):
        for k, name in enumerate(('/tick_a', '/tick_b', '/tick_c')):
            start = self.latest_clock()
            self.wait(lambda: self.latest_clock() > start + 0.3 + 0.13 * k, 'sim time runs')
            self.start_mid_run([name], name)
        with self.lock:
            self.assertEqual(self.warnings, [])  # nothing waited for before its publisher came

    def test_2_a_spawned_robots_commands_are_ticks(self):
        rospy.wait_for_service('/gazebo/spawn_urdf_model', WAIT)
        p = Pose()
        p.position.z = 0.012
        p.orientation.w = 1.0
        r = rospy.ServiceProxy('/gazebo/spawn_urdf_model', SpawnModel)(
            'tianracer', rospy.get_param('/robot_description'), '/tianracer', p, 'world')
        self.assertTrue(r.success, r.status_message)
        for name in ('load_controller', 'switch_controller'):
            rospy.wait_for_service(CM + name, WAIT)
        load = rospy.ServiceProxy(CM + 'load_controller', LoadController)
        for c in CONTROLLERS:
            self.assertTrue(load(c).ok, c)
        switch = rospy.ServiceProxy(CM + 'switch_controller', SwitchController)
        self.assertTrue(switch(CONTROLLERS, [], SwitchControllerRequest.STRICT, False, 0.0).ok)
        spawned_at = self.latest_clock()
        # Nobody publishes on them yet: no wait, no warning.
        self.wait(lambda: self.latest_clock() > spawned_at + 0.5, 'sim time runs on after the spawn')
        with self.lock:
            self.assertEqual(self.warnings, [])
        self.start_mid_run(COMMANDS, 'commands')


if __name__ == '__main__':
    rostest.rosrun('tianracer_sim', 'lockstep_ticks', LockstepTicksTest)
