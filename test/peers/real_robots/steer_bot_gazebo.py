#!/usr/bin/env python3
"""An Ackermann robot driven through ackermann_steering_controller/AckermannSteeringController as
its users start it in Gazebo, on the simulator (run by hand, not in CI; docs/real_robots.md):

  test/peers/real_robots/steer_bot_gazebo.py --upstream GITDIR [--ref master] [--ws /tmp/steer_ws]
        [--sim-setup .build/devel/setup.bash] [--wall 300]

GITDIR: a bare git dir of srmainwaring/steer_bot (its README: "Simulate a simple Ackermann
steering vehicle in Gazebo using ros_control, the ackermann_steering_controller and
steer_bot_hardware_gazebo"; its robot is CIR-KIT steer_drive_ros' steerbot). Exports
steer_bot_description, steer_bot_control and steer_bot_gazebo into WS/src, runs
`roslaunch steer_bot_gazebo steer_bot_sim.launch` unchanged, then a rospy client: the controllers
running, then cmd_vel on /steer_bot/ackermann_steering_controller/cmd_vel (linear.x the speed,
angular.z the steering angle, as the controller reads it), and the turning radius the ground
truth shows against the one the steering gives (wheel_separation_h / tan(angle)). Ends with one
PASS/FAIL line."""
import math
import os
import sys

import common

NS = '/steer_bot'
ROBOT = 'steer_bot'
SPEED, STEER, SECONDS = 0.5, 0.3, 6.0


def yaw_of(q):
    return math.atan2(2.0 * (q.w * q.z + q.x * q.y), 1.0 - 2.0 * (q.y * q.y + q.z * q.z))


def client():
    import rospy
    from controller_manager_msgs.srv import ListControllers
    from gazebo_msgs.msg import ModelStates
    from geometry_msgs.msg import Twist
    from nav_msgs.msg import Odometry
    from rosgraph_msgs.msg import Clock
    from sensor_msgs.msg import JointState
    from tianracer_sim.sim_time import Stream, clock_stamp, drive_twist, sim_sleep, wait_for

    rospy.init_node('steer_bot_check')
    clock = Stream('/clock', Clock, stamp=clock_stamp, keep=1)
    odom = Stream(NS + '/ackermann_steering_controller/odom', Odometry, keep=5000)
    joints = Stream(NS + '/joint_states', JointState, keep=10)
    poses = []

    def on_states(m):
        if ROBOT in m.name:
            p = m.pose[m.name.index(ROBOT)]
            poses.append((rospy.get_time(), p.position.x, p.position.y, yaw_of(p.orientation)))
    states_topic = None
    wait_for(clock.latest, '/clock', 120)
    for t, _ in rospy.get_published_topics():
        if t.endswith('/model_states'):
            states_topic = t
    states_topic = states_topic or '/gazebo/model_states'
    rospy.Subscriber(states_topic, ModelStates, on_states, queue_size=100)
    srv = NS + '/controller_manager/list_controllers'
    rospy.wait_for_service(srv, 120)
    lc = rospy.ServiceProxy(srv, ListControllers)
    want = ('joint_state_publisher', 'ackermann_steering_controller')
    wait_for(lambda: len([c for c in lc().controller if c.name in want and c.state == 'running'])
             == 2, 'both controllers running', 120)
    for c in lc().controller:
        print('controller %s (%s): %s; claims %s' % (
            c.name, c.type, c.state,
            '; '.join('%s %s' % (r.hardware_interface.split('::')[-1], ' '.join(r.resources))
                      for r in c.claimed_resources)))
    sim_sleep(3.0)  # spawned 1 m up: let it land
    wait_for(lambda: poses and odom.latest(), states_topic + ' and odom', 60)
    pub = rospy.Publisher(NS + '/ackermann_steering_controller/cmd_vel', Twist, queue_size=1)
    t0, x0, y0, a0 = poses[-1]
    o0 = odom.latest().pose.pose
    drive_twist(pub, SECONDS, SPEED, STEER)
    t1, x1, y1, a1 = poses[-1]
    o1 = odom.latest().pose.pose
    js = joints.latest()
    print('joint_states after the drive: ' + ', '.join(
        '%s %.3f rad %.3f rad/s' % (n, p, v) for n, p, v in zip(js.name, js.position, js.velocity)))
    dist = math.hypot(x1 - x0, y1 - y0)
    dyaw = math.atan2(math.sin(a1 - a0), math.cos(a1 - a0))
    odyaw = yaw_of(o1.orientation) - yaw_of(o0.orientation)
    odist = math.hypot(o1.position.x - o0.position.x, o1.position.y - o0.position.y)
    h = rospy.get_param(NS + '/ackermann_steering_controller/wheel_separation_h')
    expected = h / math.tan(STEER)
    # radius of the arc through the start and end poses: chord / (2 sin(dyaw / 2))
    radius = dist / (2.0 * math.sin(abs(dyaw) / 2.0)) if abs(dyaw) > 1e-3 else float('inf')
    print('ground truth over %.1f s: %.3f m, yaw %+.3f rad, turning radius %.3f m' % (
        SECONDS, dist, dyaw, radius))
    print('odometry: %.3f m, yaw %+.3f rad' % (odist, odyaw))
    print('the steering gives: radius %.3f m (wheel_separation_h %.3f / tan(%.2f)), %.3f m of travel'
          % (expected, h, STEER, SPEED * SECONDS))
    ok = dist > 0.5 * SPEED * SECONDS and abs(radius - expected) <= 0.15 * expected
    return 0 if ok else 1


def main():
    ap = common.arg_parser(__doc__, '/tmp/steer_ws')
    ap.add_argument('--upstream', help='bare git dir of srmainwaring/steer_bot')
    ap.add_argument('--ref', default='master')
    a = ap.parse_args()
    if a.client:
        common.wait_for_sim_time_param()
        return client()
    if not a.upstream:
        ap.error('--upstream GITDIR is required')
    src = common.fresh_workspace(a.ws)
    dirs = ['steer_bot_description', 'steer_bot_control', 'steer_bot_gazebo']
    commit = common.export(a.upstream, a.ref, dirs, src)
    print('srmainwaring/steer_bot %s (%s): %s' % (a.ref, commit, ' '.join(dirs)))
    port = common.free_port()
    env = common.sim_env(a.sim_setup, src, port)
    log = os.path.join(a.ws, 'logs', 'launch.log')
    ok = common.launch_and_run(env, port, ['steer_bot_gazebo', 'steer_bot_sim.launch'], log,
                               os.path.abspath(__file__), [], a.wall)
    return common.verdict(ok, 'steer_bot_gazebo steer_bot_sim.launch: the Ackermann '
                          'steering controller drives steer_bot on the radius its steering gives')


if __name__ == '__main__':
    sys.exit(main())
