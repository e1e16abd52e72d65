"""What the demo, the benchmarks, the soak, the batch runner and the tests share: a ROS graph
of their own (a private master on a free port, the environment for it), one roslaunch with a
reliable way to end it, and questions to the graph.

roslaunch starts every node (and the master) in a new session (os.setsid), so killing
roslaunch's process group does not reach them: RosSession records the pid of the master and
of every node it sees, asks roslaunch to shut down (SIGINT), and SIGKILLs whatever is left.
"""
import os
import shlex
import signal
import subprocess
import time
import xmlrpc.client

from tianracer_sim.master import (free_port, master_cmd, ros_env, spawn_master,  # noqa: F401
                                  stop_master, wait_for_master)

CALLER = "/ros_session"


def wrapper_launch(path, args, params, extra_xml=""):
    """A launch file that includes tianracer_sim's sim.launch with args and sets extra params.

    params go to the parameter server before any node starts (e.g. /tianracer_sim/seed, a
    private parameter the launch file has no arg for); extra_xml is added as is (more nodes).
    """
    lines = ["<launch>"]
    for name, value in params.items():
        lines.append('  <param name="%s" value="%s" />' % (name, value))
    lines.append('  <include file="$(find tianracer_sim)/launch/sim.launch">')
    for name, value in args.items():
        lines.append('    <arg name="%s" value="%s" />' % (name, value))
    lines.append("  </include>")
    if extra_xml:
        lines.append(extra_xml)
    lines.append("</launch>")
    with open(path, "w") as f:
        f.write("\n".join(lines) + "\n")
    return path


class RosSession:
    """own_master: start rosmaster first and wait for it (roslaunch gives a master 10 s to come
    up, which a loaded machine can miss); False: roslaunch starts it, as a user's launch does.
    launch_file is a path, or roslaunch's arguments as a user types them (a list, e.g.
    ['tianracer_bringup', 'tianracer.launch', 'robot_name:=racecar']). env: more environment
    variables for every process of the session; popen: more Popen arguments for each (cwd,
    preexec_fn)."""

    def __init__(self, launch_file, log_path, log_dir=None, port=None, own_master=True, env=None,
                 **popen):
        self.own_master = own_master
        self.master_proc = None
        self.port = port or free_port()
        self.uri = "http://localhost:%d" % self.port
        self.env = ros_env(self.port, log_dir)
        self.env.update(env or {})
        self.popen_kw = popen
        self.launch_file = launch_file
        self.log_path = log_path
        self.proc = None
        self.procs = {}  # name -> Popen of every process started but the master, in start order
        self.pids = {}  # name -> pid of the master and of nodes seen
        self.files = []  # logs opened, closed by close()
        self._log = None  # the session's log, opened by the first process that writes to it
        self.t_start = None

    # -- lifetime -------------------------------------------------------------------------
    def start(self):
        if self.own_master:
            self.spawn_master()
            self.pids["master"] = wait_for_master(self.master_proc, self.port,
                                                  what="; see %s" % self.log_path)
        self.t_start = time.time()
        self.launch()
        return self

    def launch(self, name="launch", log_path=None):
        """roslaunch of the session's launch file (self.proc)."""
        launch = list(self.launch_file) if isinstance(self.launch_file, (list, tuple)) else [self.launch_file]
        self.proc = self.spawn(name, ["roslaunch", "-p", str(self.port)] + launch, log_path)
        return self.proc

    def _open_log(self, log_path, cmd):
        """The session's log (log_path None), or a log of its own that starts with the command."""
        if log_path is None:
            if self._log is None:
                self._log = open(self.log_path, "w")
                self.files.append(self._log)
            return self._log
        f = open(log_path, "w")
        self.files.append(f)
        f.write("$ %s\n" % " ".join(shlex.quote(c) for c in cmd))
        f.flush()
        return f

    def spawn_master(self, log_path=None):
        """rosmaster on the session's port, its output to the session's log or to log_path."""
        log = self._open_log(log_path, master_cmd(self.port))
        self.master_proc = spawn_master(self.port, self.env, log, **self.popen_kw)
        return self.master_proc

    def spawn(self, name, cmd, log_path=None):
        """A process of the session's graph (roslaunch, a node, a client) in a session of its own,
        its output to the session's log or to log_path; ended by close()."""
        log = self._open_log(log_path, cmd)
        p = subprocess.Popen(cmd, env=self.env, stdout=log, stderr=subprocess.STDOUT,
                             stdin=subprocess.DEVNULL, start_new_session=True, **self.popen_kw)
        self.procs[name] = p
        return p

    def popen(self, cmd, **kw):
        """A client process in this session's ROS graph; ended by close()."""
        kw.setdefault("stdin", subprocess.DEVNULL)
        p = subprocess.Popen(cmd, env=self.env, start_new_session=True, **kw)
        self.procs["client %d" % len(self.procs)] = p
        return p

    def close(self):
        """SIGINT to every process (the clients first), SIGKILL to those still there after 15 s;
        then the master; then every node seen that is still alive."""
        self.remember_pids()
        running = list(reversed(list(self.procs.values())))
        for p in running:
            _signal_group(p, signal.SIGINT)
        deadline = time.time() + 15.0
        for p in running:
            stop_process(p, max(0.1, deadline - time.time()), signal_first=False)
        if self.master_proc:
            stop_master(self.master_proc)
        for name, pid in self.pids.items():
            if _alive(pid):
                try:
                    os.kill(pid, signal.SIGKILL)
                except ProcessLookupError:
                    pass
        self.close_logs()

    def close_logs(self):
        for f in self.files:
            f.close()
        self.files = []

    def __enter__(self):
        return self.start()

    def __exit__(self, *exc):
        self.close()

    # -- graph queries ---------------------------------------------------------------------
    def master(self):
        return xmlrpc.client.ServerProxy(self.uri)

    def check_running(self):
        if self.proc.poll() is not None:
            raise RuntimeError("roslaunch exited with %s; see %s" % (self.proc.returncode, self.log_path))

    def system_state(self):
        code, _, state = self.master().getSystemState(CALLER)
        return state if code == 1 else ([], [], [])

    def wait_for(self, predicate, timeout, what):
        deadline = time.time() + timeout
        while True:
            self.check_running()
            try:
                if predicate():
                    return
            except (OSError, xmlrpc.client.Error):
                pass  # master not up yet
            if time.time() > deadline:
                raise RuntimeError("timed out after %.0f s waiting for %s; see %s" % (timeout, what, self.log_path))
            time.sleep(0.05)

    def wait_for_service(self, service, timeout=60.0):
        self.wait_for(lambda: self.master().lookupService(CALLER, service)[0] == 1, timeout, service)

    def node_pid(self, node):
        code, _, uri = self.master().lookupNode(CALLER, node)
        if code != 1:
            return None
        code, _, pid = xmlrpc.client.ServerProxy(uri).getPid(CALLER)
        return pid if code == 1 else None

    def remember_pids(self):
        """Record the master's and every node's pid (best effort; called again by close())."""
        try:
            self.pids["master"] = self.master().getPid(CALLER)[2]
            pubs, subs, srvs = self.system_state()
            nodes = {n for entry in pubs + subs + srvs for n in entry[1]}
            for n in nodes:
                pid = self.node_pid(n)
                if pid and pid != os.getpid():
                    self.pids[n] = pid
        except (OSError, xmlrpc.client.Error):
            pass


def _alive(pid):
    try:
        with open("/proc/%d/stat" % pid) as f:
            return f.read().split(")")[-1].split()[0] != "Z"
    except OSError:
        return False


def _signal_group(p, sig):
    try:
        os.killpg(p.pid, sig)
    except (ProcessLookupError, PermissionError):
        pass


def stop_process(p, timeout, signal_first=True):
    """SIGINT to the process group of `p` (a process started in a session of its own) while it
    runs, SIGKILL to the group after `timeout` s."""
    if signal_first and p.poll() is None:
        _signal_group(p, signal.SIGINT)
    try:
        p.wait(timeout)
    except subprocess.TimeoutExpired:
        _signal_group(p, signal.SIGKILL)
        p.wait()


def proc_cpu_seconds(pid):
    """utime + stime of a process (all its threads), seconds."""
    with open("/proc/%d/stat" % pid) as f:
        fields = f.read().rsplit(")", 1)[1].split()
    return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")


def proc_peak_rss_mb(pid):
    with open("/proc/%d/status" % pid) as f:
        for line in f:
            if line.startswith("VmHWM:"):
                return int(line.split()[1]) / 1024.0
    return None


def bus_connections(node_uri, caller=CALLER):
    """A node's connections (getBusInfo): [id, other end, 'i'/'o'/'b', transport, topic, connected, ...]."""
    code, _, info = xmlrpc.client.ServerProxy(node_uri).getBusInfo(caller)
    return info if code == 1 else []


def graph_connected(master, caller=CALLER):
    """True when every publisher of every subscribed topic has a live connection to each of the
    topic's subscribers (registration at the master comes before the connection: a message
    published in between is lost to the subscriber that is not yet connected)."""
    code, _, (pubs, subs, _) = master.getSystemState(caller)
    if code != 1:
        return False
    subscribers = {t: set(nodes) for t, nodes in subs}
    uris = {}
    for topic, nodes in pubs:
        wanted = subscribers.get(topic, set())
        for node in nodes:
            if not wanted - {node}:
                continue
            if node not in uris:
                code, _, uri = master.lookupNode(caller, node)
                uris[node] = uri if code == 1 else None
            if not uris[node]:
                return False
            out = [c for c in bus_connections(uris[node], caller) if c[2] == 'o' and c[4] == topic and c[5]]
            if len(out) < len(wanted - {node}):
                return False
    return True
