#!/usr/bin/env python3
"""ros_controllers' own ROS 1 tests (noetic-devel), unchanged, against tianracer sim in place of their
hardware nodes. Run by hand from the project root after the build; not part of CI. See README.md.

  test/peers/ros_controllers/run.py --upstream GITDIR [--ref noetic-devel] [--only REGEX] [--list]
        [--ws /tmp/rcp-ws] [--sim-setup .build/devel/setup.bash] [--limit 240] [--no-build]

1. Exports every package's test/ directory from the bare git dir GITDIR (git archive) into a
   throwaway catkin workspace and checks each exported file against its git blob (sha256).
2. Reads each package's CMakeLists.txt (from git, not exported) for its tests: add_rostest_gtest /
   add_rostest are ROS-level tests; catkin_add_gtest are unit tests of the C++ classes, and a rostest
   whose gtest source includes the package's own headers instantiates the controller's C++ class
   directly: both are listed as not applicable. add_executable(... test/...) are the hardware nodes:
   each is replaced by a wrapper around standin_hw.py (the simulator on the test's own robot).
3. Writes a package.xml and a CMakeLists.txt per package that build only the test nodes, builds
   them (make -k: a node that cannot build fails only its tests), runs each applicable .test file
   with rostest (own master, a free port, wall-clock cap), prints one line per test and ends with
   'N passed, N failed, N not applicable'. Exit status 1 if any failed. Logs: WS/logs/.
"""
import argparse
import hashlib
import os
import re
import shutil
import signal
import subprocess
import sys
import time
import xmlrpc.client

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, '..', '..', '..', 'tianracer_sim', 'python'))
from tianracer_sim.master import free_port  # noqa: E402
# What the tests' nodes may include; each found package is added (a missing one only fails the
# nodes that need it).
OPTIONAL_DEPS = ['roscpp', 'rostest', 'std_msgs', 'std_srvs', 'geometry_msgs', 'nav_msgs', 'tf',
                 'control_msgs', 'controller_manager_msgs', 'rosgraph_msgs', 'actionlib',
                 'dynamic_reconfigure', 'trajectory_msgs', 'sensor_msgs', 'four_wheel_steering_msgs',
                 'ackermann_msgs', 'realtime_tools', 'urdf', 'angles']


def git(gitdir, *args, binary=False):
    out = subprocess.check_output(['git', '--git-dir=' + gitdir] + list(args))
    return out if binary else out.decode()


def cmake_calls(text, project):
    """(command, [args]) of each call in a CMakeLists text, ${PROJECT_NAME} substituted."""
    text = re.sub(r'#[^\n]*', '', text).replace('${PROJECT_NAME}', project)
    return [(m.group(1).lower(), m.group(2).split())
            for m in re.finditer(r'\b(\w+)\s*\(([^()]*)\)', text)]


def classify(gitdir, ref, pkg):
    """Tests and hardware nodes of one package, from its CMakeLists.txt."""
    cm = git(gitdir, 'show', '%s:%s/CMakeLists.txt' % (ref, pkg))
    calls = cmake_calls(cm, pkg)
    hw, gtests, tests, na = {}, {}, [], []
    for cmd, args in calls:
        if cmd == 'add_executable' and len(args) >= 2 and all(a.startswith('test/') for a in args[1:]):
            hw[args[0]] = args[1:]
        elif cmd == 'add_rostest_gtest':
            srcs = [a for a in args[2:] if a.endswith('.cpp')]
            own = [s for s in srcs if re.search(r'#include\s*[<"]%s/' % re.escape(pkg),
                                                 git(gitdir, 'show', '%s:%s/%s' % (ref, pkg, s)))]
            if own:
                na.append((pkg + '/' + args[1], 'gtest %s includes <%s/...>: it instantiates the '
                           "controller's C++ classes directly" % (args[0], pkg)))
            else:
                gtests[args[0]] = srcs
                tests.append(pkg + '/' + args[1])
        elif cmd == 'add_rostest':
            tests.append(pkg + '/' + args[0])
        elif cmd == 'catkin_add_gtest':
            na.append((pkg + '/' + args[0] + ' (gtest)',
                       'unit test of the C++ classes (catkin_add_gtest, no ROS graph)'))
    return hw, gtests, tests, na


def harness_files(pkg, gtests, test_dirs, ws_deps=()):
    """ws_deps: packages built in the same workspace (realtime_tools): declared so catkin configures
    them first and find_package finds them."""
    pkgxml = ('<?xml version="1.0"?>\n<package format="2">\n  <name>%s</name>\n  <version>0.0.0</version>\n'
              '  <description>ros_controllers test nodes only (tianracer peer harness)</description>\n'
              '  <maintainer email="none@example.com">harness</maintainer>\n  <license>BSD</license>\n'
              '  <buildtool_depend>catkin</buildtool_depend>\n%s</package>\n'
              % (pkg, ''.join('  <depend>%s</depend>\n' % d for d in ws_deps)))
    lines = ['cmake_minimum_required(VERSION 3.0.2)', 'project(%s)' % pkg,
             'find_package(catkin REQUIRED)', 'catkin_package()',
             'add_compile_options(-std=c++17 -DBOOST_BIND_GLOBAL_PLACEHOLDERS)',
             'set(deps_INCLUDE_DIRS "")', 'set(deps_LIBRARIES "")']
    for d in OPTIONAL_DEPS:
        lines += ['find_package(%s QUIET)' % d,
                  'if(%s_FOUND)' % d,
                  '  list(APPEND deps_INCLUDE_DIRS ${%s_INCLUDE_DIRS})' % d,
                  '  list(APPEND deps_LIBRARIES ${%s_LIBRARIES})' % d,
                  'else()', '  message(WARNING "harness: %s not found")' % d, 'endif()']
    lines.append('include_directories(%s ${deps_INCLUDE_DIRS})' % ' '.join(test_dirs))
    for name, srcs in sorted(gtests.items()):
        lines += ['catkin_add_executable_with_gtest(%s %s EXCLUDE_FROM_ALL)' % (name, ' '.join(srcs)),
                  'if(TARGET %s)' % name,
                  '  target_link_libraries(%s ${deps_LIBRARIES})' % name,
                  'endif()']
    return pkgxml, '\n'.join(lines) + '\n'


def sim_time_master(uri, env, log):
    """Starts roscore at uri (its processes carry env's RCP_RUN_TOKEN, so reap() ends them) and
    sets /use_sim_time on it; 0 when done, 1 (logged) when the master did not answer in 30 s."""
    subprocess.Popen(['roscore', '-p', uri.rsplit(':', 1)[1]], stdout=log, stderr=subprocess.STDOUT, env=env)
    proxy = xmlrpc.client.ServerProxy(uri)
    deadline = time.time() + 30
    while time.time() < deadline:
        try:
            if proxy.getPid('/rcp_runner')[0] == 1:
                proxy.setParam('/rcp_runner', '/use_sim_time', True)
                return 0
        except OSError:
            pass
        time.sleep(0.1)
    log.write('run.py: the master at %s did not answer in 30 s\n' % uri)
    return 1


def reap(token):
    left = []
    for pid in os.listdir('/proc'):
        if not pid.isdigit() or int(pid) == os.getpid():
            continue
        try:
            with open('/proc/%s/environ' % pid, 'rb') as f:
                if ('RCP_RUN_TOKEN=' + token).encode() in f.read().split(b'\0'):
                    left.append(int(pid))
        except OSError:
            pass
    for sig in (signal.SIGINT, signal.SIGKILL):
        for pid in left:
            try:
                os.kill(pid, sig)
            except OSError:
                pass
        if left and sig == signal.SIGINT:
            time.sleep(3)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument('--upstream', required=True, help='bare git dir of github: ros-controls/ros_controllers')
    ap.add_argument('--ref', default='noetic-devel')
    ap.add_argument('--ws', default='/tmp/rcp-ws')
    ap.add_argument('--sim-setup', default=os.path.join(os.getcwd(), '.build/devel/setup.bash'))
    ap.add_argument('--only', default='', help='only tests whose path matches this regex')
    ap.add_argument('--list', action='store_true', help='list the tests and their class, run nothing')
    ap.add_argument('--limit', type=int, default=240, help='wall-clock cap per test file, seconds')
    ap.add_argument('--no-build', action='store_true')
    ap.add_argument('--realtime-tools', metavar='GITDIR',
                    help='bare git dir of github: ros-controls/realtime_tools (Debian 12 has none; the '
                         "joint_trajectory_controller test nodes include its headers): built in WS's own workspace")
    ap.add_argument('--realtime-tools-ref', default='noetic-devel')
    ap.add_argument('--rrbot-gravity', action='store_true',
                    help='simulate the rrbot fixtures (joint_trajectory_controller) with gravity; by default '
                         'their links are weightless, as the upstream nodes, which simulate no dynamics')
    a = ap.parse_args()

    up = os.path.abspath(a.upstream)
    commit = git(up, 'rev-parse', a.ref + '^{commit}').strip()
    files = git(up, 'ls-tree', '-r', '--name-only', commit).split('\n')
    pkgs = sorted({f.split('/')[0] for f in files if '/test/' in f and f.count('/') >= 2
                   and f.split('/')[0] + '/CMakeLists.txt' in files})
    plan = {}
    for p in pkgs:
        plan[p] = classify(up, commit, p)
    sel = lambda t: re.search(a.only, t) if a.only else True
    tests = [t for p in pkgs for t in plan[p][2] if sel(t)]
    na = [x for p in pkgs for x in plan[p][3] if sel(x[0])]
    if a.list:
        for p in pkgs:
            print('%s: hardware nodes %s' % (p, ' '.join(sorted(plan[p][0])) or '-'))
        for t in tests:
            print('RUN  ' + t)
        for t, why in na:
            print('N/A  %s  (%s)' % (t, why))
        return 0

    ws = a.ws
    for d in ('src', 'logs', 'test_results'):
        shutil.rmtree(os.path.join(ws, d), ignore_errors=True)
    os.makedirs(os.path.join(ws, 'src'))
    os.makedirs(os.path.join(ws, 'logs', 'ros'))
    os.makedirs(os.path.join(ws, 'bin'), exist_ok=True)
    if not os.path.exists(os.path.join(ws, 'bin', 'python')):
        os.symlink('/usr/bin/python3', os.path.join(ws, 'bin', 'python'))
    # include/ too: some test helpers (joint_trajectory_controller/test/test_common.h) include
    # upstream's header-only types; the controllers' sources are not exported.
    incs = [p + '/include' for p in pkgs if any(f.startswith(p + '/include/') for f in files)]
    archive = subprocess.Popen(['git', '--git-dir=' + up, 'archive', commit] + [p + '/test' for p in pkgs] + incs,
                               stdout=subprocess.PIPE)
    subprocess.check_call(['tar', '-x', '-C', os.path.join(ws, 'src')], stdin=archive.stdout)
    if archive.wait():
        sys.exit('git archive failed')
    # Byte for byte: every exported file against its blob.
    exported = [f for f in files if any(f.startswith(p + '/test/') or f.startswith(p + '/include/')
                                        for p in pkgs)]
    bad = []
    for f in exported:
        blob = git(up, 'cat-file', 'blob', '%s:%s' % (commit, f), binary=True)
        with open(os.path.join(ws, 'src', f), 'rb') as fh:
            if hashlib.sha256(fh.read()).digest() != hashlib.sha256(blob).digest():
                bad.append(f)
    if bad:
        sys.exit('exported files differ from upstream: ' + ' '.join(bad))
    print('==> %s %s (%s): %d test files exported, sha256 equal to their git blobs'
          % (up, a.ref, commit[:12], len(exported)))
    ws_deps = []
    if a.realtime_tools:
        # A test peer like the test nodes: upstream's package as it is, built in this throwaway
        # workspace only (its library and headers), never installed nor committed.
        rt = os.path.abspath(a.realtime_tools)
        rt_commit = git(rt, 'rev-parse', a.realtime_tools_ref + '^{commit}').strip()
        dest = os.path.join(ws, 'src', 'realtime_tools')
        os.makedirs(dest)
        archive = subprocess.Popen(['git', '--git-dir=' + rt, 'archive', rt_commit], stdout=subprocess.PIPE)
        subprocess.check_call(['tar', '-x', '-C', dest], stdin=archive.stdout)
        if archive.wait():
            sys.exit('git archive of realtime_tools failed')
        ws_deps.append('realtime_tools')
        print('==> realtime_tools %s (%s) from %s, built in %s' % (a.realtime_tools_ref, rt_commit[:12], rt, ws))

    for p in pkgs:
        hw, gtests, _, _ = plan[p]
        test_dirs = sorted({os.path.dirname(f)[len(p) + 1:] for f in exported
                            if f.startswith(p + '/test/') and f.endswith('.h')} | {'test'})
        if os.path.isdir(os.path.join(ws, 'src', p, 'include')):
            test_dirs.append('include')
        pkgxml, cml = harness_files(p, gtests, test_dirs, ws_deps)
        for name, text in (('package.xml', pkgxml), ('CMakeLists.txt', cml)):
            path = os.path.join(ws, 'src', p, name)
            assert not os.path.exists(path)
            with open(path, 'w') as fh:
                fh.write(text)

    env = dict(os.environ)
    env['PATH'] = os.path.join(ws, 'bin') + ':/usr/bin:' + env.get('PATH', '')
    env['ROS_HOSTNAME'] = 'localhost'
    env.pop('ROS_IP', None)

    def sourced(setup):
        out = subprocess.check_output(['bash', '-c', 'source "%s" >/dev/null && env -0' % setup], env=env)
        return dict(kv.split('=', 1) for kv in out.decode().split('\0') if '=' in kv)

    if not os.path.isfile(a.sim_setup):
        sys.exit('no tianracer sim devel space at %s (--sim-setup)' % a.sim_setup)
    env = sourced(a.sim_setup)
    build_log = os.path.join(ws, 'logs', 'build.log')
    if not a.no_build:
        print('==> building the test nodes (log %s)' % build_log)
        with open(build_log, 'w') as log:
            rc = subprocess.call(['catkin_make', '-C', ws, '-DPYTHON_EXECUTABLE=/usr/bin/python3',
                                  '-DCATKIN_ENABLE_TESTING=ON', 'cmake_check_build_system'],
                                 stdout=log, stderr=subprocess.STDOUT, env=env)
            if rc == 0:
                targets = [n for p in pkgs for n in plan[p][1] if any(sel(t) for t in plan[p][2])]
                # The test nodes link realtime_tools' library by its devel path, not its target.
                targets = ws_deps + targets
                subprocess.call(['make', '-C', os.path.join(ws, 'build'), '-k', '-j2'] + targets,
                                stdout=log, stderr=subprocess.STDOUT, env=env)
        if rc:
            sys.exit('the harness workspace did not configure (log %s)' % build_log)
    env = sourced(os.path.join(ws, 'devel', 'setup.bash'))
    # The stand-ins, where rostest looks for the hardware nodes: devel/lib/PKG/NODE.
    for p in pkgs:
        for node in plan[p][0]:
            d = os.path.join(ws, 'devel', 'lib', p)
            os.makedirs(d, exist_ok=True)
            path = os.path.join(d, node)
            with open(path, 'w') as fh:
                fh.write('#!/bin/sh\n# stand-in for upstream %s/%s: tianracer sim\nexec /usr/bin/python3 "%s" %s "$@"\n'
                         % (p, ' '.join(plan[p][0][node]), os.path.join(HERE, 'standin_hw.py'), node))
            os.chmod(path, 0o755)
    env['RCP_RRBOT_GRAVITY'] = 'on' if a.rrbot_gravity else 'off'
    env['ROS_HOME'] = os.path.join(ws, 'ros_home')
    env['ROS_LOG_DIR'] = os.path.join(ws, 'logs', 'ros')

    passed = failed = 0
    rows = []
    for t in tests:
        name = os.path.splitext(os.path.basename(t))[0]
        log = os.path.join(ws, 'logs', name + '.log')
        token = '%d-%s' % (os.getpid(), name)
        master = 'http://localhost:%d' % free_port()
        e = dict(env, RCP_RUN_TOKEN=token, ROS_MASTER_URI=master)
        start = time.time()
        with open(log, 'w') as fh:
            try:
                # The test's nodes on the simulator's clock: a master with /use_sim_time set before
                # rostest starts them, as a simulator's launch sets it before its users' nodes
                # (roscpp and rospy read it once, at start; the simulator sets it too, but only once
                # it runs, after the test node may have started on wall time).
                rc = sim_time_master(master, e, fh)
                if rc == 0:
                    rc = subprocess.call(['timeout', '--signal=INT', '--kill-after=30', str(a.limit),
                                          'rostest', '--reuse-master',
                                          '--results-base-dir=' + os.path.join(ws, 'test_results'),
                                          os.path.join(ws, 'src', t)], stdout=fh, stderr=subprocess.STDOUT, env=e)
            finally:
                reap(token)
        secs = time.time() - start
        text = open(log, errors='replace').read()
        counts = ' '.join(re.findall(r'^ \* ((?:TESTS|ERRORS|FAILURES): \d+)', text, re.M))
        if rc == 0:
            verdict = 'PASS'
            passed += 1
        else:
            verdict = 'FAIL'
            failed += 1
            if rc == 124:
                counts = 'wall-clock cap %ds; %s' % (a.limit, counts)
        row = '%-4s %5.0fs  %-100s %s' % (verdict, secs, t, counts or 'no SUMMARY (%s)' % log)
        print(row, flush=True)
        rows.append(row)
    for t, why in na:
        print('N/A          %-100s %s' % (t, why))
    print('%d passed, %d failed, %d not applicable' % (passed, failed, len(na)))
    return 1 if failed else 0


if __name__ == '__main__':
    sys.exit(main())
