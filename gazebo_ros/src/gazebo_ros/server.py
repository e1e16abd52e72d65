"""gzserver, gazebo and debug: Gazebo classic's server command line (gazebo/Server.cc,
Server::ParseArgs) turned into tianracer_sim's node on that world, named /gazebo as
gazebo_ros's API plugin names its node, with no robot at start: robots come through
/gazebo/spawn_urdf_model (spawn_model). Each Gazebo option we do not take is named with what
happens instead; ROS arguments (name:=value) go to the node unchanged.

Also what gazebo_ros's paths plugin does for world files: packages that export
gazebo_media_path for gazebo_ros extend GAZEBO_RESOURCE_PATH (the node itself finds the
gazebo_model_path exports for model:// URIs)."""
from __future__ import print_function

import os
import shutil
import subprocess
import sys
import time

# Options with a value, and flags (Gazebo 11's gzserver --help).
VALUE_OPTIONS = {'-e': '--physics', '-p': '--play', '-s': '--server-plugin', '-o': '--profile'}
LONG_VALUE_OPTIONS = {'--physics', '--play', '--server-plugin', '--profile', '--seed', '--iters',
                      '--record_encoding', '--record_path', '--record_period', '--record_filter',
                      '--server-logfile'}
FLAGS = {'-v': '--version', '-h': '--help', '-u': '--pause', '-r': '--record'}
LONG_FLAGS = {'--version', '--help', '--pause', '--record', '--record_resources', '--verbose',
              '--minimal_comms', '--lockstep'}
# System plugins whose work the node does itself.
BUILT_IN_PLUGINS = {'libgazebo_ros_api_plugin.so', 'libgazebo_ros_paths_plugin.so'}

USAGE = """%(prog)s -- tianracer_sim in place of Gazebo's server (gazebo_ros stand-in).

`%(prog)s` [options] <world_file> [ROS arguments name:=value ...]

Starts tianracer_sim's node as /gazebo on the world (default worlds/empty.world), with no robot:
robots come through /gazebo/spawn_urdf_model (rosrun gazebo_ros spawn_model ...).

Options taken: -u/--pause (start paused), --seed N (sensor noise seed), --verbose,
  -s/--server-plugin libgazebo_ros_api_plugin.so|libgazebo_ros_paths_plugin.so (built in),
  -e/--physics ENGINE (noted: the physics is Bullet's), -h/--help, -v/--version.
Options noted and left out: -r/--record and --record_*, --iters, --server-logfile,
  --minimal_comms, --lockstep, -o/--profile, other -s plugins.
Refused: -p/--play (log playback).
World files: as given, else under each GAZEBO_RESOURCE_PATH folder, else tianracer_sim's
  worlds folder by base name (worlds/empty.world is tianracer_sim's empty world).
"""


class ServerArgs(object):
    def __init__(self):
        self.world = None
        self.paused = False
        self.seed = None
        self.plugins = []
        self.physics = None
        self.remaps = []        # ROS arguments for the node
        self.notes = []         # what we do instead of an option
        self.error = None       # an option we refuse
        self.help = False
        self.version = False
        self.verbose = False


def parse(argv):
    """Gazebo's options (anywhere, --name=value or --name value) into ServerArgs."""
    a = ServerArgs()
    positional = []
    i = 0
    while i < len(argv):
        arg = argv[i]
        i += 1
        if ':=' in arg:
            a.remaps.append(arg)
            continue
        if not arg.startswith('-') or arg == '-':
            positional.append(arg)
            continue
        name, value = arg, None
        if arg.startswith('--') and '=' in arg:
            name, value = arg.split('=', 1)
        name = VALUE_OPTIONS.get(name, FLAGS.get(name, name))
        if name in LONG_VALUE_OPTIONS:
            if value is None:
                if i >= len(argv):
                    a.error = 'option %s needs a value' % name
                    return a
                value = argv[i]
                i += 1
            _take_value(a, name, value)
        elif name in LONG_FLAGS:
            _take_flag(a, name)
        else:
            a.notes.append('%s is not a gzserver option; ignored (as gzserver ignores unknown '
                           'options)' % arg)
    if positional:
        a.world = positional[0]
    if len(positional) > 1:
        a.notes.append('arguments after the world file (%s) are for system plugins; none is '
                       'loaded, so they change nothing' % ' '.join(positional[1:]))
    return a


def _take_value(a, name, value):
    if name == '--physics':
        a.physics = value
        a.notes.append('-e %s: tianracer_sim simulates with Bullet (btMultiBody) whatever engine '
                       'is named; the <physics> step, rate and gravity of the world apply' % value)
    elif name == '--play':
        a.error = ('-p %s: log playback is not supported (tianracer_sim runs worlds, not Gazebo '
                   'state logs)' % value)
    elif name == '--server-plugin':
        base = os.path.basename(value)
        if base not in BUILT_IN_PLUGINS:
            a.notes.append('-s %s: system plugin not loaded (tianracer_sim loads no Gazebo plugin '
                           'libraries; the plugins it simulates are listed at start-up)' % value)
        a.plugins.append(value)
    elif name == '--seed':
        try:
            a.seed = int(float(value))
        except ValueError:
            a.notes.append('--seed %s is not a number; the default seed is used' % value)
    elif name == '--iters':
        a.notes.append('--iters %s: not supported; the simulation runs until it is shut down'
                       % value)
    elif name.startswith('--record'):
        a.notes.append('%s %s: recording is not supported (record topics with rosbag)'
                       % (name, value))
    elif name == '--server-logfile':
        a.notes.append('--server-logfile %s: not used; the node logs through ROS' % value)
    elif name == '--profile':
        a.notes.append('-o %s: physics profiles are not supported; the world\'s <physics> '
                       'applies' % value)


def _take_flag(a, name):
    if name == '--pause':
        a.paused = True
    elif name == '--help':
        a.help = True
    elif name == '--version':
        a.version = True
    elif name == '--verbose':
        a.verbose = True
    elif name in ('--record', '--record_resources'):
        a.notes.append('%s: recording is not supported (record topics with rosbag)' % name)
    elif name == '--minimal_comms':
        a.notes.append('--minimal_comms: accepted; changes nothing (no Gazebo transport here)')
    elif name == '--lockstep':
        a.notes.append('--lockstep: accepted; sensors always update in step with the physics '
                       'here')


def resolve_world(name, resource_path, shipped_dir):
    """The world file for Gazebo's world argument; raises LookupError naming the folders
    searched."""
    name = name or 'worlds/empty.world'
    if os.path.isfile(name):
        return os.path.abspath(name)
    searched = []
    for folder in [p for p in resource_path.split(':') if p]:
        candidate = os.path.join(folder, name)
        searched.append(folder)
        if os.path.isfile(candidate):
            return candidate
    base = os.path.basename(name)
    if not base.endswith('.world'):
        base += '.world'
    candidate = os.path.join(shipped_dir, base)
    searched.append(shipped_dir)
    if os.path.isfile(candidate):
        return candidate
    raise LookupError('world file %s not found (looked in: the current folder, %s)'
                      % (name, ', '.join(searched)))


def world_or_fallback(name, resource_path, shipped_dir):
    """(world file, warning): the world named, or, where it is not found, worlds/empty.world with
    a warning naming what was searched, as Gazebo's Server::ParseArgs falls back when LoadFile
    fails (gazebo/Server.cc: "Falling back on worlds/empty.world"). LookupError when empty.world
    is not found either."""
    try:
        return resolve_world(name, resource_path, shipped_dir), None
    except LookupError as e:
        return (resolve_world('worlds/empty.world', resource_path, shipped_dir),
                '%s; falling back on worlds/empty.world, as Gazebo does' % e)


def exported_paths(attribute, run=subprocess.run):
    """Paths that packages export for gazebo_ros under `attribute` (rospack plugins)."""
    try:
        out = run(['rospack', 'plugins', '--attrib=' + attribute, 'gazebo_ros'],
                  stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, universal_newlines=True,
                  check=False).stdout
    except OSError:
        return []
    paths = []
    for line in out.splitlines():
        parts = line.split(None, 1)
        if len(parts) == 2:
            paths.extend(p for p in parts[1].strip().split(':') if p)
    return paths


def extend_env_path(env, variable, paths):
    current = [p for p in env.get(variable, '').split(':') if p]
    for p in paths:
        if p not in current:
            current.append(p)
    if current:
        env[variable] = ':'.join(current)


def node_name(remaps, environ):
    """The node's full name from __name:= and __ns:= (or ROS_NAMESPACE); 'gazebo' by default,
    as gazebo_ros's node is named."""
    name, ns = 'gazebo', environ.get('ROS_NAMESPACE', '/')
    for r in remaps:
        key, value = r.split(':=', 1)
        if key == '__name':
            name = value
        elif key == '__ns':
            ns = value
    ns = '/' + ns.strip('/')
    return (ns.rstrip('/') + '/' + name) if ns != '/' else '/' + name


def _say(prog, text):
    sys.stderr.write('%s: %s\n' % (prog, text))


def _set_params(full_name, params, prog):
    import rosgraph
    master = rosgraph.Master(full_name)
    warned = False
    while True:
        try:
            for key, value in params.items():
                master.setParam(full_name + '/' + key, value)
            return
        except Exception:  # master not up yet, as roscpp nodes wait for it
            if not warned:
                _say(prog, 'waiting for the ROS master at %s' % rosgraph.get_master_uri())
                warned = True
            time.sleep(0.5)


def main(argv, mode):
    prog = os.path.basename(argv[0]) if argv else mode
    a = parse(argv[1:])
    if a.help:
        print(USAGE % {'prog': prog})
        return 0
    if a.version:
        print('%s: tianracer_sim in place of Gazebo (gazebo_ros stand-in)' % prog)
        return 0
    if a.error:
        _say(prog, 'error: ' + a.error)
        return 2
    if mode == 'gazebo':
        _say(prog, 'note: tianracer_sim has no GUI (gzclient): running the server only')
    for note in a.notes:
        _say(prog, 'note: ' + note)

    import roslib.packages
    import rospkg
    env = dict(os.environ)
    extend_env_path(env, 'GAZEBO_RESOURCE_PATH', exported_paths('gazebo_media_path'))
    shipped = os.path.join(rospkg.RosPack().get_path('tianracer_sim'), 'worlds')
    try:
        world, fallback = world_or_fallback(a.world, env.get('GAZEBO_RESOURCE_PATH', ''), shipped)
    except LookupError as e:
        _say(prog, 'error: %s' % e)
        return 1
    if fallback:
        _say(prog, 'warning: ' + fallback)
    nodes = roslib.packages.find_node('tianracer_sim', 'tianracer_sim_node')
    if not nodes:
        _say(prog, 'error: tianracer_sim_node not found (is tianracer_sim built?)')
        return 1
    remaps = list(a.remaps)
    if not any(r.startswith('__name:=') for r in remaps):
        remaps.append('__name:=gazebo')
    full_name = node_name(remaps, env)
    # gazebo_ros's interface exactly: no ~step services and no /diagnostics, which Gazebo has
    # not (ROS arguments _step_services:=true / _diagnostics:=true bring them back).
    # gazebo_ros_api_plugin advertises in its node's private namespace ("~"): /gazebo/... for a
    # node named gazebo at the root, /<ns>/gazebo/... under a launch file's <group ns>.
    params = {'world': world, 'paused': a.paused, 'robots': [], 'step_services': False,
              'diagnostics': False, 'gazebo_namespace': full_name}
    if a.seed is not None:
        params['seed'] = a.seed
    _set_params(full_name, params, prog)
    cmd = [nodes[0]] + remaps
    if mode == 'debug':
        gdb = shutil.which('gdb')
        if gdb:
            cmd = [gdb, '-ex', 'run', '--args'] + cmd
        else:
            _say(prog, 'note: gdb is not installed: running without the debugger')
    sys.stdout.flush()
    sys.stderr.flush()
    os.execve(cmd[0], cmd, env)
