#!/usr/bin/env python3
"""rostest: the sim node's Gazebo interface with gazebo_msgs types, in walled_room.

- /gazebo/model_states and /gazebo/link_states list every model and body, at 50 Hz sim time;
  an odometry relay built on link_states agrees with the ground truth within 1 mm;
- set_model_state teleports the car and its lidar sees the room from the new pose within one
  scan period; reference frames (world, a model, model::link) are honoured;
- apply_body_wrench on the car, lifted off the ground, moves its centre of mass by F t^2/(2m);
- bad input (NaN, zero quaternion, unknown names and frames, static models) is answered with
  success false and a message, and the sim runs on with everything it publishes finite.
Sim time throughout; wall time only bounds the waits.
"""
import math
import xml.etree.ElementTree as ET

import numpy as np
import rospy
import rostest
from gazebo_msgs.msg import LinkStates, ModelState, ModelStates, LinkState
from geometry_msgs.msg import Point, Pose, Quaternion, Twist, Wrench, Vector3
from nav_msgs.msg import Odometry
from sensor_msgs.msg import LaserScan
from std_msgs.msg import Float64
from tianracer_sim.rotation import quaternion_from_rpy
from tianracer_sim.sim_time import Stream, messages_sent, wait_connected, wait_for

from gazebo_case import GazeboCase, moved_in_plane, no_stamp

MODEL = 'tianracer'
NS = '/tianracer'
WORLD_MODELS = ['ground_plane', 'walls', 'box_front', 'box_sw', 'box_nw', 'box_rotated',
                'cylinder']


def yaw_quaternion(yaw):
    return Quaternion(*quaternion_from_rpy(0.0, 0.0, yaw))


def rot(q):
    x, y, z, w = q.x, q.y, q.z, q.w
    return np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
                     [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
                     [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]])


def pos(p):
    return np.array([p.position.x, p.position.y, p.position.z])


def finite_pose_twist(poses, twists):
    vals = []
    for p in poses:
        vals += [p.position.x, p.position.y, p.position.z, p.orientation.x, p.orientation.y,
                 p.orientation.z, p.orientation.w]
    for t in twists:
        vals += [t.linear.x, t.linear.y, t.linear.z, t.angular.x, t.angular.y, t.angular.z]
    return all(math.isfinite(v) for v in vals)


def urdf_inertials(urdf_xml):
    """link -> (mass, centre of mass in the link frame)."""
    out = {}
    for link in ET.fromstring(urdf_xml).findall('link'):
        inertial = link.find('inertial')
        if inertial is None:
            continue
        mass = float(inertial.find('mass').get('value'))
        origin = inertial.find('origin')
        xyz = [0.0, 0.0, 0.0] if origin is None else [float(v) for v in
                                                      origin.get('xyz', '0 0 0').split()]
        out[link.get('name')] = (mass, np.array(xyz))
    return out


SIM = '/tianracer_sim'


class GazeboInterface(GazeboCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node('test_gazebo_interface')
        cls.model_states = Stream('/gazebo/model_states', ModelStates, stamp=no_stamp,
                                  keep=1000)
        cls.link_states = Stream('/gazebo/link_states', LinkStates, stamp=no_stamp, keep=1000)
        cls.relay = Stream('/relay/odom', Odometry, keep=1000)
        cls.truth = Stream(NS + '/ground_truth/odom', Odometry, keep=1000)
        cls.scans = Stream('/scan', LaserScan, keep=1000)
        cls.connect(['pause_physics', 'unpause_physics', 'reset_world', 'get_model_state',
                     'set_model_state', 'get_link_state', 'set_link_state',
                     'get_model_properties', 'get_world_properties', 'apply_body_wrench',
                     'clear_body_wrenches'])
        cls.set_model_state_pub = rospy.Publisher('/gazebo/set_model_state', ModelState,
                                                  queue_size=10)
        cls.urdf = rospy.get_param('/robot_description')
        for stream in (cls.relay, cls.truth, cls.scans, cls.link_states, cls.model_states):
            stream.wait_count(1)

    @staticmethod
    def latest(stream):
        return stream.latest()

    def model_state(self, name=MODEL, frame=''):
        r = self.get_model_state(name, frame)
        self.assertTrue(r.success, r.status_message)
        return r

    def assert_all_finite(self, what):
        """Everything the sim published over the last second is finite; the clock advances."""
        t0 = rospy.get_time()
        self.wait_sim(0.5)
        self.assertGreater(rospy.get_time(), t0, what + ': the sim stopped')
        ms, ls = self.model_states.messages()[-25:], self.link_states.messages()[-25:]
        gt = self.truth.messages()[-25:]
        for m in ms:
            self.assertTrue(finite_pose_twist(m.pose, m.twist), what + ': model_states')
        for m in ls:
            self.assertTrue(finite_pose_twist(m.pose, m.twist), what + ': link_states')
        for m in gt:
            self.assertTrue(finite_pose_twist([m.pose.pose], [m.twist.twist]),
                            what + ': ground truth')

    def teleport(self, x, y, yaw, z=None, frame=''):
        if z is None:
            z = self.model_state().pose.position.z
        r = self.set_model_state(ModelState(MODEL, Pose(Point(x, y, z), yaw_quaternion(yaw)),
                                            Twist(), frame))
        self.assertTrue(r.success, r.status_message)

    # ---------------------------------------------------------------------------------------------
    def test_a_states_list_every_model_and_body(self):
        # What the sim published in 2 s of sim time (ModelStates and LinkStates carry no
        # stamps): its count of messages sent to us between two pauses.
        with self.paused() as p0:
            sent0 = [messages_sent(SIM, s.topic) for s in (self.model_states, self.link_states)]
        self.wait_sim(2.0)
        with self.paused() as p1:
            sent1 = [messages_sent(SIM, s.topic) for s in (self.model_states, self.link_states)]
            n_ms, n_ls = [b - a for a, b in zip(sent0, sent1)]
            m, l = self.model_states.latest(), self.link_states.latest()
        span = p1.t - p0.t
        self.assertEqual(m.name, WORLD_MODELS + [MODEL])
        self.assertEqual(len(m.pose), len(m.name))
        self.assertEqual(len(m.twist), len(m.name))
        self.assertIn('walls::link', l.name)
        self.assertIn('ground_plane::link', l.name)
        robot = [n for n in l.name if n.startswith(MODEL + '::')]
        # Gazebo lumps links joined by fixed joints: base_link, 2 hinges, 4 wheels.
        self.assertEqual(robot[0], MODEL + '::base_link')
        self.assertEqual(len(robot), 7, robot)
        for n in ('left_rear_wheel', 'right_front_wheel', 'left_steering_hinge'):
            self.assertIn(MODEL + '::' + n, robot)
        box = m.pose[m.name.index('box_front')]
        self.assertAlmostEqual(box.position.x, 2.0)
        rospy.loginfo('model_states: %d messages in %.3f s of sim time', n_ms, span)
        self.assertAlmostEqual(n_ms / span, 50.0, delta=3.0)
        self.assertAlmostEqual(n_ls / span, 50.0, delta=3.0)

    def test_b_odometry_relay_agrees_with_ground_truth(self):
        """The car drives a curve on its wheel commands; at five moments the relay's latest
        odometry is compared with the ground truth of the same step (the sim publishes
        link_states and ground truth on the same 50 Hz steps)."""
        wheels = [rospy.Publisher(NS + '/%s_rear_wheel_velocity_controller/command' % s,
                                  Float64, queue_size=1, latch=True) for s in ('left', 'right')]
        steer = [rospy.Publisher(NS + '/%s_steering_hinge_position_controller/command' % s,
                                 Float64, queue_size=1, latch=True) for s in ('left', 'right')]
        for p in wheels + steer:
            wait_connected(p)
        for p in wheels:
            p.publish(Float64(15.0))
        for p in steer:
            p.publish(Float64(0.3))
        worst_p, worst_v, speeds = 0.0, 0.0, []
        for _ in range(5):
            n_relay = self.relay.count()
            self.wait_sim(0.7)
            # The relay stamps its answer with its own clock, and link_states carry no stamp:
            # the step is the ground truth's nearest in position among those around the stamp
            # (steps are 10 mm apart at this speed; a quarter lap around it). No "last message"
            # to wait for: the sim's link_states queue is 1 deep and may drop one.
            relay = self.relay.wait_count(n_relay + 1)
            t_r = relay.header.stamp.to_sec()
            self.truth.first_stamped(t_r + 0.5)
            truth = min(self.truth.between(t_r - 2.0, t_r + 0.5),
                        key=lambda m: np.linalg.norm(pos(m.pose.pose) - pos(relay.pose.pose)))
            dp = np.linalg.norm(pos(relay.pose.pose) - pos(truth.pose.pose))
            q1, q2 = relay.pose.pose.orientation, truth.pose.pose.orientation
            dq = 1.0 - abs(q1.x * q2.x + q1.y * q2.y + q1.z * q2.z + q1.w * q2.w)
            v1, v2 = relay.twist.twist, truth.twist.twist
            dv = max(abs(v1.linear.x - v2.linear.x), abs(v1.linear.y - v2.linear.y),
                     abs(v1.angular.z - v2.angular.z))
            worst_p, worst_v = max(worst_p, dp), max(worst_v, dv)
            speeds.append(math.hypot(v2.linear.x, v2.linear.y))
            self.assertLess(dq, 1e-9)
        for p in wheels + steer:
            p.publish(Float64(0.0))
        rospy.loginfo('relay vs ground truth: worst position %.3g m, twist %.3g at speeds %s',
                      worst_p, worst_v, speeds)
        print('FIGURE relay vs ground truth: worst position difference %.3g m, twist %.3g '
              '(m/s, rad/s), car speeds %s m/s' % (worst_p, worst_v,
                                                  ['%.3f' % s for s in speeds]))
        self.assertGreater(min(speeds), 0.2)  # it was moving
        self.assertLess(worst_p, 0.001)
        self.assertLess(worst_v, 0.001)
        self.wait_sim(1.0)
        self.reset_world()
        self.wait_sim(0.5)

    def test_c_set_model_state_teleports_and_the_lidar_follows(self):
        """From the spawn facing +x (the centre beam on box_front) to (0, 0.5) facing +y: the
        first scan after the teleport, within one scan period (25 ms), reads the north wall
        (inner face y = 2.0) at 2.0 - y_lidar."""
        self.reset_world()
        self.wait_sim(0.5)
        with self.paused() as paused:
            self.teleport(0.0, 0.5, math.pi / 2)
            t0 = paused.t
            lidar = self.get_link_state('tianracer::lidar', '')
            self.assertTrue(lidar.success, lidar.status_message)
            n = self.scans.count()
        first = self.scans.first(lambda t, m: t > t0 + 1e-6, 'a scan after the teleport', n)[2]
        centre = first.ranges[len(first.ranges) // 2]
        y_lidar = lidar.link_state.pose.position.y
        expected = 2.0 - y_lidar
        text = ('first scan %.3f s after the teleport: centre range %.4f m, expected %.4f m '
                '(lidar at y %.4f)' % (first.header.stamp.to_sec() - t0, centre, expected,
                                       y_lidar))
        print('FIGURE teleport: ' + text)
        self.assertLessEqual(first.header.stamp.to_sec() - t0, 0.025 + 1e-6, text)
        self.assertAlmostEqual(centre, expected, delta=0.05, msg=text)  # lidar noise 0.01
        self.reset_world()
        self.wait_sim(0.5)

    def test_d_reference_frames(self):
        self.reset_world()
        self.wait_sim(0.5)
        # In box_front's frame (box at (2, 0), yaw 0): 1 m behind it is world x = 1.
        z = self.model_state().pose.position.z
        self.paused()
        r = self.set_model_state(ModelState(MODEL, Pose(Point(-1.0, 0.3, z - 0.25),
                                                        yaw_quaternion(0.5)), Twist(),
                                            'box_front'))
        self.assertTrue(r.success, r.status_message)
        s = self.model_state()
        self.assertAlmostEqual(s.pose.position.x, 1.0, places=6)
        self.assertAlmostEqual(s.pose.position.y, 0.3, places=6)
        self.assertAlmostEqual(s.pose.position.z, z, places=6)
        # Relative to box_front again, and to the car's own base_link (identity).
        rel = self.model_state(MODEL, 'box_front')
        self.assertAlmostEqual(rel.pose.position.x, -1.0, places=6)
        self.assertEqual(rel.header.frame_id, 'box_front')
        own = self.model_state(MODEL, MODEL + '::base_link')
        self.assertAlmostEqual(own.pose.position.x, 0.0, places=9)
        self.assertAlmostEqual(abs(own.pose.orientation.w), 1.0, places=9)
        # get_link_state of base_link in the world is the model state.
        ls = self.get_link_state(MODEL + '::base_link', 'world')
        self.assertTrue(ls.success, ls.status_message)
        self.assertAlmostEqual(ls.link_state.pose.position.x, s.pose.position.x, places=9)
        # set_link_state on a wheel moves the whole car rigidly.
        wheel = self.get_link_state(MODEL + '::left_rear_wheel', '').link_state
        target = Pose(Point(wheel.pose.position.x + 0.5, wheel.pose.position.y,
                            wheel.pose.position.z), wheel.pose.orientation)
        r = self.set_link_state(LinkState(MODEL + '::left_rear_wheel', target, Twist(), ''))
        self.assertTrue(r.success, r.status_message)
        moved = self.model_state()
        self.assertAlmostEqual(moved.pose.position.x, s.pose.position.x + 0.5, places=6)
        # The topic does what the service does.
        wait_connected(self.set_model_state_pub)
        self.set_model_state_pub.publish(ModelState(MODEL, Pose(Point(-1.0, -0.5, z),
                                                                 yaw_quaternion(0.0)),
                                                    Twist(), ''))
        wait_for(lambda: abs(self.model_state().pose.position.x + 1.0) <= 1e-6,
                 'the car where the set_model_state topic put it', poll=0.05)
        self.assertAlmostEqual(self.model_state().pose.position.x, -1.0, places=6)
        self.unpause_physics()
        props = self.get_model_properties(MODEL)
        self.assertTrue(props.success)
        self.assertEqual(props.canonical_body_name, 'base_link')
        self.assertIn('left_rear_wheel_joint', props.joint_names)
        self.assertFalse(props.is_static)
        world = self.get_world_properties()
        self.assertEqual(world.model_names, WORLD_MODELS + [MODEL])
        self.assertGreater(world.sim_time, 0.0)
        box = self.get_model_properties('box_front')
        self.assertTrue(box.success and box.is_static)
        self.reset_world()
        self.wait_sim(0.5)

    def test_e_bad_input(self):
        before = self.model_state()
        nan = float('nan')
        cases = [
            (ModelState(MODEL, Pose(Point(nan, 0, 0.1), Quaternion(0, 0, 0, 1)), Twist(), ''),
             "set_model_state: pose of 'tianracer' is not finite"),
            (ModelState(MODEL, Pose(Point(0, 0, 0.1), Quaternion(0, 0, 0, 0)), Twist(), ''),
             'zero quaternion'),
            (ModelState(MODEL, Pose(Point(0, 0, 0.1), Quaternion(0, 0, 0, 1)),
                        Twist(Vector3(0, 0, 0), Vector3(0, 0, float('inf'))), ''),
             "twist of 'tianracer' is not finite"),
            (ModelState(MODEL, Pose(Point(0, 0, 0.1), Quaternion(0, 0, 0, 1)), Twist(),
                        'no_such_frame'), "reference_frame: no model named 'no_such_frame'"),
            (ModelState(MODEL, Pose(Point(0, 0, 0.1), Quaternion(0, 0, 0, 1)), Twist(),
                        'tianracer::no_link'), "reference_frame: model 'tianracer' has no link"),
            (ModelState('no_such_model', Pose(Point(0, 0, 0.1), Quaternion(0, 0, 0, 1)), Twist(),
                        ''), "no model named 'no_such_model'"),
            (ModelState('box_front', Pose(Point(0, 0, 0.1), Quaternion(0, 0, 0, 1)), Twist(), ''),
             'static'),
        ]
        for state, text in cases:
            r = self.set_model_state(state)
            self.assertFalse(r.success, state)
            self.assertIn(text, r.status_message)
        # The same through the topic: logged, nothing changes.
        self.set_model_state_pub.publish(cases[0][0])
        r = self.get_model_state(MODEL, 'nowhere')
        self.assertFalse(r.success)
        self.assertIn("reference_frame: no model named 'nowhere'", r.status_message)
        r = self.get_link_state('base_link', '')
        self.assertFalse(r.success)
        self.assertIn('model::link', r.status_message)
        r = self.apply_body_wrench(MODEL + '::base_link', '', Point(),
                                   Wrench(Vector3(nan, 0, 0), Vector3()), rospy.Time(0),
                                   rospy.Duration(1.0))
        self.assertFalse(r.success)
        self.assertIn('not finite', r.status_message)
        r = self.apply_body_wrench(MODEL + '::base_link', '', Point(),
                                   Wrench(Vector3(1e30, 0, 0), Vector3()), rospy.Time(0),
                                   rospy.Duration(1.0))
        self.assertFalse(r.success)
        self.assertIn('out of range', r.status_message)
        r = self.apply_body_wrench('box_front::link', '', Point(),
                                   Wrench(Vector3(1, 0, 0), Vector3()), rospy.Time(0),
                                   rospy.Duration(1.0))
        self.assertFalse(r.success)
        self.assertIn('static', r.status_message)
        self.wait_sim(0.5)
        self.assertLess(moved_in_plane(before, self.model_state()), 0.005)
        self.assert_all_finite('bad input')

    def test_f_apply_body_wrench_moves_the_centre_of_mass(self):
        """The car lifted 10 m (no contact: only gravity and the wrench act on it): a horizontal
        force F on base_link for T = 0.4 s moves the whole car's centre of mass by
        F T^2 / (2 m) + (F T / m)(t - T) along x, whatever the car's joints and rotation do."""
        inertials = urdf_inertials(self.urdf)
        mass = sum(m for m, _ in inertials.values())
        self.reset_world()
        self.wait_sim(0.5)
        self.paused()
        # 10 m up: still falling after 1.3 s, however late after 0.5 s the pause comes.
        self.teleport(0.0, 0.0, 0.0, z=10.0)

        def com():
            total = np.zeros(3)
            for link, (m, c) in inertials.items():
                s = self.get_link_state(MODEL + '::' + link, '')
                self.assertTrue(s.success, s.status_message)
                p = s.link_state.pose
                total += m * (pos(p) + rot(p.orientation).dot(c))
            return total / mass

        c0 = com()
        t0 = self.get_world_properties().sim_time
        F, T = 2.0, 0.4
        self.push_x(MODEL + '::base_link', F, T)
        c1 = com()
        t1 = self.get_world_properties().sim_time
        self.unpause_physics()
        t = t1 - t0
        expected = F * T * T / (2 * mass) + F * T / mass * (t - T)
        dx = c1[0] - c0[0]
        text = ('F %.1f N for %.2f s on a %.4f kg car, %.3f s in the air: centre of mass moved '
                '%.5f m along x, F T^2/(2m) + (F T/m)(t - T) = %.5f m (%+.2f %%); fell %.3f m'
                % (F, T, mass, t, dx, expected, 100.0 * (dx / expected - 1.0), c0[2] - c1[2]))
        print('FIGURE apply_body_wrench: ' + text)
        self.assertGreater(t, T)
        self.assertLess(c0[2] - c1[2], 9.8, text)  # still in the air
        self.assertLess(abs(dx / expected - 1.0), 0.03, text)
        # A wrench until cleared, then clear_body_wrenches: the speed stops growing.
        r = self.apply_body_wrench(MODEL + '::base_link', '', Point(),
                                   Wrench(Vector3(0, 0, 5.0), Vector3()), rospy.Time(0),
                                   rospy.Duration(-1))
        self.assertTrue(r.success, r.status_message)
        self.clear_body_wrenches(MODEL + '::base_link')
        self.reset_world()
        self.wait_sim(1.0)
        self.assert_all_finite('after the wrench')


if __name__ == '__main__':
    rostest.rosrun('tianracer_sim', 'gazebo_interface', GazeboInterface)
