#!/usr/bin/env python3
"""A Universal Robots arm as its users start it in Gazebo, on the simulator (run by hand, not in CI;
docs/real_robots.md):

  test/peers/real_robots/ur_gazebo.py --upstream GITDIR [--ref noetic-devel] [--model ur5e]
        [--ws /tmp/ur_ws] [--sim-setup .build/devel/setup.bash] [--wall 300]

GITDIR: a bare git dir of ros-industrial/universal_robot. Exports ur_description and ur_gazebo at
REF into WS/src (put on ROS_PACKAGE_PATH: launch, xacro, yaml and meshes only), runs
`roslaunch ur_gazebo <model>_bringup.launch gui:=false` unchanged, then a rospy client: the
controllers the launch spawned (list_controllers), a two-point goal on
/eff_joint_traj_controller/follow_joint_trajectory that must SUCCEED, and /joint_states within
the YAML's goal tolerances of the last point once the goal succeeded (sim time). Prints what the
launch said it does not simulate and ends with one PASS/FAIL line."""
import os
import sys

import common

CONTROLLER = '/eff_joint_traj_controller'
JOINTS = ['shoulder_pan_joint', 'shoulder_lift_joint', 'elbow_joint', 'wrist_1_joint',
          'wrist_2_joint', 'wrist_3_joint']
# Two points (s from start, positions): from the spawn pose (all joints 0) up to a pose the
# ur_gazebo wiki calls "home" (-pi/2 on shoulder lift), then on to a bent pose.
POINTS = [(3.0, [0.3, -0.8, 0.5, -0.4, 0.3, 0.3]),
          (6.0, [0.6, -1.5, 1.2, -1.0, 0.6, 0.6])]


def client(model):
    import actionlib
    import rospy
    from actionlib_msgs.msg import GoalStatus
    from control_msgs.msg import (FollowJointTrajectoryAction, FollowJointTrajectoryGoal,
                                  JointTrajectoryControllerState)
    from controller_manager_msgs.srv import ListControllers
    from rosgraph_msgs.msg import Clock
    from sensor_msgs.msg import JointState
    from trajectory_msgs.msg import JointTrajectoryPoint
    from tianracer_sim.sim_time import Stream, clock_stamp, sim_sleep, wait_for

    common.wait_for_sim_time_param()
    rospy.init_node('ur_gazebo_check')
    clock = Stream('/clock', Clock, stamp=clock_stamp, keep=1)
    states = Stream('/joint_states', JointState, keep=2000)
    ctrl = Stream(CONTROLLER + '/state', JointTrajectoryControllerState, keep=5000)
    wait_for(clock.latest, '/clock', 120)
    rospy.wait_for_service('/controller_manager/list_controllers', 120)
    lc = rospy.ServiceProxy('/controller_manager/list_controllers', ListControllers)

    def controllers():
        return {c.name: c for c in lc().controller}

    wait_for(lambda: controllers().get('eff_joint_traj_controller') and
             controllers()['eff_joint_traj_controller'].state == 'running',
             'eff_joint_traj_controller running', 120)
    sim_sleep(0.5)
    cs = controllers()
    for name in sorted(cs):
        print('controller %s (%s): %s' % (name, cs[name].type, cs[name].state))
    ok = (cs.get('joint_state_controller') is not None and
          cs['joint_state_controller'].state == 'running' and
          cs.get('joint_group_eff_controller') is not None and
          cs['joint_group_eff_controller'].state in ('initialized', 'stopped'))

    tol = rospy.get_param(CONTROLLER + '/constraints')
    goal_tol = [tol[j]['goal'] for j in JOINTS]
    ac = actionlib.SimpleActionClient(CONTROLLER + '/follow_joint_trajectory',
                                      FollowJointTrajectoryAction)
    wait_for(lambda: ac.wait_for_server(rospy.Duration(0.1)), 'the action server', 120)

    def positions():
        m = states.latest()
        return [m.position[m.name.index(j)] for j in JOINTS], m

    # The arm hangs on its joints with no torque from spawn until the controller starts (as with
    # gazebo_ros_control): it falls, then the controller holds it. A user sends goals once it is
    # at rest: all joints below the YAML's stopped_velocity_tolerance.
    rest = tol.get('stopped_velocity_tolerance', 0.05)
    first = states.messages()[0]
    print('first /joint_states (sim %.3f s): velocities %s' % (
        first.header.stamp.to_sec(), ' '.join('%.2f' % v for v in first.velocity)))
    try:
        wait_for(lambda: all(abs(v) < rest for v in states.latest().velocity), 'the arm at rest',
                 120)
    except AssertionError as e:
        m, c = states.latest(), ctrl.latest()
        print('%s\n  /joint_states at sim %.3f s: positions %s velocities %s\n  controller desired '
              '%s' % (e, m.header.stamp.to_sec(), ' '.join('%.3f' % p for p in m.position),
                      ' '.join('%.2f' % v for v in m.velocity),
                      ' '.join('%.3f' % p for p in c.desired.positions)))
        return 1
    hold = ctrl.latest()
    print('at rest (sim %.3f s): controller desired %s actual %s' % (
        hold.header.stamp.to_sec(), ' '.join('%.3f' % p for p in hold.desired.positions),
        ' '.join('%.3f' % p for p in hold.actual.positions)))
    start, _ = positions()
    print('start (sim %.3f s): %s' % (rospy.get_time(), ' '.join('%.3f' % p for p in start)))
    goal = FollowJointTrajectoryGoal()
    goal.trajectory.joint_names = JOINTS
    for t, q in POINTS:
        p = JointTrajectoryPoint()
        p.positions, p.velocities = q, [0.0] * len(q)
        p.time_from_start = rospy.Duration(t)
        goal.trajectory.points.append(p)
    t0 = rospy.get_time()
    ac.send_goal(goal)
    wait_for(lambda: ac.get_state() not in (GoalStatus.PENDING, GoalStatus.ACTIVE),
             'the goal to finish', 300)
    t1 = rospy.get_time()
    result = ac.get_result()
    state = ac.get_state()
    print('goal: %s after %.3f s of sim time, error_code %d %r' % (
        GoalStatus.to_string(state), t1 - t0, result.error_code if result else -99,
        result.error_string if result else ''))
    ok = ok and state == GoalStatus.SUCCEEDED and result.error_code == 0
    worst = [0.0] * len(JOINTS)
    for m in ctrl.between(t0, t1):
        worst = [max(w, abs(e)) for w, e in zip(worst, m.error.positions)]
    print('largest path error (controller state, %d messages): %s' % (
        len(ctrl.between(t0, t1)), ' '.join('%s %.4f' % (j, w) for j, w in zip(JOINTS, worst))))
    if state != GoalStatus.SUCCEEDED:
        for m in ctrl.between(t0 - 0.02, t1 + 0.01):
            print('  state %.3f desired %s actual %s' % (
                m.header.stamp.to_sec(), ' '.join('%.3f' % p for p in m.desired.positions),
                ' '.join('%.3f' % p for p in m.actual.positions)))
    states.first_stamped(t1)
    q, m = positions()
    final = POINTS[-1][1]
    print('joint_states at sim %.3f s:' % m.header.stamp.to_sec())
    for j, a, b, g in zip(JOINTS, q, final, goal_tol):
        print('  %-20s %+.4f goal %+.4f error %+.4f (tolerance %.2f)' % (j, a, b, a - b, g))
        ok = ok and abs(a - b) <= g
    return 0 if ok else 1


def main():
    ap = common.arg_parser(__doc__, '/tmp/ur_ws')
    ap.add_argument('--upstream', help='bare git dir of ros-industrial/universal_robot')
    ap.add_argument('--ref', default='noetic-devel')
    ap.add_argument('--model', default='ur5e')
    a = ap.parse_args()
    if a.client:
        return client(a.model)
    if not a.upstream:
        ap.error('--upstream GITDIR is required')
    src = common.fresh_workspace(a.ws)
    commit = common.export(a.upstream, a.ref, ['ur_description', 'ur_gazebo'], src)
    print('universal_robot %s (%s): ur_description, ur_gazebo -> %s' % (a.ref, commit, src))
    port = common.free_port()
    env = common.sim_env(a.sim_setup, src, port)
    log = os.path.join(a.ws, 'logs', 'launch.log')
    ok = common.launch_and_run(env, port, ['ur_gazebo', a.model + '_bringup.launch', 'gui:=false'],
                               log, os.path.abspath(__file__), ['--model', a.model], a.wall)
    return common.verdict(ok, 'ur_gazebo %s_bringup.launch: follow_joint_trajectory '
                          'goal succeeded and /joint_states within the goal tolerances' % a.model)


if __name__ == '__main__':
    sys.exit(main())
