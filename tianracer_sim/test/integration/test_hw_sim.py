#!/usr/bin/env python3
"""rostest: DefaultRobotHWSim's parameters and e-stop through ROS (hw_sim.test): the hinge
commanded to 0.9 rad (within its URDF limit 1.0) stops at /hw/joint_limits/hinge's 0.3; the
spinner reaches its command under pid_gains; while /hw/e_stop is true the hinge holds where it
was and the spinner stops whatever the commands; released, the controllers restart and new
commands move the joints again. Sim time throughout."""
import unittest

import rospy
import rostest
from rosgraph_msgs.msg import Clock
from sensor_msgs.msg import JointState
from std_msgs.msg import Bool, Float64
from tianracer_sim.sim_time import Stream, clock_stamp, sim_sleep, wait_for

WALL_TIMEOUT = 120.0


class HwSimTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node('test_hw_sim')
        cls.clock = Stream('/clock', Clock, stamp=clock_stamp, keep=1)
        cls.joint_states = Stream('/hw/joint_states', JointState, keep=50)
        cls.hinge = rospy.Publisher('/hw/hinge_controller/command', Float64, queue_size=1,
                                    latch=True)
        cls.spinner = rospy.Publisher('/hw/spinner_controller/command', Float64, queue_size=1,
                                      latch=True)
        cls.e_stop = rospy.Publisher('/hw/e_stop', Bool, queue_size=1, latch=True)
        wait_for(lambda: cls.clock.latest(), '/clock', WALL_TIMEOUT)
        wait_for(lambda: cls.joint_states.latest(), '/hw/joint_states', WALL_TIMEOUT)
        for pub in (cls.hinge, cls.spinner, cls.e_stop):
            wait_for(lambda: pub.get_num_connections() > 0, pub.name, WALL_TIMEOUT)

    def state(self, joint):
        self.joint_states.first_stamped(rospy.get_time())
        m = self.joint_states.latest()
        i = m.name.index(joint)
        return m.position[i], m.velocity[i]

    def test_limits_pid_and_e_stop(self):
        self.hinge.publish(Float64(0.9))
        self.spinner.publish(Float64(3.0))
        sim_sleep(2.0, wall_timeout=WALL_TIMEOUT)
        hinge, _ = self.state('hinge')
        _, spin = self.state('spinner')
        print('hinge %.4f rad for 0.9 (joint_limits 0.3), spinner %.3f rad/s' % (hinge, spin))
        self.assertAlmostEqual(hinge, 0.3, delta=0.005)
        self.assertAlmostEqual(spin, 3.0, delta=0.1)

        # the stop: new commands do not move the hinge, the spinner stops
        self.e_stop.publish(Bool(True))
        sim_sleep(0.2, wall_timeout=WALL_TIMEOUT)
        self.hinge.publish(Float64(-0.2))
        sim_sleep(1.5, wall_timeout=WALL_TIMEOUT)
        hinge, _ = self.state('hinge')
        _, spin = self.state('spinner')
        print('stopped: hinge %.4f rad, spinner %.3f rad/s' % (hinge, spin))
        self.assertAlmostEqual(hinge, 0.3, delta=0.01)
        self.assertAlmostEqual(spin, 0.0, delta=0.1)

        # released: the controllers restart (position: hold, velocity: 0), then follow commands
        self.e_stop.publish(Bool(False))
        sim_sleep(0.5, wall_timeout=WALL_TIMEOUT)
        hinge, _ = self.state('hinge')
        self.assertAlmostEqual(hinge, 0.3, delta=0.01)
        self.hinge.publish(Float64(-0.2))
        sim_sleep(1.5, wall_timeout=WALL_TIMEOUT)
        hinge, _ = self.state('hinge')
        print('released: hinge %.4f rad' % hinge)
        self.assertAlmostEqual(hinge, -0.2, delta=0.005)


if __name__ == '__main__':
    rostest.rosrun('tianracer_sim', 'hw_sim', HwSimTest)
