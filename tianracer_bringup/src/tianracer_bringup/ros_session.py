"""What the demo, the benchmarks, the soak, the batch runner and the tests share: a ROS graph
of their own (a private master on a free port, the environment for it), one roslaunch with a
reliable way to end it, and questions to the graph.

roslaunch starts every node (and the master) in a new session (os.setsid), so killing
roslaunch's process group does not reach them: RosSession records the pid of the master and
of every node it sees, asks roslaunch to shut down (SIGINT), and SIGKILLs whatever is left.
"""
import os
import signal
import socket
import subprocess
import time
import xmlrpc.client

CALLER = "/ros_session"


def free_port():
    with socket.socket(socket.AF_INET, socket.SOCK_STREAM) as s:
        s.bind(("localhost", 0))
        return s.getsockname()[1]


def ros_env(port, log_dir=None):
    env = dict(os.environ)
    env["PATH"] = "/usr/bin:" + env.get("PATH", "")
    env["ROS_MASTER_URI"] = "http://localhost:%d" % port
    env["ROS_HOSTNAME"] = "localhost"
    env.pop("ROS_IP", None)
    if log_dir:
        env["ROS_LOG_DIR"] = log_dir
    return env


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
    ['tianracer_bringup', 'tianracer.launch', 'robot_name:=racecar'])."""

    def __init__(self, launch_file, log_path, log_dir=None, port=None, own_master=True):
        self.own_master = own_master
        self.master_proc = None
        self.port = port or free_port()
        self.uri = "http://localhost:%d" % self.port
        self.env = ros_env(self.port, log_dir)
        self.launch_file = launch_file
        self.log_path = log_path
        self.proc = None
        self.pids = {}  # name -> pid of the master and of nodes seen
        self.others = []  # extra Popen objects tied to this session (clients)
        self.t_start = None

    # -- lifetime -------------------------------------------------------------------------
    def start(self):
        self._log = open(self.log_path, "w")
        if self.own_master:
            self.master_proc = subprocess.Popen(["rosmaster", "--core", "-p", str(self.port), "-w", "3"],
                                                env=self.env, stdout=self._log, stderr=subprocess.STDOUT,
                                                stdin=subprocess.DEVNULL, start_new_session=True)
            deadline = time.time() + 120.0
            while True:
                try:
                    self.pids["master"] = self.master().getPid(CALLER)[2]
                    break
                except OSError:
                    if self.master_proc.poll() is not None or time.time() > deadline:
                        raise RuntimeError("rosmaster on port %d did not start; see %s" % (self.port, self.log_path))
                    time.sleep(0.05)
        self.t_start = time.time()
        launch = list(self.launch_file) if isinstance(self.launch_file, (list, tuple)) else [self.launch_file]
        self.proc = subprocess.Popen(["roslaunch", "-p", str(self.port)] + launch,
                                     env=self.env, stdout=self._log, stderr=subprocess.STDOUT,
                                     stdin=subprocess.DEVNULL, start_new_session=True)
        return self

    def popen(self, cmd, **kw):
        """A client process in this session's ROS graph; ended by close()."""
        kw.setdefault("stdin", subprocess.DEVNULL)
        p = subprocess.Popen(cmd, env=self.env, start_new_session=True, **kw)
        self.others.append(p)
        return p

    def close(self):
        self.remember_pids()
        for p in self.others:
            _signal_group(p, signal.SIGINT)
        if self.proc and self.proc.poll() is None:
            _signal_group(self.proc, signal.SIGINT)
        deadline = time.time() + 15.0
        for p in self.others + ([self.proc] if self.proc else []):
            try:
                p.wait(max(0.1, deadline - time.time()))
            except subprocess.TimeoutExpired:
                _signal_group(p, signal.SIGKILL)
                p.wait()
        if self.master_proc:
            _signal_group(self.master_proc, signal.SIGINT)
            try:
                self.master_proc.wait(5.0)
            except subprocess.TimeoutExpired:
                _signal_group(self.master_proc, signal.SIGKILL)
                self.master_proc.wait()
        for name, pid in self.pids.items():
            if _alive(pid):
                try:
                    os.kill(pid, signal.SIGKILL)
                except ProcessLookupError:
                    pass
        if getattr(self, "_log", None):
            self._log.close()

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
