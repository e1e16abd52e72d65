#!/usr/bin/env python3
"""rostest: the Gazebo interface on a free box (free_box.world's 'crate', 0.5 kg): it is in
model_states and link_states where the physics has it, set_model_state moves it, and
apply_body_wrench moves it by F t^2/(2m) (lifted 10 m, so that only gravity, vertical, acts
besides the force). Sim time; wall time only bounds the waits."""
import rospy
import rostest
from gazebo_msgs.msg import LinkStates, ModelState, ModelStates
from geometry_msgs.msg import Point, Pose, Quaternion, Twist
from tianracer_sim.sim_time import Stream, wait_for

from gazebo_case import GazeboCase, no_stamp

BOX, MASS = 'crate', 0.5


class GazeboFreeBody(GazeboCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node('test_gazebo_free_body')
        cls.models = Stream('/gazebo/model_states', ModelStates, stamp=no_stamp, keep=500)
        cls.links = Stream('/gazebo/link_states', LinkStates, stamp=no_stamp, keep=500)
        cls.connect(['pause_physics', 'unpause_physics', 'reset_world', 'get_model_state',
                     'set_model_state', 'get_model_properties', 'get_world_properties',
                     'apply_body_wrench'])
        cls.models.wait_count(1)
        cls.links.wait_count(1)

    def test_a_the_box_is_a_moving_model(self):
        props = self.get_model_properties(BOX)
        self.assertTrue(props.success, props.status_message)
        self.assertFalse(props.is_static)
        self.assertIn(BOX, self.get_world_properties().model_names)
        # Lift it 0.5 m: it falls back; model_states and link_states follow it.
        self.paused()
        s = self.get_model_state(BOX, '')
        r = self.set_model_state(ModelState(BOX, Pose(Point(0.8, 0.0, 0.65),
                                                      Quaternion(0, 0, 0, 1)), Twist(), ''))
        self.assertTrue(r.success, r.status_message)
        n_models, n_links = self.models.count(), self.links.count()
        self.unpause_physics()
        # ModelStates and LinkStates carry no stamp: a step of the fall shows in both with the
        # box at vz < -1.5 m/s (-g t: from 0.153 s on, until it lands at 0.32 s) and the same
        # height. (Any such step: the sim's queues are 1 deep and may drop one of them.)
        def falling_pair():
            links = [l.pose[l.name.index(BOX + '::link')].position.z
                     for l in self.links.messages(n_links)]
            for m in self.models.messages(n_models):
                i = m.name.index(BOX)
                if m.twist[i].linear.z < -1.5:
                    z = m.pose[i].position.z
                    match = [zl for zl in links if abs(zl - z) < 1e-9]
                    if match:
                        return z, match[0], m.twist[i].linear.z
            return None

        z_model, z_link, vz = wait_for(falling_pair, 'a step of the fall in model_states and '
                                       'link_states')
        text = 'falling: z %.4f (link %.4f), vz %.3f' % (z_model, z_link, vz)
        self.assertLess(z_model, 0.65 - 0.1, text)  # falling: 0.196 m after 0.2 s
        self.assertGreater(z_model, s.pose.position.z, text)
        self.assertAlmostEqual(z_model, z_link, places=9, msg=text)
        self.assertLess(vz, -1.5, text)
        self.wait_sim(1.0)
        self.reset_world()
        self.wait_sim(0.3)

    def test_b_apply_body_wrench_moves_the_box(self):
        F, T = 1.0, 0.4
        self.paused()
        # 10 m up: still falling after 1.3 s, however late after 0.5 s the pause comes.
        r = self.set_model_state(ModelState(BOX, Pose(Point(0.8, 0.0, 10.0),
                                                      Quaternion(0, 0, 0, 1)), Twist(), ''))
        self.assertTrue(r.success, r.status_message)
        x0 = self.get_model_state(BOX, '').pose.position.x
        t0 = self.get_world_properties().sim_time
        self.push_x(BOX + '::link', F, T)
        s = self.get_model_state(BOX, '')
        t = self.get_world_properties().sim_time - t0
        self.unpause_physics()
        expected = F * T * T / (2 * MASS) + F * T / MASS * (t - T)
        dx = s.pose.position.x - x0
        text = ('F %.1f N for %.2f s on the %.1f kg box, %.3f s in the air: moved %.5f m, '
                'F T^2/(2m) + (F T/m)(t - T) = %.5f m (%+.2f %%); vx %.4f m/s (F T/m = %.4f)'
                % (F, T, MASS, t, dx, expected, 100.0 * (dx / expected - 1.0),
                   s.twist.linear.x, F * T / MASS))
        print('FIGURE apply_body_wrench on a free box: ' + text)
        self.assertGreater(s.pose.position.z, 1.0, text)  # still in the air
        self.assertLess(abs(dx / expected - 1.0), 0.03, text)
        self.assertAlmostEqual(s.twist.linear.x, F * T / MASS, delta=0.01 * F * T / MASS)
        self.wait_sim(1.0)
        self.reset_world()
        self.wait_sim(0.3)
        back = self.get_model_state(BOX, '').pose.position
        self.assertAlmostEqual(back.x, 0.8, delta=0.01)


if __name__ == '__main__':
    rostest.rosrun('tianracer_sim', 'gazebo_free_body', GazeboFreeBody)
