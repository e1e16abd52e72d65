#!/usr/bin/env python3
"""rostest: a world's <actor> in /gazebo/model_states (docs/actors.md).

test/data/worlds/actor_walker.world: a box actor walks a 2 m square at z 1 in 4 s, looped,
standing at its <pose> (0 0 5) until its first frame (1/30 s of sim time). The test reads
/gazebo/model_states with the /clock time of each message: the walker is listed, it is on the
square (|x| or |y| near 1, z 1) once it plays, its pose changes between two sim times 0.5 s apart,
and get_model_state gives it too. Sim time throughout; wall time only bounds the waits.
"""
import unittest

import rospy
import rostest
from tianracer_sim.sim_time import Stream, clock_stamp, wait_for
from gazebo_msgs.msg import ModelStates
from gazebo_msgs.srv import GetModelState
from rosgraph_msgs.msg import Clock

WALL_TIMEOUT = 120.0


def walker_pose(msg):
    return msg.pose[msg.name.index('walker')].position


class ActorWorldTest(unittest.TestCase):
    def test_model_states_follow_the_actor(self):
        rospy.init_node('test_actor_world')
        clock = Stream('/clock', Clock, stamp=clock_stamp, keep=1)
        states = Stream('/gazebo/model_states', ModelStates, stamp=lambda m: 0.0, keep=1)
        wait_for(lambda: clock.latest() and clock.latest().clock.to_sec() > 0.2,
                 '0.2 s of sim time', WALL_TIMEOUT)
        msg = wait_for(lambda: states.latest(), '/gazebo/model_states', WALL_TIMEOUT)
        self.assertIn('walker', msg.name)
        p = walker_pose(msg)
        self.assertAlmostEqual(p.z, 1.0, places=6)  # playing: its <pose> had z 5
        self.assertGreater(max(abs(p.x), abs(p.y)), 0.9, 'on the square: %s' % p)
        t0 = clock.latest().clock.to_sec()
        wait_for(lambda: clock.latest().clock.to_sec() > t0 + 0.5, '0.5 s of sim time',
                 WALL_TIMEOUT)
        q = wait_for(lambda: walker_pose(states.latest()) if
                     (walker_pose(states.latest()).x, walker_pose(states.latest()).y) != (p.x, p.y)
                     else None, 'the walker to move', WALL_TIMEOUT)
        self.assertGreater(abs(q.x - p.x) + abs(q.y - p.y), 0.1)
        rospy.wait_for_service('/gazebo/get_model_state', timeout=WALL_TIMEOUT)
        res = rospy.ServiceProxy('/gazebo/get_model_state', GetModelState)('walker', 'world')
        self.assertTrue(res.success, res.status_message)
        self.assertAlmostEqual(res.pose.position.z, 1.0, places=6)
        self.assertEqual(res.twist.linear.x, 0.0)


if __name__ == '__main__':
    rostest.rosrun('tianracer_sim', 'test_actor_world', ActorWorldTest)
