#!/usr/bin/env python3
"""Clearpath's Jackal as its users start it in Gazebo, on the simulator (run by hand, not in CI;
docs/real_robots.md):

  test/peers/real_robots/jackal_gazebo.py [--mirror /work/.mirror] [--ws /tmp/jackal_ws]
        [--sim-setup .build/devel/setup.bash] [--launch jackal_world.launch] [--wall 300]

Bare git dirs, each overridable (--jackal GITDIR ...), by default under MIRROR/<owner>+<name>/repo:
jackal/jackal (noetic-devel: jackal_description, jackal_control), jackal/jackal_simulator
(melodic-devel, its newest ROS 1 branch: jackal_gazebo), the description packages that
jackal_description's accessories.urdf.xacro includes unconditionally (uos/sick_tim noetic,
clearpathrobotics/LMS1xx noetic-devel, ros-drivers/pointgrey_camera_driver noetic-devel,
ros-drivers/flir_camera_driver noetic-devel: their package.xml, urdf/ and meshes/ only, no
driver), velodyne_description (LCAS/velodyne_simulator master, a fork of the original, which is
not to be had here), and the world's models from osrf/gazebo_models (the models Gazebo would
fetch from its model database) on GAZEBO_MODEL_PATH.

Runs `roslaunch jackal_gazebo jackal_world.launch gui:=false world_name:=worlds/empty.world` (the
launch file unchanged; its own world argument, --world: the race world has a barrier 0.5 m ahead),
then a rospy client:
both controllers running, then Twist commands on /jackal_velocity_controller/cmd_vel (the topic
twist_mux would forward /cmd_vel to; twist_mux is not in Debian): straight, on the spot, on an arc; prints
the diff drive's odometry and the ground truth (/gazebo/model_states) side by side. Ends with one
PASS/FAIL line."""
import math
import os
import re
import sys

import common

ROBOT = 'jackal'
# (repository, ref, directories, prefix for a package at the repository's root)
SOURCES = {
    'jackal': ('jackal+jackal', 'noetic-devel', ['jackal_description', 'jackal_control'], None),
    'jackal_simulator': ('jackal+jackal_simulator', 'melodic-devel', ['jackal_gazebo'], None),
    'sick_tim': ('uos+sick_tim', 'noetic', ['package.xml', 'urdf', 'meshes'], 'sick_tim'),
    'lms1xx': ('clearpathrobotics+LMS1xx', 'noetic-devel', ['package.xml', 'urdf', 'meshes'], 'lms1xx'),
    'pointgrey': ('ros-drivers+pointgrey_camera_driver', 'noetic-devel',
                  ['pointgrey_camera_description'], None),
    'flir': ('ros-drivers+flir_camera_driver', 'noetic-devel', ['flir_camera_description'], None),
    'velodyne': ('LCAS+velodyne_simulator', 'master', ['velodyne_description'], None),
}
# jackal_race.world spawns Jackal at the origin facing +x in a corridor of jersey barriers that
# runs at +45 degrees (the world's <state> poses): a barrier is 0.5 m ahead, so the drive runs in
# the empty world, through the launch file's own world_name argument (--world; '' keeps the race
# world). Straight, on the spot, an arc, stop: (seconds of sim time, v m/s, w rad/s)
LEGS = [(4.0, 0.5, 0.0), (6.0, 0.0, 0.5), (4.0, 0.5, 0.5), (1.0, 0.0, 0.0)]
# Agreement asked of the odometry: a straight leg within 5 % of the distance and 0.05 rad; a turn
# within 20 % of the ground truth's yaw (Jackal is skid steered: its YAML's
# wheel_separation_multiplier 1.5 is Clearpath's estimate of the scrub, not a kinematic fact).


def yaw_of(q):
    return math.atan2(2.0 * (q.w * q.z + q.x * q.y), 1.0 - 2.0 * (q.y * q.y + q.z * q.z))


def relative(p0, y0, p, y):
    """Pose (x, y, yaw) of p/y in the frame of p0/y0 (planar)."""
    dx, dy = p.x - p0.x, p.y - p0.y
    c, s = math.cos(-y0), math.sin(-y0)
    return (c * dx - s * dy, s * dx + c * dy, math.atan2(math.sin(y - y0), math.cos(y - y0)))


def client():
    import rospy
    from controller_manager_msgs.srv import ListControllers
    from gazebo_msgs.msg import ModelStates
    from geometry_msgs.msg import Twist
    from nav_msgs.msg import Odometry
    from rosgraph_msgs.msg import Clock
    from tianracer_sim.sim_time import Stream, clock_stamp, drive_twist, sim_sleep, wait_for

    rospy.init_node('jackal_gazebo_check')
    clock = Stream('/clock', Clock, stamp=clock_stamp, keep=1)
    odom = Stream('/jackal_velocity_controller/odom', Odometry, keep=5000)
    truth = {}

    def on_states(m):
        if ROBOT in m.name:
            truth['pose'] = m.pose[m.name.index(ROBOT)]
            truth['t'] = rospy.get_time()
    rospy.Subscriber('/gazebo/model_states', ModelStates, on_states, queue_size=1)
    wait_for(clock.latest, '/clock', 120)
    rospy.wait_for_service('/controller_manager/list_controllers', 120)
    lc = rospy.ServiceProxy('/controller_manager/list_controllers', ListControllers)
    want = ('jackal_joint_publisher', 'jackal_velocity_controller')
    wait_for(lambda: all(c.state == 'running' for c in lc().controller if c.name in want) and
             len([c for c in lc().controller if c.name in want]) == 2, 'both controllers running',
             120)
    for c in lc().controller:
        print('controller %s (%s): %s' % (c.name, c.type, c.state))
    sim_sleep(3.0)  # spawned 1 m up: let it land and settle
    wait_for(lambda: odom.latest() and 'pose' in truth, 'odom and model_states', 60)
    pub = rospy.Publisher('/jackal_velocity_controller/cmd_vel', Twist, queue_size=1)

    def snapshot():
        o = odom.latest().pose.pose
        g = truth['pose']
        return o.position, yaw_of(o.orientation), g.position, yaw_of(g.orientation)

    ok = True
    o0, oy0, g0, gy0 = snapshot()
    print('start: odom (%.3f, %.3f, yaw %.3f), ground truth (%.3f, %.3f, %.3f, yaw %.3f)' % (
        o0.x, o0.y, oy0, g0.x, g0.y, g0.z, gy0))
    for seconds, v, w in LEGS:
        a = snapshot()
        drive_twist(pub, seconds, v, w)
        b = snapshot()
        od = relative(a[0], a[1], b[0], b[1])
        gd = relative(a[2], a[3], b[2], b[3])
        dist = math.hypot(gd[0], gd[1])
        err = math.hypot(od[0] - gd[0], od[1] - gd[1])
        print('leg %.1f s v %.2f w %.2f: odometry dx %.3f dy %.3f dyaw %.3f | ground truth dx %.3f '
              'dy %.3f dyaw %.3f | position difference %.3f m (%.1f %% of %.3f m), yaw difference '
              '%.3f rad' % (seconds, v, w, od[0], od[1], od[2], gd[0], gd[1], gd[2], err,
                            100.0 * err / dist if dist > 1e-6 else 0.0, dist, od[2] - gd[2]))
        if v > 0 and w == 0:
            good = dist > 0.8 * v * seconds and err <= 0.05 * dist and abs(od[2] - gd[2]) <= 0.05
        elif w != 0:
            good = abs(gd[2]) > 0.5 * abs(w) * seconds and abs(od[2] - gd[2]) <= 0.2 * abs(gd[2])
            if v > 0:
                good = good and dist > 0.8 * v * seconds and err <= 0.1 * dist
        else:
            good = dist < 0.05
        print('  -> %s' % ('agrees' if good else 'DOES NOT AGREE'))
        ok = ok and good
    tw = odom.latest().twist.twist
    print('odom twist after stopping: %.3f m/s %.3f rad/s' % (tw.linear.x, tw.angular.z))
    oN, oyN, gN, gyN = snapshot()
    od = relative(o0, oy0, oN, oyN)
    gd = relative(g0, gy0, gN, gyN)
    print('total: odometry (%.3f, %.3f, yaw %.3f), ground truth (%.3f, %.3f, yaw %.3f)' % (
        od + gd))
    return 0 if ok else 1


def main():
    ap = common.arg_parser(__doc__, '/tmp/jackal_ws')
    ap.add_argument('--mirror', default='/work/.mirror')
    for key in SOURCES:
        ap.add_argument('--' + key.replace('_', '-'), dest=key, help='bare git dir of ' + SOURCES[key][0])
    ap.add_argument('--gazebo-models', help='bare git dir of osrf/gazebo_models')
    ap.add_argument('--launch', default='jackal_world.launch')
    ap.add_argument('--world', default='worlds/empty.world',
                    help="the launch's world_name argument ('': the launch's own default)")
    a = ap.parse_args()
    if a.client:
        common.wait_for_sim_time_param()
        return client()
    src = common.fresh_workspace(a.ws)
    for key, (repo, ref, dirs, prefix) in SOURCES.items():
        gitdir = getattr(a, key) or os.path.join(a.mirror, repo, 'repo')
        dest = os.path.join(src, prefix) if prefix else src
        commit = common.export(gitdir, ref, dirs, dest)
        print('%s %s (%s): %s' % (repo.replace('+', '/'), ref, commit, ' '.join(dirs)))
    # The world's model:// URIs: the models Gazebo would download from its database.
    world = open(os.path.join(src, 'jackal_gazebo', 'worlds', 'jackal_race.world')).read()
    models = sorted(set(re.findall(r'model://([A-Za-z0-9_]+)', world)))
    gm = a.gazebo_models or os.path.join(a.mirror, 'osrf+gazebo_models', 'repo')
    models_dir = os.path.join(a.ws, 'models')
    commit = common.export(gm, 'HEAD', models, models_dir)
    print('osrf/gazebo_models (%s): %s -> GAZEBO_MODEL_PATH' % (commit, ' '.join(models)))
    port = common.free_port()
    env = common.sim_env(a.sim_setup, src, port)
    env['GAZEBO_MODEL_PATH'] = models_dir
    log = os.path.join(a.ws, 'logs', 'launch.log')
    args = ['jackal_gazebo', a.launch, 'gui:=false']
    if a.world:
        args.append('world_name:=' + a.world)
    ok = common.launch_and_run(env, port, args, log, os.path.abspath(__file__), [], a.wall)
    return common.verdict(ok, 'jackal_gazebo %s %s: the diff drive moves Jackal and its '
                          'odometry agrees with the ground truth' % (a.launch, a.world))


if __name__ == '__main__':
    sys.exit(main())
