#!/usr/bin/env python3
"""rostest: the car with a bumper on base_link, driven at 1 m/s (wheel commands) into
walled_room's box_front (its face at x = 1.8 m), publishes gazebo_msgs/ContactsState on
/tianracer/bumper: empty before the car reaches the box, then states naming the box, with
contact points at the box's face, normals pushing the car back and a force that stops it.
The robot's own /tianracer/contacts (tianracer_sim/Contact), subscribed, reports the box too:
contacts are tracked while someone reads them. Everything in sim time. A bumper whose frameName
is no link, and a contact sensor without the plugin, are left out with a message."""
import unittest

import rospy
import rostest
from gazebo_msgs.msg import ContactsState
from std_msgs.msg import Float64
from tianracer_sim.msg import Contact
from tianracer_sim.sim_time import Stream, published_rate

from sim_node_binary import sensor_startup_output

WHEEL_RADIUS = 0.032
COMMANDS = ['/tianracer/left_rear_wheel_velocity_controller/command',
            '/tianracer/right_rear_wheel_velocity_controller/command']


class BumperTest(unittest.TestCase):
    def test_a_car_into_box(self):
        rospy.init_node('test_bumper')
        bumper = Stream('/tianracer/bumper', ContactsState)
        contacts = Stream('/tianracer/contacts', Contact, stamp=lambda m: m.stamp.to_sec())
        pubs = [rospy.Publisher(t, Float64, queue_size=1, latch=True) for t in COMMANDS]
        for p in pubs:
            p.publish(Float64(1.0 / WHEEL_RADIUS))

        def box(m):
            return any(s.collision2_name.startswith('box_front') for s in m.states)

        # The first contact with the box, then 0.5 s of sim time of it.
        _, t_hit, _ = bumper.first(lambda t, m: box(m), 'a contact with box_front')
        bumper.first_stamped(t_hit + 0.5)
        states = bumper.messages()
        hit = [m for m in states if box(m)]
        first = hit[0]
        # Published at the sensor's 50 Hz, empty while nothing touched.
        before = [m for m in states if m.header.stamp < first.header.stamp]
        self.assertGreater(len(before), 20)
        self.assertTrue(all(not m.states for m in before[:10]), 'contacts before the car moved')
        self.assertAlmostEqual(published_rate(states[:50]), 50.0, delta=5.0)
        self.assertEqual(first.header.frame_id, 'world')
        s = [s for s in first.states if s.collision2_name.startswith('box_front')][0]
        self.assertEqual(s.collision1_name, 'tianracer::base_link')
        self.assertEqual(s.collision2_name, 'box_front::link')
        self.assertEqual(len(s.contact_positions), len(s.depths))
        self.assertEqual(len(s.wrenches), len(s.depths))
        for p in s.contact_positions:
            self.assertAlmostEqual(p.x, 1.8, delta=0.02)  # the box's face
        for n in s.contact_normals:
            self.assertLess(n.x, -0.9)  # pushing the car back
        # The car is stopped by the box: over the last 0.5 s the force is backwards.
        later = [m for m in hit if m.header.stamp.to_sec() > t_hit + 0.2]
        forces = [st.total_wrench.force.x for m in later for st in m.states
                  if st.collision2_name.startswith('box_front')]
        self.assertTrue(forces)
        self.assertLess(sum(forces) / len(forces), 0.0)
        # The robot's contacts topic names the box within the bumper's 0.5 s of contact.
        _, t_contact, c = contacts.first(lambda t, m: m.other_model == 'box_front',
                                         'a /tianracer/contacts message about box_front')
        self.assertLess(t_contact, t_hit + 0.5)
        self.assertGreater(t_contact, t_hit - 0.1)
        self.assertAlmostEqual(c.position.x, 1.8, delta=0.05)
        published = dict(rospy.get_published_topics())
        self.assertIn('/tianracer/bumper', published)
        self.assertNotIn('/tianracer/bad_bumper', published)

    def test_b_bad_sensors_messages(self):
        """What the node says about them: the same model in a sim of its own (own master), so
        that its start-up output can be read."""
        out = sensor_startup_output(
            'tianracer_bumper.xacro',
            ["'nowhere'", 'no libgazebo_ros_bumper plugin', "contact sensor 'bumper'"],
            'bumper_bad_input')
        bad = [l for l in out.splitlines() if 'bad_frame_bumper' in l and "'nowhere'" in l
               and 'neither world nor a link' in l and 'left out' in l]
        self.assertTrue(bad, out)
        silent = [l for l in out.splitlines() if "'silent_contact'" in l
                  and 'no libgazebo_ros_bumper plugin' in l]
        self.assertTrue(silent, out)
        self.assertIn("contact sensor 'bumper'", out)  # the good one is set up in the same run


if __name__ == '__main__':
    rostest.rosrun('tianracer_sim', 'bumper', BumperTest)
