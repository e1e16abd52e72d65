"""What the rostests of the Gazebo interface share (test_gazebo_interface.py,
test_gazebo_free_body.py; test_bad_input_matrix.py for moved_in_plane): /gazebo's services as
attributes of the test case, sim-time waits, a push by apply_body_wrench, and how far a model
moved."""
import math
import unittest

import rospy
from gazebo_msgs.srv import (ApplyBodyWrench, BodyRequest, GetLinkState, GetModelProperties,
                             GetModelState, GetWorldProperties, SetLinkState, SetModelState)
from geometry_msgs.msg import Point, Vector3, Wrench
from std_srvs.srv import Empty
from tianracer_sim.sim_time import Paused, connect_gazebo, sim_sleep

SERVICES = {'pause_physics': Empty, 'unpause_physics': Empty, 'reset_world': Empty,
            'get_model_state': GetModelState, 'set_model_state': SetModelState,
            'get_link_state': GetLinkState, 'set_link_state': SetLinkState,
            'get_model_properties': GetModelProperties,
            'get_world_properties': GetWorldProperties, 'apply_body_wrench': ApplyBodyWrench,
            'clear_body_wrenches': BodyRequest}


def no_stamp(msg):
    return 0.0  # ModelStates and LinkStates carry no header


def moved_in_plane(before, after):
    """How far a model moved in x and y from one of its states (get_model_state's answers)
    to another."""
    return math.hypot(after.pose.position.x - before.pose.position.x,
                      after.pose.position.y - before.pose.position.y)


class GazeboCase(unittest.TestCase):
    @classmethod
    def connect(cls, names):
        """Each /gazebo service of `names` (keys of SERVICES), once it is there, as an attribute."""
        connect_gazebo(cls, {n: SERVICES[n] for n in names}, 60)

    def wait_sim(self, seconds):
        sim_sleep(seconds)

    def paused(self):
        """pause_physics; returns once this process's clock is at the paused time."""
        return Paused()

    def push_x(self, link, F, T):
        """apply_body_wrench: F N along x on `link` for T s of sim time from now; then, unpaused,
        0.5 s of sim time, and paused again."""
        r = self.apply_body_wrench(link, '', Point(), Wrench(Vector3(F, 0, 0), Vector3()),
                                   rospy.Time(0), rospy.Duration(T))
        self.assertTrue(r.success, r.status_message)
        self.unpause_physics()
        self.wait_sim(0.5)
        self.paused()
