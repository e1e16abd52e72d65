"""Scenario files for `rosrun tianracer_bringup batch`: a base scenario and a matrix of values to
vary, validated strictly (every error names the file and line) and expanded into runs.

    name: pure_pursuit_speeds
    base:
      world: racetrack
      duration: 40
      driver: {command: rosrun tianracer_bringup pure_pursuit, args: {speed: 1.0}}
      success: {laps: 1, no_collision: true}
    matrix:
      driver.args.speed: [0.5, 1.0, 1.5]
      seed: [0, 1, 2]

The matrix is a product: every combination of its axes is one run, in file order (the last axis
varies fastest). A matrix key is a dotted path into `base` (`spawn.x`, `driver.args.speed`,
`params./cmd_vel_node/max_accel`). ROS-free: importable without a ROS environment.
"""
import copy
import itertools
import os
import re

import yaml


class ScenarioError(Exception):
    """One or more problems, each as 'file:line: message'."""

    def __init__(self, problems):
        self.problems = list(problems)
        super().__init__('\n'.join(self.problems))


# --- the schema -------------------------------------------------------------------------------
# A field is (type, required, default); type is one of the names below or a dict (a sub-mapping
# with its own fields). 'any_map' is a mapping with free keys and scalar values.
NUMBER, INT, BOOL, STR, STR_OR_LIST = 'number', 'int', 'bool', 'str', 'str_or_list'
ANY_MAP, METRICS = 'any_map', 'metrics'

SCHEMA = {
    'world': (STR, True, None),
    'model': (STR, False, None),
    'model_args': (ANY_MAP, False, {}),
    'control_config': (STR, False, None),
    'spawn': ({'x': (NUMBER, False, 0.0), 'y': (NUMBER, False, 0.0),
               'yaw': (NUMBER, False, 0.0)}, False, None),
    'sensors': ({'lidar': (BOOL, False, False), 'camera': (BOOL, False, False),
                 'depth': (BOOL, False, False)}, False, None),
    'seed': (INT, False, 0),
    'duration': (NUMBER, True, None),
    'timeout': (NUMBER, False, None),
    'real_time_factor': (NUMBER, False, 0.0),
    'params': (ANY_MAP, False, {}),
    'driver': ({'launch': (STR, False, None), 'command': (STR_OR_LIST, False, None),
                'args': (ANY_MAP, False, {}), 'ready_topic': (STR, False, '/cmd_vel'),
                'reply_period': (NUMBER, False, 0.02)},
               False, None),
    'success': ({'laps': (INT, False, 0),
                 'goal': ({'x': (NUMBER, True, None), 'y': (NUMBER, True, None),
                           'radius': (NUMBER, False, 0.5)}, False, None),
                 'no_collision': (BOOL, False, False),
                 'stop': (BOOL, False, False)}, False, None),
    'metrics': (METRICS, False, []),
}
METRIC_FIELDS = {'name': STR, 'topic': STR, 'field': STR, 'type': STR, 'stat': STR}
METRIC_STATS = ('mean', 'min', 'max', 'last')
TOP = {'name': STR, 'description': STR, 'base': dict, 'matrix': dict}
SHIPPED_WORLDS = ('empty', 'walled_room', 'racetrack')


# --- YAML with line numbers -------------------------------------------------------------------
class _Node:
    """A YAML value with the line it starts on (1-based)."""
    __slots__ = ('value', 'line')

    def __init__(self, value, line):
        self.value, self.line = value, line


def _compose(text, path):
    loader = yaml.SafeLoader(text)
    try:
        root = loader.get_single_node()
    except yaml.YAMLError as e:
        mark = getattr(e, 'problem_mark', None)
        line = mark.line + 1 if mark else 1
        raise ScenarioError(['%s:%d: not valid YAML: %s' % (path, line, getattr(e, 'problem', e))])
    finally:
        loader.dispose()
    if root is None:
        raise ScenarioError(['%s:1: the file is empty' % path])
    problems = []

    def walk(node):
        line = node.start_mark.line + 1
        if isinstance(node, yaml.MappingNode):
            out = {}
            for k, v in node.value:
                key = loader.construct_object(k, deep=True)
                if not isinstance(key, str):
                    problems.append('%s:%d: keys must be strings, got %r' % (path, k.start_mark.line + 1, key))
                    continue
                if key in out:
                    problems.append('%s:%d: duplicate key %r' % (path, k.start_mark.line + 1, key))
                out[key] = walk(v)
                out[key].line = k.start_mark.line + 1  # report a value at its key's line
            return _Node(out, line)
        if isinstance(node, yaml.SequenceNode):
            return _Node([walk(v) for v in node.value], line)
        return _Node(loader.construct_object(node, deep=True), line)

    tree = walk(root)
    if problems:
        raise ScenarioError(problems)
    return tree


def _plain(node):
    """The _Node tree as plain Python values."""
    if isinstance(node.value, dict):
        return {k: _plain(v) for k, v in node.value.items()}
    if isinstance(node.value, list):
        return [_plain(v) for v in node.value]
    return node.value


# --- validation -------------------------------------------------------------------------------
def _type_name(v):
    if v is None:
        return 'nothing'
    return {bool: 'a boolean', int: 'an integer', float: 'a number', str: 'a string',
            list: 'a list', dict: 'a mapping'}.get(type(v), type(v).__name__)


class _Checker:
    def __init__(self, path):
        self.path = path
        self.problems = []

    def err(self, line, msg):
        self.problems.append('%s:%d: %s' % (self.path, line, msg))

    def scalar(self, node, kind, where):
        v = node.value
        ok = {
            NUMBER: isinstance(v, (int, float)) and not isinstance(v, bool),
            INT: isinstance(v, int) and not isinstance(v, bool),
            BOOL: isinstance(v, bool),
            STR: isinstance(v, str),
            STR_OR_LIST: isinstance(v, str) or (isinstance(v, list) and all(
                isinstance(x.value, (str, int, float)) and not isinstance(x.value, bool) for x in v)),
        }[kind]
        if not ok:
            want = {NUMBER: 'a number', INT: 'an integer', BOOL: 'true or false', STR: 'a string',
                    STR_OR_LIST: 'a string or a list of strings'}[kind]
            self.err(node.line, '%s must be %s, got %s %r' % (where, want, _type_name(v), _plain(node)))
            return False
        if kind == NUMBER and v != v:
            self.err(node.line, '%s must be a number, got NaN' % where)
            return False
        return True

    def mapping(self, node, fields, where, partial=False):
        if not isinstance(node.value, dict):
            self.err(node.line, '%s must be a mapping, got %s' % (where, _type_name(_plain(node))))
            return
        for key, child in node.value.items():
            if key not in fields:
                self.err(child.line, 'unknown key %r in %s (known: %s)' % (key, where, ', '.join(fields)))
                continue
            self.field(child, fields[key][0], '%s.%s' % (where, key) if where != 'base' else key)
        if not partial:
            for key, (_, required, _) in fields.items():
                if required and key not in node.value:
                    self.err(node.line, '%s has no %r (required)' % (where, key))

    def field(self, node, kind, where):
        if isinstance(kind, dict):
            self.mapping(node, kind, where)
        elif kind == ANY_MAP:
            if not isinstance(node.value, dict):
                self.err(node.line, '%s must be a mapping, got %s' % (where, _type_name(_plain(node))))
                return
            for key, child in node.value.items():
                if isinstance(child.value, (dict, list)) or child.value is None:
                    self.err(child.line, '%s.%s must be a number, string or boolean, got %s'
                             % (where, key, _type_name(_plain(child))))
        elif kind == METRICS:
            if not isinstance(node.value, list):
                self.err(node.line, '%s must be a list, got %s' % (where, _type_name(_plain(node))))
                return
            for i, m in enumerate(node.value):
                w = '%s[%d]' % (where, i)
                if not isinstance(m.value, dict):
                    self.err(m.line, '%s must be a mapping with name, topic and field' % w)
                    continue
                for key, child in m.value.items():
                    if key not in METRIC_FIELDS:
                        self.err(child.line, 'unknown key %r in %s (known: %s)'
                                 % (key, w, ', '.join(METRIC_FIELDS)))
                    elif self.scalar(child, METRIC_FIELDS[key], '%s.%s' % (w, key)) and key == 'stat' \
                            and child.value not in METRIC_STATS:
                        self.err(child.line, '%s.stat must be one of %s, got %r'
                                 % (w, ', '.join(METRIC_STATS), child.value))
                for key in ('name', 'topic', 'field'):
                    if key not in m.value:
                        self.err(m.line, '%s has no %r (required)' % (w, key))
        else:
            self.scalar(node, kind, where)


def _lookup_kind(dotted):
    """The schema type at a dotted matrix key, or None when the key is not in the schema."""
    parts = dotted.split('.')
    fields = SCHEMA
    for i, part in enumerate(parts):
        if not isinstance(fields, dict) or part not in fields:
            return None
        kind = fields[part][0]
        rest = parts[i + 1:]
        if kind == ANY_MAP:
            return STR_OR_ANY if len(rest) == 1 else (ANY_MAP if not rest else None)
        if not rest:
            return kind
        fields = kind
    return None


STR_OR_ANY = 'scalar'


def _resolve_path(value, base_dir):
    """$(find pkg) substituted, relative paths taken from the scenario file's folder."""
    m = re.match(r'^\$\(find ([A-Za-z0-9_]+)\)(.*)$', value)
    if m:
        try:
            import rospkg
            return rospkg.RosPack().get_path(m.group(1)) + m.group(2)
        except Exception as e:  # rospkg missing or the package not found
            raise ValueError('cannot resolve $(find %s): %s' % (m.group(1), e))
    value = os.path.expanduser(value)
    return value if os.path.isabs(value) else os.path.normpath(os.path.join(base_dir, value))


def _set_dotted(d, dotted, value):
    parts = dotted.split('.')
    for part in parts[:-1]:
        if d.get(part) is None:
            d[part] = {}
        d = d[part]
    d[parts[-1]] = value


def get_dotted(d, dotted):
    for part in dotted.split('.'):
        if not isinstance(d, dict) or part not in d:
            return None
        d = d[part]
    return d


def _with_defaults(value, fields):
    out = {}
    for key, (kind, _, default) in fields.items():
        v = value.get(key) if value else None
        if isinstance(kind, dict):
            out[key] = _with_defaults(v, kind) if (v is not None or key in ('spawn', 'sensors')) else None
        else:
            out[key] = copy.deepcopy(default) if v is None else v
    return out


def _short(v):
    """A matrix value for labels: mappings as {k: v, ...} without quotes."""
    if isinstance(v, dict):
        return '{%s}' % ', '.join('%s: %s' % (k, _short(x)) for k, x in v.items())
    if isinstance(v, list):
        return '[%s]' % ', '.join(_short(x) for x in v)
    return str(v)


class Run:
    """One expanded run: `id` (run_000, ...), `label` (the matrix values), `values` (matrix key ->
    value) and `config` (the complete base with defaults and the values applied, paths absolute)."""

    def __init__(self, index, values, config):
        self.index = index
        self.id = 'run_%03d' % index
        self.values = values
        self.label = ', '.join('%s=%s' % (k, _short(v)) for k, v in values.items()) or 'base'
        self.config = config

    def __repr__(self):
        return 'Run(%s: %s)' % (self.id, self.label)


class Scenario:
    def __init__(self, path, name, description, base, matrix, runs):
        self.path, self.name, self.description = path, name, description
        self.base, self.matrix, self.runs = base, matrix, runs


def load(path, check_files=True):
    """Parse, validate and expand a scenario file; raises ScenarioError with every problem."""
    try:
        with open(path) as f:
            text = f.read()
    except OSError as e:
        raise ScenarioError(['%s:1: cannot read the scenario file: %s' % (path, e.strerror)])
    return loads(text, path, check_files)


def loads(text, path='<string>', check_files=True):
    tree = _compose(text, path)
    c = _Checker(path)
    if not isinstance(tree.value, dict):
        raise ScenarioError(['%s:%d: a scenario file is a mapping with base: and matrix:' % (path, tree.line)])
    for key, child in tree.value.items():
        if key not in TOP:
            c.err(child.line, 'unknown top-level key %r (known: %s)' % (key, ', '.join(TOP)))
        elif TOP[key] == STR:
            c.scalar(child, STR, key)
    if 'base' not in tree.value:
        raise ScenarioError(c.problems + ['%s:%d: no base: scenario' % (path, tree.line)])
    base_node = tree.value['base']
    c.mapping(base_node, SCHEMA, 'base', partial=True)

    matrix_node = tree.value.get('matrix', _Node({}, tree.line))
    axes = []
    if not isinstance(matrix_node.value, dict):
        c.err(matrix_node.line, 'matrix must be a mapping of key: [values], got %s'
              % _type_name(_plain(matrix_node)))
    else:
        for key, child in matrix_node.value.items():
            kind = _lookup_kind(key)
            if kind is None:
                c.err(child.line, 'unknown matrix key %r: not a key of the base scenario' % key)
                continue
            if not isinstance(child.value, list):
                c.err(child.line, 'matrix.%s must be a list of values, got %s'
                      % (key, _type_name(_plain(child))))
                continue
            if not child.value:
                c.err(child.line, 'matrix.%s is an empty list: an axis needs at least one value' % key)
                continue
            for i, v in enumerate(child.value):
                where = 'matrix.%s[%d]' % (key, i)
                if kind != STR_OR_ANY:
                    c.field(v, kind, where)
                elif isinstance(v.value, (dict, list)) or v.value is None:
                    c.err(v.line, '%s must be a number, string or boolean, got %s'
                          % (where, _type_name(_plain(v))))
            axes.append((key, child))

    # Keys every run needs, whether from base or the matrix.
    base_keys = set(base_node.value) if isinstance(base_node.value, dict) else set()
    axis_keys = {k for k, _ in axes}
    for key, (_, required, _) in SCHEMA.items():
        if required and key not in base_keys and key not in axis_keys:
            c.err(base_node.line, 'base has no %r (required; e.g. %s)'
                  % (key, {'world': 'world: racetrack', 'duration': 'duration: 30'}[key]))
    if c.problems:
        raise ScenarioError(c.problems)

    base = _plain(base_node)
    base_dir = os.path.dirname(os.path.abspath(path)) if path != '<string>' else os.getcwd()
    runs = []
    for index, combo in enumerate(itertools.product(*[child.value for _, child in axes])):
        cfg = copy.deepcopy(base)
        values = {}
        for (key, _), node in zip(axes, combo):
            _set_dotted(cfg, key, _plain(node))
            values[key] = _plain(node)
        cfg = _finish(cfg, c, base_node, dict(zip([k for k, _ in axes], combo)), base_dir, check_files)
        runs.append(Run(index, values, cfg))
    if c.problems:
        # The same problem can show in many runs: report each once.
        raise ScenarioError(list(dict.fromkeys(c.problems)))
    name = tree.value['name'].value if 'name' in tree.value else \
        os.path.splitext(os.path.basename(path))[0]
    desc = tree.value['description'].value if 'description' in tree.value else ''
    return Scenario(path, name, desc, base, dict((k, _plain(v)) for k, v in axes), runs)


def _finish(cfg, c, base_node, combo_nodes, base_dir, check_files):
    """Defaults filled in, paths resolved and checked, cross-field rules."""
    cfg = _with_defaults(cfg, SCHEMA)

    def line_of(key):
        if key in combo_nodes:
            return combo_nodes[key].line
        node = base_node
        for part in key.split('.'):
            if not isinstance(node.value, dict) or part not in node.value:
                return node.line
            node = node.value[part]
        return node.line

    def path_field(key, what):
        v = get_dotted(cfg, key)
        if v is None:
            return
        try:
            p = _resolve_path(v, base_dir)
        except ValueError as e:
            c.err(line_of(key), '%s: %s' % (key, e))
            return
        if check_files and not os.path.exists(p):
            c.err(line_of(key), '%s: %s %r not found (looked for %s)' % (key, what, v, p))
        _set_dotted(cfg, key, p)

    w = cfg['world']
    if w not in SHIPPED_WORLDS:
        if not (w.endswith('.world') or '/' in w):
            c.err(line_of('world'), "world %r is neither a shipped world (%s) nor a .world path"
                  % (w, ', '.join(SHIPPED_WORLDS)))
        else:
            path_field('world', 'world file')
    path_field('model', 'model')
    path_field('control_config', 'controller YAML')
    if cfg['duration'] <= 0:
        c.err(line_of('duration'), 'duration must be > 0 sim seconds, got %r' % cfg['duration'])
    if cfg['timeout'] is not None and cfg['timeout'] <= 0:
        c.err(line_of('timeout'), 'timeout must be > 0 wall seconds, got %r' % cfg['timeout'])
    if cfg['real_time_factor'] < 0:
        c.err(line_of('real_time_factor'), 'real_time_factor must be >= 0, got %r' % cfg['real_time_factor'])
    d = cfg['driver']
    if d is not None:
        if (d['launch'] is None) == (d['command'] is None):
            c.err(line_of('driver'), 'driver needs exactly one of launch: (a launch file) or command:')
        if d['launch'] is not None:
            path_field('driver.launch', 'launch file')
        if isinstance(d['command'], str):
            d['command'] = d['command'].split()
        elif d['command'] is not None:
            d['command'] = [str(x) for x in d['command']]
        if d['command'] is not None and not d['command']:
            c.err(line_of('driver.command'), 'driver.command is empty')
        if d['reply_period'] < 0:
            c.err(line_of('driver.reply_period'),
                  'driver.reply_period must be >= 0 sim seconds (0 = no lockstep), got %r' % d['reply_period'])
    s = cfg['success']
    if s is not None:
        if s['laps'] < 0:
            c.err(line_of('success.laps'), 'success.laps must be >= 0, got %r' % s['laps'])
        if s['goal'] is not None and s['goal']['radius'] <= 0:
            c.err(line_of('success.goal.radius'), 'success.goal.radius must be > 0')
    names = [m['name'] for m in cfg['metrics']]
    for n in names:
        if names.count(n) > 1:
            c.err(line_of('metrics'), 'metric name %r is used twice' % n)
    return cfg


def lockstep(cfg):
    """The simulator's lockstep parameters for a run ({} = none): at real_time_factor 0 the
    simulator waits each driver.reply_period for the driver's answer on its ready_topic, and for
    the cmd_vel node's controller commands at each of its ticks. When the driver answers on one of
    the cmd_vel node's inputs, the node's echo of each command it took (/cmd_vel_node/received) is
    a reply too: the node then has the answer before the step's /clock reaches it (its
    connections to the driver and to the simulator are not ordered)."""
    d = cfg['driver']
    if cfg['real_time_factor'] != 0 or not d or not d['ready_topic'] or not d['reply_period']:
        return {}
    replies = d['ready_topic']
    if replies in CMD_VEL_NODE_INPUTS:
        replies += ' ' + CMD_VEL_NODE_ECHO
    return {'replies': replies, 'reply_period': d['reply_period'], 'ticks': 'commands'}


# tianracer.launch's cmd_vel node (tianracer_control/launch/control.launch): its inputs, and the
# topic on which it echoes each command it took.
CMD_VEL_NODE_INPUTS = ('/cmd_vel', '/ackermann_cmd')
CMD_VEL_NODE_ECHO = '/cmd_vel_node/received'


def run_timeout(cfg):
    """Wall seconds a run may take before it is stopped as hung (start-up included)."""
    if cfg['timeout'] is not None:
        return float(cfg['timeout'])
    return 60.0 + 5.0 * float(cfg['duration'])
