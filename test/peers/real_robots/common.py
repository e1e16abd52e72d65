"""What the real-robot scripts share (run by hand, not in CI; see docs/real_robots.md): export an
upstream repository's packages from its bare git dir into a throwaway workspace, start the
robot's own launch file against the simulator with roslaunch, run a rospy client in the same
environment, and pick out of the launch's log what the simulator says it does not simulate."""
import argparse
import os
import re
import shutil
import signal
import subprocess
import sys
import time

ROOT = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', '..', '..'))
sys.path.insert(0, os.path.join(ROOT, 'tianracer_sim', 'python'))
from tianracer_sim.master import free_port  # noqa: E402,F401 (the scripts' common.free_port)
# The lines of a launch's log that say what is not simulated, left out or failed.
NOTE = re.compile(r'not simulated|not supported|ignored|left out|not read|with differences|'
                  r'falling back|warning:|cannot launch node|ERROR|Error|no gazebo_ros plugin|'
                  r'not one of', re.I)


def git(gitdir, *args):
    return subprocess.check_output(['git', '--git-dir=' + gitdir] + list(args)).decode().strip()


def export(gitdir, ref, dirs, src):
    """git archive of `dirs` at `ref` into `src`; returns the commit exported."""
    os.makedirs(src, exist_ok=True)
    archive = subprocess.Popen(['git', '--git-dir=' + gitdir, 'archive', ref] + list(dirs),
                               stdout=subprocess.PIPE)
    subprocess.check_call(['tar', '-x', '-C', src], stdin=archive.stdout)
    if archive.wait() != 0:
        raise SystemExit('git archive %s %s failed' % (ref, ' '.join(dirs)))
    return git(gitdir, 'rev-parse', ref + '^{commit}')


def fresh_workspace(ws):
    shutil.rmtree(ws, ignore_errors=True)
    os.makedirs(os.path.join(ws, 'src'))
    os.makedirs(os.path.join(ws, 'logs'))
    return os.path.join(ws, 'src')


def arg_parser(doc, ws_default):
    """The options every robot script takes: --ws (the workspace it builds the robot's packages
    in), --sim-setup (our workspace's setup.bash), --wall (the client's wall-clock cap, s) and
    the hidden --client (the script run again as the launch's ROS client)."""
    ap = argparse.ArgumentParser(description=doc.split('\n')[0])
    ap.add_argument('--ws', default=ws_default)
    ap.add_argument('--sim-setup', default=os.path.join(ROOT, '.build/devel/setup.bash'))
    ap.add_argument('--wall', type=float, default=300.0, help='wall-clock cap of the client, s')
    ap.add_argument('--client', action='store_true', help=argparse.SUPPRESS)
    return ap


def sim_env(setup, src, port):
    """The environment of `source setup` with the workspace's packages on ROS_PACKAGE_PATH and a
    master of our own on `port`."""
    setup = os.path.abspath(setup)
    if not os.path.exists(setup):
        raise SystemExit('%s: no such file (build first, or give --sim-setup)' % setup)
    out = subprocess.check_output(['bash', '-c', 'source "%s" && env -0' % setup])
    env = dict(kv.split('=', 1) for kv in out.decode().split('\0') if '=' in kv)
    env['ROS_PACKAGE_PATH'] = src + ':' + env.get('ROS_PACKAGE_PATH', '')
    env['ROS_MASTER_URI'] = 'http://localhost:%d' % port
    env['ROS_HOSTNAME'] = 'localhost'
    env['ROS_LOG_DIR'] = os.path.join(os.path.dirname(src), 'logs', 'ros')
    env['PATH'] = '/usr/bin:' + env.get('PATH', '')
    return env


def start_launch(env, port, args, log_path):
    """roslaunch -p port ARGS, its own process group, stdout and stderr to log_path."""
    log = open(log_path, 'w')
    print('$ roslaunch ' + ' '.join(args), flush=True)
    return subprocess.Popen(['roslaunch', '-p', str(port)] + list(args), env=env, stdout=log,
                            stderr=subprocess.STDOUT, start_new_session=True)


def stop_launch(proc, wall=20.0):
    if proc.poll() is None:
        os.killpg(proc.pid, signal.SIGINT)
        end = time.time() + wall
        while proc.poll() is None and time.time() < end:
            time.sleep(0.2)
        if proc.poll() is None:
            os.killpg(proc.pid, signal.SIGKILL)
            proc.wait()


def run_client(env, script, args, wall):
    """Runs `script --client ARGS` (the robot's rospy client) in `env`; returns its exit status."""
    python = '/usr/bin/python3' if os.path.exists('/usr/bin/python3') else sys.executable
    cmd = [python, script, '--client'] + list(args)  # Debian's python: rospy, actionlib
    try:
        return subprocess.call(cmd, env=env, timeout=wall)
    except subprocess.TimeoutExpired:
        print('client: no answer within %.0f s of wall time' % wall)
        return 1


def launch_and_run(env, port, launch_args, log_path, client_script, client_args, wall):
    """Starts the launch file, runs the script's client against it, stops the launch and prints
    its notes. True when the client passed and the launch was still running at its end."""
    proc = start_launch(env, port, launch_args, log_path)
    try:
        rc = run_client(env, client_script, client_args, wall)
        alive = proc.poll() is None
    finally:
        stop_launch(proc)
    print_notes(log_path)
    return rc == 0 and alive


def print_notes(log_path):
    """The launch log's lines about what is not simulated, left out or failed, each once."""
    seen = []
    with open(log_path, errors='replace') as f:
        for line in f:
            line = re.sub(r'\x1b\[[0-9;]*m', '', line.rstrip())
            if NOTE.search(line) and line not in seen:
                seen.append(line)
    print('--- what the launch printed about what is not simulated or failed (%s):' % log_path)
    for line in seen:
        print('  ' + line)
    return seen


def wait_for_sim_time_param(wall=120.0):
    """In the client, before rospy.init_node: waits for the master and the launch's /use_sim_time
    (rospy reads it once, at init_node; without it the client would run on wall time)."""
    import rosgraph
    master = rosgraph.Master('/real_robot_client')
    end = time.time() + wall
    while time.time() < end:
        try:
            if master.hasParam('/use_sim_time'):
                return master.getParam('/use_sim_time')
        except Exception:  # the master is not up yet
            pass
        time.sleep(0.1)
    raise SystemExit('no /use_sim_time on the master after %.0f s of wall time' % wall)


def verdict(ok, what):
    print(('PASS' if ok else 'FAIL') + ': ' + what, flush=True)
    return 0 if ok else 1
