"""A ROS master of one's own, for whatever starts a graph apart from the user's (the rostests
that read a node's start-up output, tianracer_bringup's RosSession and through it the demo, the
benchmarks and the batch runner): a free port, the environment that points at it, and rosmaster
started on it and waited for."""
import os
import signal
import socket
import subprocess
import time
import xmlrpc.client

CALLER = '/private_master'
START_TIMEOUT = 120.0  # s of wall time; roslaunch gives a master 10 s, which a loaded machine can miss


def free_port():
    with socket.socket(socket.AF_INET, socket.SOCK_STREAM) as s:
        s.bind(('localhost', 0))
        return s.getsockname()[1]


def ros_env(port, log_dir=None):
    """os.environ for a graph whose master is on `port` of this host (ROS's Python first, and
    ROS_HOSTNAME=localhost so that nodes reach each other where the host name does not
    resolve)."""
    env = dict(os.environ)
    env['PATH'] = '/usr/bin:' + env.get('PATH', '')
    env['ROS_MASTER_URI'] = 'http://localhost:%d' % port
    env['ROS_HOSTNAME'] = 'localhost'
    env.pop('ROS_IP', None)
    if log_dir:
        env['ROS_LOG_DIR'] = log_dir
    return env


def master_cmd(port):
    return ['rosmaster', '--core', '-p', str(port), '-w', '3']


def spawn_master(port, env, stdout=subprocess.DEVNULL, **popen):
    """rosmaster on `port` in a session of its own (what roslaunch starts after it does not
    reach it); its output to `stdout`. Returns the Popen; wait_for_master() waits for it."""
    return subprocess.Popen(master_cmd(port), env=env,
                            stdout=stdout, stderr=subprocess.STDOUT, stdin=subprocess.DEVNULL,
                            start_new_session=True, **popen)


def master_pid(port):
    """The pid of the master on `port`; OSError while nothing answers there."""
    return xmlrpc.client.ServerProxy('http://localhost:%d' % port).getPid(CALLER)[2]


def wait_for_master(proc, port, timeout=START_TIMEOUT, what=''):
    """The master's pid once the master `proc` started on `port` answers. RuntimeError when
    `proc` exits first or nothing answers after `timeout` s (`what`: where to look)."""
    deadline = time.time() + timeout
    while True:
        try:
            return master_pid(port)
        except OSError:
            if proc.poll() is not None or time.time() > deadline:
                raise RuntimeError('rosmaster on port %d did not start%s' % (port, what))
            time.sleep(0.05)


def start_master(port, env, stdout=subprocess.DEVNULL, timeout=START_TIMEOUT, what='', **popen):
    """spawn_master() and wait_for_master(): (Popen, pid) of a master that answers."""
    proc = spawn_master(port, env, stdout, **popen)
    try:
        return proc, wait_for_master(proc, port, timeout, what)
    except RuntimeError:
        stop_master(proc)
        raise


def stop_master(proc, timeout=5.0):
    """SIGINT to the master's session, SIGKILL after `timeout` s."""
    for sig in (signal.SIGINT, signal.SIGKILL):
        try:
            os.killpg(proc.pid, sig)
        except (ProcessLookupError, PermissionError):
            pass
        try:
            proc.wait(timeout)
            return
        except subprocess.TimeoutExpired:
            pass
    proc.wait()
