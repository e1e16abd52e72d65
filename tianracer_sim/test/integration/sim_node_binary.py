"""Shared by the rostests: where the built tianracer_sim_node is (for tests that start it
themselves, with arguments or an environment a launch file cannot give), and reading its
start-up output. (Waiting on the running sim: tianracer_sim.sim_time.)"""
import os
import signal
import subprocess
import threading
import time

from tianracer_sim.master import free_port, ros_env, start_master, stop_master


TEST_URDF = os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', 'data', 'urdf')


def node_binary():
    for d in os.environ.get('CMAKE_PREFIX_PATH', '').split(':'):
        path = os.path.join(d, 'lib', 'tianracer_sim', 'tianracer_sim_node')
        if os.path.exists(path):
            return path
    raise RuntimeError('tianracer_sim_node not found on CMAKE_PREFIX_PATH')


def startup_output(args, wanted, name, timeout=90.0):
    """The output of tianracer_sim_node started with `args` on a private master (so that its
    start-up messages can be read apart from the rostest's sim): read until every string of
    `wanted` has appeared, or for at most `timeout` s of a loaded machine's wall time, then
    interrupted. The node should be paused (it runs until interrupted)."""
    port = free_port()
    # Line-buffered stdout: INFO lines arrive as they are logged, not when the node exits.
    env = dict(ros_env(port), ROSCONSOLE_STDOUT_LINE_BUFFERED='1')
    master, _ = start_master(port, env)
    try:
        node = subprocess.Popen([node_binary(), '__name:=' + name] + list(args), env=env,
                                stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                                universal_newlines=True)
        lines = []

        def read():
            for line in node.stdout:
                lines.append(line)

        reader = threading.Thread(target=read, daemon=True)
        reader.start()
        end = time.time() + timeout
        while (time.time() < end and node.poll() is None and
               not all(any(w in l for l in list(lines)) for w in wanted)):
            time.sleep(0.2)
        if node.poll() is None:
            node.send_signal(signal.SIGINT)
        node.wait(timeout=20)
        reader.join(timeout=10)
        return ''.join(lines)
    finally:
        stop_master(master)


def sensor_startup_output(xacro, wanted, name):
    """startup_output() of the model test/data/urdf/<xacro>, paused, with the camera, depth
    and ray sensors left out (the other kinds' messages are read)."""
    return startup_output(['_model:=' + os.path.join(TEST_URDF, xacro), '_paused:=true',
                           '_disable_sensors:=camera depth ray'], wanted, name)
