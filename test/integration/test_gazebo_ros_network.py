#!/usr/bin/env python3
"""rostest: the /gazebo topics and services are exactly gazebo_ros's (noetic-devel's
gazebo_ros_api_plugin.cpp with its physics dynamic_reconfigure server), or with
~enable_ros_network false (--disabled) none but the node's loggers. Our own check, written from
gazebo_ros's published interface; gazebo_properties.test runs the enabled case. With --ns NS
(empty_world.launch included in a <group ns="NS">, as steer_bot_gazebo's launch file does) they
are all under /NS/gazebo/, the node's private namespace where gazebo_ros_api_plugin advertises
them, and none under /gazebo/."""
import subprocess
import sys
import time
import unittest

import rospy
import rostest
from rosgraph_msgs.msg import Clock

# name -> type, as gazebo_ros offers them.
GAZEBO_TOPICS = {
    '/clock': 'rosgraph_msgs/Clock',
    '/gazebo/set_model_state': 'gazebo_msgs/ModelState',
    '/gazebo/set_link_state': 'gazebo_msgs/LinkState',
    '/gazebo/link_states': 'gazebo_msgs/LinkStates',
    '/gazebo/model_states': 'gazebo_msgs/ModelStates',
    '/gazebo/parameter_descriptions': 'dynamic_reconfigure/ConfigDescription',
    '/gazebo/parameter_updates': 'dynamic_reconfigure/Config',
}
GAZEBO_SERVICES = {
    '/gazebo/apply_body_wrench': 'gazebo_msgs/ApplyBodyWrench',
    '/gazebo/apply_joint_effort': 'gazebo_msgs/ApplyJointEffort',
    '/gazebo/clear_body_wrenches': 'gazebo_msgs/BodyRequest',
    '/gazebo/clear_joint_forces': 'gazebo_msgs/JointRequest',
    '/gazebo/delete_light': 'gazebo_msgs/DeleteLight',
    '/gazebo/delete_model': 'gazebo_msgs/DeleteModel',
    '/gazebo/get_joint_properties': 'gazebo_msgs/GetJointProperties',
    '/gazebo/get_light_properties': 'gazebo_msgs/GetLightProperties',
    '/gazebo/get_link_properties': 'gazebo_msgs/GetLinkProperties',
    '/gazebo/get_link_state': 'gazebo_msgs/GetLinkState',
    '/gazebo/get_model_properties': 'gazebo_msgs/GetModelProperties',
    '/gazebo/get_model_state': 'gazebo_msgs/GetModelState',
    '/gazebo/get_physics_properties': 'gazebo_msgs/GetPhysicsProperties',
    '/gazebo/get_world_properties': 'gazebo_msgs/GetWorldProperties',
    '/gazebo/pause_physics': 'std_srvs/Empty',
    '/gazebo/reset_simulation': 'std_srvs/Empty',
    '/gazebo/reset_world': 'std_srvs/Empty',
    '/gazebo/set_joint_properties': 'gazebo_msgs/SetJointProperties',
    '/gazebo/set_light_properties': 'gazebo_msgs/SetLightProperties',
    '/gazebo/set_link_properties': 'gazebo_msgs/SetLinkProperties',
    '/gazebo/set_link_state': 'gazebo_msgs/SetLinkState',
    '/gazebo/set_model_configuration': 'gazebo_msgs/SetModelConfiguration',
    '/gazebo/set_model_state': 'gazebo_msgs/SetModelState',
    '/gazebo/set_parameters': 'dynamic_reconfigure/Reconfigure',
    '/gazebo/set_physics_properties': 'gazebo_msgs/SetPhysicsProperties',
    '/gazebo/spawn_sdf_model': 'gazebo_msgs/SpawnModel',
    '/gazebo/spawn_urdf_model': 'gazebo_msgs/SpawnModel',
    '/gazebo/unpause_physics': 'std_srvs/Empty',
}
LOGGERS = {'/gazebo/get_loggers': 'roscpp/GetLoggers',
           '/gazebo/set_logger_level': 'roscpp/SetLoggerLevel'}


def run(cmd):
    return subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                          check=True).stdout


def topics():
    """Every topic with a publisher or subscriber but this test's own, with its type."""
    out = {}
    for line in run(['rostopic', 'list', '-v']).splitlines():
        line = line.strip()
        if line.startswith('* '):
            name, kind = line[2:].split(' ')[:2]
            out[name] = kind.strip('[]')
    out.pop('/rosout', None)  # every node's log
    return out


def services():
    me = rospy.get_name()
    names = [s for s in run(['rosservice', 'list']).split() if not s.startswith(me + '/')]
    return {s: run(['rosservice', 'type', s]).strip() for s in names}


def namespaced(names, ns):
    return {(ns + k if k.startswith('/gazebo/') else k): v for k, v in names.items()}


def expected(disabled, ns=''):
    if disabled:
        return {'/clock': 'rosgraph_msgs/Clock'}, namespaced(LOGGERS, ns)
    return (namespaced(GAZEBO_TOPICS, ns),
            namespaced(dict(GAZEBO_SERVICES, **LOGGERS), ns))


def check_lists(test, disabled, ns=''):
    want_topics, want_services = expected(disabled, ns)
    # A node still starting (spawn_model, the launch's other nodes) comes and goes: the lists
    # are compared once /gazebo offers all it will and the lists stay the same.
    deadline = time.time() + 60.0
    while True:
        got_topics, got_services = topics(), services()
        got_services = {k: v for k, v in got_services.items() if not k.startswith('/spawn_')}
        if (got_topics, got_services) == (want_topics, want_services) or time.time() > deadline:
            break
        time.sleep(1.0)
    test.assertEqual(got_topics, want_topics)
    test.assertEqual(got_services, want_services)


class NetworkTest(unittest.TestCase):
    def test_lists(self):
        rospy.wait_for_message('/clock', Clock, timeout=60.0)
        ns = sys.argv[sys.argv.index('--ns') + 1] if '--ns' in sys.argv else ''
        check_lists(self, '--disabled' in sys.argv, ns)


if __name__ == '__main__':
    rospy.init_node('test_gazebo_ros_network')
    rostest.rosrun('tianracer_tests', 'gazebo_ros_network', NetworkTest)
