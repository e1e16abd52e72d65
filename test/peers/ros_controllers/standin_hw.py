#!/usr/bin/env python3
"""Stand-in for one of ros_controllers' test hardware nodes (diffbot, skidsteerbot, the steer bots,
rrbot, rrbot_wrapping, simple_bot_hw): starts tianracer_sim_node, under the node name roslaunch gave,
on the test's own /robot_description (on a ground plane, world 'empty') and with the controller YAML
the test's launch file loaded. No controller is started: the test's spawner loads them.

The test robots' URDFs were written for hardware nodes that register their joints' interfaces in C++,
so their transmissions name no <hardwareInterface> and they carry no gazebo_ros_control plugin. The
stand-in gives the simulator a copy of the description (parameter ~standin_robot_description; the
test's /robot_description is left as it is) with, exactly as the upstream node registers them:
  * <hardwareInterface> on each transmission joint that names none (INTERFACES below);
  * a SimpleTransmission for each movable joint the node registers that has no transmission (rrbot);
  * <gazebo><plugin filename="libgazebo_ros_control.so"> with robotNamespace '/' (the upstream node
    runs its ControllerManager on the root node handle);
  * for rrbot and rrbot_wrapping, <gazebo reference="LINK"><turnGravityOff>true</turnGravityOff> on each
    link (WEIGHTLESS below), unless RCP_RRBOT_GRAVITY=on (run.py --rrbot-gravity).
Usage (by roslaunch, through the per-node wrapper the runner writes): standin_hw.py HW_NODE [ros args]
"""
import os
import re
import subprocess
import sys
import time
import xml.etree.ElementTree as ET

import rosgraph

V, P, E = ('hardware_interface/VelocityJointInterface', 'hardware_interface/PositionJointInterface',
           'hardware_interface/EffortJointInterface')


def _rrbot(joint, params):
    # rrbot.cpp registers position and velocity handles and switches between them; a simulator
    # joint has one command interface: the one the loaded controllers' types name.
    types = [v for k, v in params if k.endswith('/type') and isinstance(v, str)]
    return V if any(t.startswith('velocity_controllers/') for t in types) else P


# Hardware node -> (joint name -> interface), from the upstream node's sources.
INTERFACES = {
    'diffbot': lambda j, p: V,        # diff_drive_controller/test/diffbot.h: wheel_<i>_joint, velocity
    'skidsteerbot': lambda j, p: V,   # diffbot.h (6 wheels): velocity
    # ackermann_steering_bot.h: rear wheels (and the virtual rear_wheel_joint) velocity, steers position
    'ackermann_steering_controller_ackermann_steering_bot': lambda j, p: P if 'steer' in j else V,
    # four_wheel_steering.h: *_steering_joint position, wheels velocity
    'four_wheel_steering': lambda j, p: P if 'steering' in j else V,
    'rrbot': _rrbot,
    'rrbot_wrapping': lambda j, p: V,  # rrbot_wrapping.cpp: velocity handles
    'simple_bot_hw': lambda j, p: E,   # effort_controllers/test/simple_bot_hw.cpp: effort
}


# Fixture nodes that integrate their commands without any dynamics (rrbot.cpp, rrbot_wrapping.cpp:
# the state is the command, or the command integrated), so without gravity: their arm, upright
# links of 1 kg on 20 N m joints, is given no weight unless the runner is asked for it
# (run.py --rrbot-gravity: as Gazebo would simulate rrbot.xacro, which falls under the controllers).
WEIGHTLESS = ('rrbot', 'rrbot_wrapping')


def flatten(prefix, value, out):
    if isinstance(value, dict):
        for k, v in value.items():
            flatten(prefix + '/' + k, v, out)
    else:
        out.append((prefix, value))


def augment(urdf, rule, params, weightless=False):
    root = ET.fromstring(urdf)
    notes = []
    movable = [j.get('name') for j in root.findall('joint') if j.get('type') not in ('fixed', None)]
    with_trans = set()
    for t in root.findall('transmission'):
        for j in t.findall('joint'):
            with_trans.add(j.get('name'))
            if j.find('hardwareInterface') is None and (t.find('actuator') is None or
                                                        t.find('actuator').find('hardwareInterface') is None):
                iface = rule(j.get('name'), params)
                ET.SubElement(j, 'hardwareInterface').text = iface
                notes.append('%s: %s' % (j.get('name'), iface))
    for name in movable:
        if name in with_trans:
            continue
        iface = rule(name, params)
        t = ET.SubElement(root, 'transmission', name=name + '_standin_trans')
        ET.SubElement(t, 'type').text = 'transmission_interface/SimpleTransmission'
        ET.SubElement(ET.SubElement(t, 'joint', name=name), 'hardwareInterface').text = iface
        ET.SubElement(t, 'actuator', name=name + '_standin_motor')
        notes.append('%s: %s (added transmission)' % (name, iface))
    # The upstream hardware node runs its ControllerManager in its own (root) namespace: a test
    # URDF's own gazebo_ros_control without robotNamespace (four_wheel_steering.urdf.xacro) would
    # put it under the model's name, as Gazebo does.
    for plugin in root.iter('plugin'):
        if plugin.get('filename') == 'libgazebo_ros_control.so' and plugin.find('robotNamespace') is None:
            ET.SubElement(plugin, 'robotNamespace').text = '/'
            notes.append('its gazebo_ros_control plugin given robotNamespace /')
    if weightless:
        for link in root.findall('link'):
            ET.SubElement(ET.SubElement(root, 'gazebo', reference=link.get('name')), 'turnGravityOff').text = 'true'
        notes.append('gravity off on every link (the upstream node simulates no gravity)')
    if not any(p.get('filename') == 'libgazebo_ros_control.so' for p in root.iter('plugin')):
        plugin = ET.SubElement(ET.SubElement(root, 'gazebo'), 'plugin',
                               name='gazebo_ros_control', filename='libgazebo_ros_control.so')
        ET.SubElement(plugin, 'robotNamespace').text = '/'
        notes.append('gazebo_ros_control plugin, robotNamespace /')
    return ET.tostring(root, encoding='unicode'), notes


def main():
    hw = sys.argv[1]
    ros_args = sys.argv[2:]
    name = next((a.split(':=', 1)[1] for a in ros_args if a.startswith('__name:=')), hw)
    master = rosgraph.Master('/%s_standin' % name)
    deadline = time.time() + 30
    while True:
        try:
            urdf = master.getParam('/robot_description')
            break
        except Exception:
            if time.time() > deadline:
                sys.exit('standin_hw: /robot_description never appeared')
            time.sleep(0.2)
    params = []
    flatten('', master.getParam('/'), params)
    weightless = hw in WEIGHTLESS and os.environ.get('RCP_RRBOT_GRAVITY', 'off') != 'on'
    text, notes = augment(urdf, INTERFACES[hw], params, weightless)
    param = '/%s/standin_robot_description' % name.strip('/')
    master.setParam(param, text)
    print('standin_hw: %s -> tianracer_sim_node on /robot_description + %s' % (hw, '; '.join(notes)),
          flush=True)
    node = subprocess.check_output(['catkin_find', '--first-only', '--libexec', 'tianracer_sim',
                                    'tianracer_sim_node'], text=True).strip()
    private = '/' + name.strip('/') + '/'
    for key, value in (('robot_param', param), ('world', 'empty'), ('controllers', []),
                       ('robot_name', name.strip('/')),
                       ('odom_frame', '')):  # no world -> odom TF: neither Gazebo nor the node has one
        master.setParam(private + key, value)
    os.execv(node, [node] + ros_args)


if __name__ == '__main__':
    main()
