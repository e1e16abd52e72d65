"""A cache of xacro's output for the xacro stand-in (./xacro), so that a second launch of the
same model skips xacro (0.3-0.5 s of a fresh Python, roslaunch's modules and the expansion).

What an expansion depends on, and what the cache checks before it answers:
- the command: the arguments as given (file and name:=value), the working directory, the
  Python and the xacro module that expanded it (path, size, mtime), this stand-in's own files;
- the contents of every file xacro read: the input, its includes and load_yaml files (the
  sha256 of each, read again on every look-up);
- the environment it consulted: each $(env X) / $(optenv X) by name and value, and
  ROS_PACKAGE_PATH / CMAKE_PREFIX_PATH, where $(find pkg) looks; each package $(find) gave
  must still be there (its package.xml).
Anything else misses: an entry is used only when all of it matches, and a changed file, arg or
variable gives a new expansion (which then replaces the entry). Only the plain form is cached
(`xacro [--inorder|-i] FILE [name:=value ...]`, output on stdout); any other option runs xacro
as it is. Left out: an include by glob pattern (`<xacro:include filename="*.xacro"/>`) that
would match a file created after the expansion.

The cache lives in $ROS_HOME/xacro_cache (~/.ros/xacro_cache). TIANRACER_XACRO_CACHE=off
disables it; TIANRACER_XACRO_CACHE=/some/dir puts it there. A cache file that cannot be read
or does not have the expected form is reported on stderr and replaced.
"""
import hashlib
import json
import os
import sys

FORMAT = 1
MAX_ENTRIES = 256
# Where $(find) looks (rospkg: ROS_PACKAGE_PATH; roslaunch's executables: CMAKE_PREFIX_PATH).
KEY_ENV = ('ROS_PACKAGE_PATH', 'CMAKE_PREFIX_PATH')
_HERE = os.path.dirname(os.path.realpath(__file__))


def cache_dir(environ=None):
    """The cache folder, or None when TIANRACER_XACRO_CACHE=off (or 0, no, false)."""
    environ = os.environ if environ is None else environ
    setting = environ.get('TIANRACER_XACRO_CACHE', '').strip()
    if setting.lower() in ('off', '0', 'no', 'false'):
        return None
    if setting:
        return setting
    ros_home = environ.get('ROS_HOME') or os.path.join(os.path.expanduser('~'), '.ros')
    return os.path.join(ros_home, 'xacro_cache')


def cacheable(argv):
    """The input file when argv is the plain form (FILE, name:=value, --inorder/-i), else None."""
    files = []
    for a in argv:
        if a in ('--inorder', '-i'):
            continue
        if ':=' in a and not a.startswith('-'):
            continue
        if a.startswith('-'):
            return None
        files.append(a)
    return files[0] if len(files) == 1 else None


def _sha256_file(path):
    with open(path, 'rb') as f:
        return hashlib.sha256(f.read()).hexdigest()


def _stamp(path):
    try:
        st = os.stat(path)
        return [path, st.st_size, st.st_mtime_ns]
    except OSError:
        return [path, None, None]


def _xacro_module_file(here):
    """The xacro package's __init__.py as `import xacro` in the stand-in finds it (not ./xacro.py)."""
    for p in sys.path:
        if os.path.realpath(p or os.curdir) == here:
            continue
        candidate = os.path.join(p or os.curdir, 'xacro', '__init__.py')
        if os.path.isfile(candidate):
            return os.path.abspath(candidate)
    return ''


class Cache(object):
    def __init__(self, directory, argv, environ=None, cwd=None, err=None):
        self.directory = directory
        self.argv = list(argv)
        self.environ = os.environ if environ is None else environ
        self.cwd = os.getcwd() if cwd is None else cwd
        self.err = err or sys.stderr
        key = {
            'format': FORMAT,
            'argv': self.argv,
            'cwd': self.cwd,
            'python': [sys.executable, list(sys.version_info[:3])],
            'xacro': _stamp(_xacro_module_file(_HERE)),
            'stand_in': [_stamp(os.path.join(_HERE, n)) for n in ('xacro', 'noetic_symbols.py',
                                                                 'xacro_cache.py')],
            'env': {name: self.environ.get(name) for name in KEY_ENV},
        }
        digest = hashlib.sha256(json.dumps(key, sort_keys=True).encode()).hexdigest()
        self.path = os.path.join(directory, digest + '.json')

    def _note(self, text):
        self.err.write('xacro: cache %s: %s\n' % (self.path, text))

    def lookup(self):
        """(stdout, stderr) of the cached expansion when everything it read is unchanged; else None."""
        try:
            with open(self.path, 'rb') as f:
                raw = f.read()
        except FileNotFoundError:
            return None
        except OSError as e:
            self._note('cannot be read (%s); expanding again' % e.strerror)
            return None
        try:
            entry = json.loads(raw.decode('utf-8'))
            if not isinstance(entry, dict) or entry.get('format') != FORMAT:
                raise ValueError('not a format %d cache entry' % FORMAT)
            files, env, packages = entry['files'], entry['env'], entry['packages']
            out, err = entry['stdout'], entry['stderr']
            if not (isinstance(files, dict) and isinstance(env, dict) and isinstance(packages, dict)
                    and isinstance(out, str) and isinstance(err, str) and files):
                raise ValueError('fields of the wrong type')
        except (ValueError, KeyError, UnicodeDecodeError) as e:
            self._note('is not a valid cache entry (%s); expanding again' % e)
            return None
        for path, digest in files.items():
            try:
                if _sha256_file(path) != digest:
                    return None
            except OSError:
                return None
        for name, value in env.items():
            if self.environ.get(name) != value:
                return None
        for path in packages.values():
            if not os.path.isfile(os.path.join(path, 'package.xml')):
                return None
        return out, err

    def store(self, files, env, packages, out, err):
        entry = {'format': FORMAT, 'argv': self.argv,
                 'files': {p: _sha256_file(p) for p in sorted(set(files))},
                 'env': env, 'packages': packages, 'stdout': out, 'stderr': err}
        try:
            os.makedirs(self.directory, exist_ok=True)
            tmp = '%s.%d.tmp' % (self.path, os.getpid())
            with open(tmp, 'w') as f:
                json.dump(entry, f)
            os.replace(tmp, self.path)
            self._prune()
        except OSError as e:
            self._note('cannot be written (%s); the expansion is not cached' % e.strerror)

    def _prune(self):
        names = [n for n in os.listdir(self.directory) if n.endswith('.json')]
        if len(names) <= MAX_ENTRIES:
            return
        paths = sorted((os.path.join(self.directory, n) for n in names), key=os.path.getmtime)
        for p in paths[:len(paths) - MAX_ENTRIES]:
            try:
                os.remove(p)
            except OSError:
                pass


class _Tee(object):
    """Writes through to a stream and keeps a copy."""

    def __init__(self, stream):
        self.stream = stream
        self.parts = []

    def write(self, text):
        self.parts.append(text)
        return self.stream.write(text)

    def text(self):
        return ''.join(self.parts)

    def __getattr__(self, name):
        return getattr(self.stream, name)


def expand_and_store(cache, xacro, input_file):
    """Runs xacro.main() with what it reads recorded; stores its output when it succeeds.
    Returns xacro.main()'s exit status."""
    from roslaunch import substitution_args as sa
    env_used, packages = {}, {}
    eval_env, eval_optenv, get_rospack = sa._eval_env, sa._eval_optenv, sa._get_rospack

    def record_env(name, *args, **kwargs):
        env_used[name] = os.environ.get(name)
        return eval_env(name, *args, **kwargs)

    def record_optenv(name, *args, **kwargs):
        env_used[name] = os.environ.get(name)
        return eval_optenv(name, *args, **kwargs)

    class RecordingRosPack(object):
        def __init__(self, rp):
            self._rp = rp

        def get_path(self, name):
            path = self._rp.get_path(name)
            packages[name] = path
            return path

        def __getattr__(self, name):
            return getattr(self._rp, name)

    sa._eval_env, sa._eval_optenv = record_env, record_optenv
    eval_dict = dict(sa._eval_dict)  # $(eval env('X')) and optenv() look them up here
    sa._eval_dict.update(env=record_env, optenv=record_optenv)
    sa._get_rospack = lambda: RecordingRosPack(get_rospack())
    out, err = _Tee(sys.stdout), _Tee(sys.stderr)
    sys.stdout, sys.stderr = out, err
    try:
        status = xacro.main()
    except SystemExit as e:
        status = e.code
    finally:
        sys.stdout, sys.stderr = out.stream, err.stream
        sa._eval_env, sa._eval_optenv, sa._get_rospack = eval_env, eval_optenv, get_rospack
        sa._eval_dict.update(env=eval_dict['env'], optenv=eval_dict['optenv'])
    if status in (None, 0):
        files = [os.path.abspath(input_file)] + [os.path.abspath(p) for p in xacro.all_includes]
        sys.stdout.flush()
        cache.store(files, env_used, packages, out.text(), err.text())
    return status
