#!/usr/bin/env python3
"""rostest: the gym env and the ROS node are the same simulation.

The env runs first, here, without ROS: the tianracer_gym model (84 x 84 camera), the racetrack,
seed 7, 120 control periods of 0.01 s with controller commands (both steering hinges, both rear
wheels) that change every period. Then the node (launched paused, lockstep) gets the same
commands: the test answers the ground-truth message of each period with the period's commands
on the four command topics, which are the lockstep's reply topics, so the simulator applies them
from the next step exactly as the env does. Every /scan, /gym/camera/image_raw and ground-truth
message must be byte for byte the env's value sampled at its stamp (the env reports when each
of its observations was sampled).

The commands go straight to the controllers: through the cmd_vel node the comparison would
depend on whether that node reads the driver's Ackermann message before the /clock of its tick,
which two ROS connections do not order. The env's Ackermann action runs the cmd_vel node's own
class (tianracer_control::CmdVelProcessor) onto the same controllers."""
import math
import struct
import threading
import time
import unittest

import numpy as np
import rospy
import rostest
from nav_msgs.msg import Odometry
from sensor_msgs.msg import Image, LaserScan
from std_msgs.msg import Float64
from std_srvs.srv import Empty

from tianracer_gym import TianracerEnv, packages

STEPS = 120
PERIOD = 0.01
WAIT = 300.0
WHEEL_RADIUS = 0.032


def command(k, specs):
    """The controller commands of period k, one per entry of the env's `commands`."""
    out = []
    for c in specs:
        if 'position' in c['type']:  # a steering hinge (rad)
            v = 0.35 * math.sin(k / 9.0)
        else:  # a rear wheel (rad/s): 1.0 +- 0.8 m/s
            v = (1.0 + 0.8 * math.sin(k / 17.0)) / WHEEL_RADIUS
        out.append(min(max(v, c['lower']), c['upper']))
    return np.array(out, np.float64)


def gym_run(model):
    env = TianracerEnv(model=model, control_config=packages.default_control_config(),
                       world='racetrack', observe=('scan', 'odom', 'camera_small'),
                       action='commands', control_period=PERIOD, random_start=False,
                       max_episode_time=1e9, terminate_on_collision=False)
    specs = env.sim.commands
    obs, _ = env.reset(seed=7)
    scans, images, odoms = {}, {}, {}

    def keep(obs, k):
        stamps = env.sim.stamps()
        scans[round(stamps['scan'] * 1e6)] = obs['scan'].tobytes()
        images[round(stamps['camera_small'] * 1e6)] = obs['camera_small'].tobytes()
        odoms[k] = obs['odom'].tobytes()

    keep(obs, 0)
    for k in range(STEPS):
        obs = env.step(command(k, specs))[0]
        keep(obs, k + 1)
    return specs, scans, images, odoms


class RosEquality(unittest.TestCase):
    def test_the_node_publishes_what_the_env_observes(self):
        model = rospy.get_param('~model')
        specs, scans, images, odoms = gym_run(model)
        robot = rospy.get_param('~robot_name', 'tianracer')

        lock = threading.Lock()
        got = {'scan': {}, 'image': {}, 'odom': {}}
        pubs = [rospy.Publisher('/%s/%s/command' % (robot, c['controller']), Float64,
                                queue_size=100, tcp_nodelay=True) for c in specs]

        def on_odom(m):
            k = round(m.header.stamp.to_sec() / PERIOD)
            p, q = m.pose.pose.position, m.pose.pose.orientation
            v, w = m.twist.twist.linear, m.twist.twist.angular
            value = np.array([p.x, p.y, p.z, q.x, q.y, q.z, q.w, v.x, v.y, v.z, w.x, w.y, w.z])
            with lock:
                got['odom'][k] = value.tobytes()
            for pub, x in zip(pubs, command(k, specs)):
                pub.publish(Float64(float(x)))

        def on_scan(m):
            with lock:
                got['scan'][round(m.header.stamp.to_sec() * 1e6)] = np.array(m.ranges, np.float32).tobytes()

        def on_image(m):
            with lock:
                got['image'][round(m.header.stamp.to_sec() * 1e6)] = bytes(m.data)

        subs = [rospy.Subscriber('/tianracer/ground_truth/odom', Odometry, on_odom, queue_size=1000,
                                 tcp_nodelay=True),
                rospy.Subscriber('/scan', LaserScan, on_scan, queue_size=1000, tcp_nodelay=True),
                rospy.Subscriber('/gym/camera/image_raw', Image, on_image, queue_size=1000,
                                 tcp_nodelay=True, buff_size=1 << 22)]
        rospy.wait_for_service('/gazebo/unpause_physics', WAIT)
        deadline = time.time() + WAIT
        while time.time() < deadline and not (all(p.get_num_connections() >= 1 for p in pubs) and
                                              all(s.get_num_connections() >= 1 for s in subs)):
            time.sleep(0.05)
        rospy.ServiceProxy('/gazebo/unpause_physics', Empty)()
        while time.time() < deadline:
            with lock:
                if max(got['odom'], default=-1) >= STEPS + 1:
                    break
            time.sleep(0.05)
        rospy.ServiceProxy('/gazebo/pause_physics', Empty)()
        time.sleep(1.0)  # the last messages in flight

        with lock:
            ros = {k: dict(v) for k, v in got.items()}
        self.assertTrue(all(k in ros['odom'] for k in range(STEPS + 1)),
                        'ground truth of steps %s missing' % sorted(set(range(STEPS + 1)) - set(ros['odom']))[:10])
        for k in range(STEPS + 1):
            self.assertEqual(ros['odom'][k], odoms[k], 'odometry differs at step %d (t = %.2f s):\n'
                             'node %s\nenv  %s' % (k, k * PERIOD, np.frombuffer(ros['odom'][k]).tolist(),
                                                   np.frombuffer(odoms[k]).tolist()))
        end = round(STEPS * PERIOD * 1e6)
        for name, env_values in (('scan', scans), ('image', images)):
            stamps = [s for s in ros[name] if s <= end]
            self.assertEqual(sorted(stamps), sorted(env_values), name + ': the same sample times')
            for s in stamps:
                self.assertEqual(ros[name][s], env_values[s], '%s differs at t = %.3f s' % (name, s / 1e6))
        self.assertGreaterEqual(len(scans), 40)   # 40 Hz over 1.2 s, and t = 0
        self.assertGreaterEqual(len(images), 30)  # 30 Hz
        # The car did drive: the commands reached both.
        x0 = struct.unpack('<d', odoms[0][:8])[0]
        x1 = struct.unpack('<d', odoms[STEPS][:8])[0]
        self.assertGreater(x1 - x0, 0.5)


if __name__ == '__main__':
    rospy.init_node('test_ros_equality')
    rostest.rosrun('tianracer_gym', 'ros_equality', RosEquality)
