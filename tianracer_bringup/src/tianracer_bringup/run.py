"""One isolated batch run: its own ROS master on a free port, its own ROS_HOME and logs, the
simulator paused until the recorder and the user's driver are connected, then unpaused and run to
the scenario's sim duration; everything stopped afterwards, whatever happened.

A run is a tianracer_bringup.ros_session.RosSession (a private master, roslaunch and the
clients each in a session of its own, SIGINT then SIGKILL), one log per process. roslaunch puts
every node in a new session, so process groups do not reach them all: every process of a run
carries the environment variable TIANRACER_BATCH_RUN=<token>, and after stopping, the process
table is searched for that token; survivors are killed and counted.

The simulator node itself is watched (roslaunch outlives a node that crashed): its death ends the
run as failed, with roslaunch's exit code line. A guard process (`python3 -m tianracer_bringup.run
--guard TOKEN`, in a session of its own) waits on a pipe from the run: if the run's process dies
without saying it is done (a Ray worker killed, its node lost), the guard kills every process
carrying the token, so that a lost run leaves nothing behind on a node that survives it.
"""
import json
import os
import re
import resource
import shlex
import signal
import socket
import subprocess
import sys
import time
import uuid
import xmlrpc.client
from xml.sax.saxutils import quoteattr

from tianracer_bringup.ros_session import (RosSession, _alive, graph_connected, stop_master,
                                           stop_process)
from tianracer_bringup.scenario import lockstep, run_timeout

TOKEN_VAR = 'TIANRACER_BATCH_RUN'
CALLER = '/batch_runner'
LOG_TAIL_LINES = 25


def _fmt(v):
    if isinstance(v, bool):
        return 'true' if v else 'false'
    return str(v)


def sim_launch_xml(cfg):
    """The run's launch file: tianracer.launch, paused, with the scenario's settings; then the
    scenario's parameters, after the include so that they override the launch files' values."""
    s, sp = cfg['sensors'], cfg['spawn']
    args = {'world': cfg['world'], 'x': sp['x'], 'y': sp['y'], 'yaw': sp['yaw'],
            'seed': cfg['seed'], 'real_time_factor': cfg['real_time_factor'], 'paused': True,
            'lidar': s['lidar'], 'camera': s['camera'], 'depth': s['depth'], 'output': 'log'}
    if cfg['model']:
        args['model'] = cfg['model']
    if cfg['control_config']:
        args['control_config'] = cfg['control_config']
    lines = ['<launch>', '  <include file="$(find tianracer_bringup)/launch/tianracer.launch">']
    lines += ['    <arg name="%s" value=%s />' % (k, quoteattr(_fmt(v))) for k, v in args.items()]
    lines.append('  </include>')
    if cfg['model_args']:
        model = cfg['model'] or '$(find tianracer_description)/urdf/tianracer_description.xacro'
        cmd = 'xacro %s %s' % (shlex.quote(model), ' '.join(
            shlex.quote('%s:=%s' % (k, _fmt(v))) for k, v in cfg['model_args'].items()))
        lines.append('  <param name="robot_description" command=%s />' % quoteattr(cmd))
    for name, value in lockstep(cfg).items():
        lines.append('  <param name="/tianracer_sim/lockstep/%s" value=%s />' % (name, quoteattr(_fmt(value))))
    for name, value in cfg['params'].items():
        lines.append('  <param name=%s value=%s />' % (quoteattr(name), quoteattr(_fmt(value))))
    lines.append('</launch>')
    return '\n'.join(lines) + '\n'


def driver_cmd(cfg, port):
    d = cfg['driver']
    if d['launch']:
        return ['roslaunch', '-p', str(port), d['launch']] + \
            ['%s:=%s' % (k, _fmt(v)) for k, v in d['args'].items()]
    return list(d['command']) + ['_%s:=%s' % (k, _fmt(v)) for k, v in d['args'].items()]


_ANSI = re.compile(r'\x1b(\[[0-9;]*[A-Za-z]|\][^\x07]*\x07)')


def _tail(path, n=LOG_TAIL_LINES):
    """The last n lines of a log, without terminal colour and title escapes."""
    try:
        with open(path, errors='replace') as f:
            return ''.join(_ANSI.sub('', line) for line in f.readlines()[-n:])
    except OSError:
        return ''


def processes_with_token(token):
    """pids of live processes whose environment carries the run's token."""
    needle = ('%s=%s' % (TOKEN_VAR, token)).encode()
    out = []
    for entry in os.listdir('/proc'):
        if not entry.isdigit() or int(entry) == os.getpid():
            continue
        try:
            with open('/proc/%s/environ' % entry, 'rb') as f:
                if needle not in f.read().split(b'\0'):
                    continue
            with open('/proc/%s/stat' % entry) as f:
                if f.read().rsplit(')', 1)[1].split()[0] == 'Z':
                    continue
        except OSError:
            continue
        out.append(int(entry))
    return out


def children_cpu_seconds():
    """CPU time (user + system) of this process's children that have exited and been waited
    for, with their own waited-for descendants (roslaunch waits for its nodes)."""
    ru = resource.getrusage(resource.RUSAGE_CHILDREN)
    return ru.ru_utime + ru.ru_stime


class RunFailed(Exception):
    pass


class _Run(RosSession):
    def __init__(self, cfg, run_dir):
        self.cfg = cfg
        self.dir = run_dir
        self.logs = os.path.join(run_dir, 'logs')
        os.makedirs(self.logs, exist_ok=True)
        self.token = uuid.uuid4().hex
        self.sim_node_pid = None
        RosSession.__init__(self, os.path.join(run_dir, 'run.launch'), self.log_file('sim'),
                            log_dir=self.logs,
                            env={'ROS_HOME': os.path.join(run_dir, 'ros_home'),
                                 TOKEN_VAR: self.token},
                            cwd=run_dir, preexec_fn=_default_signals)

    def log_file(self, name):
        return os.path.join(self.logs, name + '.log')

    def spawn(self, name, cmd, log_path=None):
        try:
            return RosSession.spawn(self, name, cmd, log_path or self.log_file(name))
        except OSError as e:
            raise RunFailed('%s: cannot start %r: %s' % (name, cmd[0], e.strerror))

    def spawn_master(self, log_path=None):
        try:
            return RosSession.spawn_master(self, log_path or self.log_file('master'))
        except OSError as e:
            raise RunFailed('master: cannot start %r: %s' % ('rosmaster', e.strerror))

    def check(self, names):
        if self.sim_node_pid and 'sim' in names and not _alive(self.sim_node_pid):
            raise RunFailed('the simulator node (pid %d) died%s' % (
                self.sim_node_pid, self.sim_exit_note()))
        for name in names:
            p = self.master_proc if name == 'master' else self.procs.get(name)
            if p is not None and p.poll() is not None and (p.returncode != 0 or name != 'driver'):
                raise RunFailed('%s exited with code %s before the run ended' % (
                    {'sim': 'the simulator launch', 'driver': 'the driver',
                     'recorder': 'the recorder', 'master': 'rosmaster'}[name], p.returncode))

    def wait(self, what, predicate, deadline, watch):
        while True:
            self.check(watch)
            try:
                if predicate():
                    return
            except (OSError, xmlrpc.client.Error):
                pass
            if time.time() > deadline:
                raise TimeoutError(what)
            time.sleep(0.05)

    def sim_exit_note(self):
        """roslaunch's line on the simulator node's exit (`process has died [pid N, exit code
        -11, ...]`), as ': exit code -11 (SIGSEGV)'; it may come a moment after the death."""
        pattern = re.compile(r'process has died \[pid %d, exit code (-?\d+)' % self.sim_node_pid)
        for _ in range(40):
            try:
                with open(self.log_file('sim'), errors='replace') as f:
                    m = pattern.search(f.read())
            except OSError:
                m = None
            if m:
                code = int(m.group(1))
                if code < 0:
                    try:
                        return ': exit code %d (%s)' % (code, signal.Signals(-code).name)
                    except ValueError:
                        pass
                return ': exit code %d' % code
            time.sleep(0.05)
        return ''

    def has_service(self, name):
        return self.master().lookupService(CALLER, name)[0] == 1

    def publishers(self, topic):
        code, _, state = self.master().getSystemState(CALLER)
        return [nodes for t, nodes in state[0] if t == topic] if code == 1 else []

    def stop(self):
        """SIGINT to every process group, then SIGKILL; then whatever still carries the token."""
        for name in ['driver', 'recorder', 'sim']:
            if name in self.procs:
                stop_process(self.procs[name], 10.0 if name == 'sim' else 5.0)
        if self.master_proc:
            stop_master(self.master_proc)
        leftovers = processes_with_token(self.token)
        self.leftover_names = []
        for pid in leftovers:
            try:
                with open('/proc/%d/cmdline' % pid, 'rb') as f:
                    self.leftover_names.append(f.read().replace(b'\0', b' ').decode(errors='replace')[:200])
            except OSError:
                pass
        for pid in leftovers:
            try:
                os.kill(pid, signal.SIGKILL)
            except ProcessLookupError:
                pass
        deadline = time.time() + 5.0
        while processes_with_token(self.token) and time.time() < deadline:
            time.sleep(0.05)
        self.close_logs()
        return leftovers


def _default_signals():
    # A Ray worker blocks SIGINT and SIGTERM in its task threads, and a blocked (or ignored)
    # signal stays so across exec: roslaunch would not hear the SIGINT that asks it to stop.
    signal.pthread_sigmask(signal.SIG_UNBLOCK, [signal.SIGINT, signal.SIGTERM])
    signal.signal(signal.SIGINT, signal.SIG_DFL)
    signal.signal(signal.SIGTERM, signal.SIG_DFL)


def start_guard(token):
    """The guard of a run's processes (module doc); its stdin is the pipe from this process. The
    process started forks the guard and exits: the guard is not this process's child, as a dying
    Ray worker kills its children (RAY_kill_child_processes_on_worker_exit)."""
    env = {k: v for k, v in os.environ.items() if k != TOKEN_VAR}
    p = subprocess.Popen([sys.executable, '-m', 'tianracer_bringup.run', '--guard', token],
                         stdin=subprocess.PIPE, env=env, start_new_session=True,
                         preexec_fn=_default_signals)
    p.wait()
    return p.stdin


def end_guard(pipe):
    try:
        pipe.write(b'done\n')
        pipe.close()
    except OSError:
        pass


def guard_main(token):
    if os.fork() > 0:
        os._exit(0)
    signal.signal(signal.SIGINT, signal.SIG_IGN)  # a Ctrl-C in the terminal is the run's to handle
    said = sys.stdin.buffer.read()  # until EOF: the run is done, or its process died
    if said.strip() == b'done':
        return 0
    for _ in range(3):  # nodes may be starting as their parents die
        for pid in processes_with_token(token):
            try:
                os.kill(pid, signal.SIGKILL)
            except ProcessLookupError:
                pass
        time.sleep(0.5)
    return 0


def run_one(run_id, cfg, run_dir):
    """Runs one scenario run; never raises for a failed run. Returns a dict: id, status ('ok' or
    'failed'), reason, metrics (from the recorder), wall times, leftover processes, log tails."""
    wall0 = time.time()
    cpu0 = children_cpu_seconds()  # a Ray worker runs one task at a time: the delta is this run's
    r = _Run(cfg, run_dir)
    guard = start_guard(r.token)
    timeout = run_timeout(cfg)
    deadline = wall0 + timeout
    result = {'id': run_id, 'host': socket.gethostname(), 'run_dir': run_dir, 'status': 'failed',
              'reason': '', 'metrics': None}
    stage = 'starting rosmaster'
    with open(os.path.join(run_dir, 'run.json'), 'w') as f:
        json.dump(cfg, f, indent=1)
    launch_file = os.path.join(run_dir, 'run.launch')
    with open(launch_file, 'w') as f:
        f.write(sim_launch_xml(cfg))
    metrics_json = os.path.join(run_dir, 'metrics.json')
    ready = os.path.join(run_dir, 'recorder.ready')
    go = os.path.join(run_dir, 'recorder.go')
    for p in (metrics_json, ready, go):
        if os.path.exists(p):
            os.remove(p)
    try:
        r.spawn_master()
        r.wait('rosmaster', lambda: r.master().getPid(CALLER)[0] == 1, deadline, ['master'])
        stage = 'starting the simulator'
        r.launch('sim')
        r.wait('the simulator (/gazebo/unpause_physics)',
               lambda: r.has_service('/gazebo/unpause_physics'), deadline, ['master', 'sim'])
        r.sim_node_pid = r.node_pid('/tianracer_sim')
        stage = 'starting the recorder'
        r.spawn('recorder', [sys.executable, '-m', 'tianracer_bringup.recorder',
                             os.path.join(run_dir, 'run.json'), metrics_json, ready, go])
        r.wait('the recorder to connect', lambda: os.path.exists(ready), deadline,
               ['master', 'sim', 'recorder'])
        watch = ['master', 'sim', 'recorder']
        if cfg['driver']:
            stage = 'starting the driver'
            r.spawn('driver', driver_cmd(cfg, r.port))
            watch.append('driver')
            topic = cfg['driver']['ready_topic']
            if topic:
                r.wait('the driver to publish %s' % topic, lambda: r.publishers(topic), deadline, watch)
            # Connections follow registrations: unpaused earlier, a first message could be lost
            # to one node and not another, and the run would start differently.
            r.wait('the ROS graph to connect', lambda: graph_connected(r.master(), CALLER), deadline, watch)
        stage = 'running'
        result['startup_wall_time'] = time.time() - wall0
        t_unpause = time.time()
        with open(go, 'w') as f:
            f.write('go\n')  # the recorder unpauses the simulator
        watch.remove('recorder')  # its exit is the end of the run
        r.wait('the run to reach %g s of sim time' % cfg['duration'],
               lambda: r.procs['recorder'].poll() is not None, deadline, watch)
        result['run_wall_time'] = time.time() - t_unpause
        if r.procs['recorder'].returncode != 0:
            raise RunFailed('the recorder exited with code %s' % r.procs['recorder'].returncode)
        with open(metrics_json) as f:
            result['metrics'] = json.load(f)
        result['status'] = 'ok'
        result['reason'] = result['metrics']['reason']
    except TimeoutError as e:
        result['reason'] = 'timed out after %.0f s wall while waiting for %s' % (timeout, e)
    except RunFailed as e:
        result['reason'] = '%s (while %s)' % (e, stage)
    except (OSError, ValueError) as e:
        result['reason'] = '%s: %s' % (stage, e)
    finally:
        t_stop = time.time()
        leftovers = r.stop()
        end_guard(guard)
        result['stop_wall_time'] = time.time() - t_stop
    # Every process of the run has been waited for by now (stop()), its nodes by roslaunch.
    result['cpu_seconds'] = children_cpu_seconds() - cpu0
    result['wall_start'] = wall0
    result['wall_end'] = time.time()
    result['wall_time'] = result['wall_end'] - wall0
    result['leftover_processes'] = len(leftovers)
    result['leftover_commands'] = r.leftover_names
    if result['status'] != 'ok' or result['metrics'] is None or not result['metrics']['success']:
        result['log_tails'] = {name: _tail(r.log_file(name)) for name in ('driver', 'recorder', 'sim')
                               if os.path.exists(r.log_file(name))}
        import glob
        for path in sorted(glob.glob(os.path.join(r.logs, '**', 'tianracer_sim-*.log'), recursive=True)):
            result['log_tails']['tianracer_sim node'] = _tail(path)
    return result


if __name__ == '__main__':
    if len(sys.argv) == 3 and sys.argv[1] == '--guard':
        sys.exit(guard_main(sys.argv[2]))
    sys.exit('usage: python3 -m tianracer_bringup.run --guard TOKEN')
