"""Scenario batches on Ray: `rosrun tianracer_bringup batch scenarios.yaml --out results/`.

Every run of the scenario's matrix is one Ray task that starts its own ROS master, simulator,
recorder and driver (run.run_one). Without --address a local Ray is started with --cpus CPUs
(default: all of this machine's); with --address (auto, host:port, ray://host:port) the runs go to
an existing Ray cluster, each node of which must have this workspace built and sourced when its
`ray start` was run. Results come back to this process, which writes results.csv, report.md and
the pictures into --out.

A run whose Ray task is lost (its worker or its node died: NodeDiedError, WorkerCrashedError, ...)
is submitted again, up to --retries times, into runs/run_NNN/retry_K; the result says which attempt
it is and what happened to the lost ones (result.json `lost_attempts`, the CSV's `attempts`, the
report's "Lost and retried runs"). Each run has exactly one result: a lost attempt never returns one.

Exit code: 0 when every run completed (ran and met its success conditions), 1 when some did not,
2 when the scenario file is invalid (nothing is started then).
"""
import argparse
import json
import logging
import os
import shutil
import socket
import sys
import tempfile
import time

from tianracer_bringup import scenario as scenario_mod


def _remote_run(run_id, cfg, run_dir, attempt=1):
    from tianracer_bringup.run import run_one
    try:
        os.makedirs(run_dir, exist_ok=True)
    except OSError:
        # Another host of a cluster: the driver's output folder is not here.
        run_dir = tempfile.mkdtemp(prefix='tianracer_batch_%s_' % run_id)
    result = run_one(run_id, cfg, run_dir)
    result['attempt'] = attempt
    try:
        import ray
        result['node'] = ray.get_runtime_context().get_node_id()
    except Exception:  # not in a Ray worker
        pass
    return result


# Ray's errors for a task whose worker or node was lost (the task's own code did not fail): such a
# run is submitted again. Names, as some are missing from older Rays.
LOST_TASK_ERRORS = ('NodeDiedError', 'WorkerCrashedError', 'ObjectLostError', 'OwnerDiedError',
                    'LocalRayletDiedError', 'ObjectFetchTimedOutError', 'ObjectReconstructionFailedError')


def lost_task_error(exc):
    """True when `exc` (from ray.get) says the task's worker or node was lost."""
    import ray.exceptions
    kinds = tuple(k for k in (getattr(ray.exceptions, n, None) for n in LOST_TASK_ERRORS) if k)
    return isinstance(exc, kinds)


def _first_line(exc):
    """The error's class and first two sentences (Ray's node errors: what, then the node's IP and
    ID; the advice after them is left out)."""
    text = str(exc).strip().splitlines()[0] if str(exc).strip() else ''
    return '%s: %s' % (type(exc).__name__, '. '.join(text.split('. ')[:2]).rstrip('.'))


def parse_args(argv):
    ap = argparse.ArgumentParser(prog='batch', description=__doc__.split('\n')[0])
    ap.add_argument('scenario', help='scenario YAML file')
    ap.add_argument('--out', default='results', help='output folder (default: results)')
    ap.add_argument('--limit', type=int, default=None, metavar='N', help='run only the first N runs')
    ap.add_argument('--duration', type=float, default=None, metavar='S',
                    help="override every run's sim duration (seconds)")
    ap.add_argument('--dry-run', action='store_true', help='print the expanded runs and stop')
    ap.add_argument('--address', default=None,
                    help='an existing Ray cluster: auto, host:port or ray://host:port')
    ap.add_argument('--cpus', type=float, default=None,
                    help='CPUs of the local Ray (default: all of this machine)')
    ap.add_argument('--cpus-per-run', type=float, default=1.0,
                    help='CPUs Ray reserves for each run (default 1)')
    ap.add_argument('--retries', type=int, default=2, metavar='N',
                    help='times a run whose Ray worker or node was lost is submitted again (default 2)')
    ap.add_argument('--no-progress', action='store_true', help='no progress bar')
    args = ap.parse_args(argv)
    if args.limit is not None and args.limit < 1:
        ap.error('--limit must be >= 1')
    if args.duration is not None and args.duration <= 0:
        ap.error('--duration must be > 0')
    if args.retries < 0:
        ap.error('--retries must be >= 0')
    if args.cpus_per_run <= 0:
        ap.error('--cpus-per-run must be > 0')
    return args


def select_runs(sc, args):
    runs = sc.runs[:args.limit] if args.limit else list(sc.runs)
    if args.duration is not None:
        for run in runs:
            run.config['duration'] = args.duration
    return runs


def print_runs(sc, runs, out=sys.stdout):
    out.write('%s: %d run(s) of %d\n' % (sc.name, len(runs), len(sc.runs)))
    for run in runs:
        c = run.config
        drv = c['driver']
        what = ('launch %s' % drv['launch']) if drv and drv['launch'] else \
            ('command %s' % ' '.join(drv['command'])) if drv else 'no driver'
        if drv and drv['args']:
            prefix = '' if drv['launch'] else '_'
            what += ' ' + ' '.join('%s%s:=%s' % (prefix, k, v) for k, v in drv['args'].items())
        out.write('  %s  %-40s world %s, %g s, seed %d, timeout %.0f s, %s\n' % (
            run.id, run.label, os.path.basename(c['world']), c['duration'], c['seed'],
            scenario_mod.run_timeout(c), what))


def main(argv=None):
    args = parse_args(sys.argv[1:] if argv is None else argv)
    try:
        sc = scenario_mod.load(args.scenario)
    except scenario_mod.ScenarioError as e:
        sys.stderr.write('ERROR [batch] invalid scenario file:\n')
        for p in e.problems:
            sys.stderr.write('  %s\n' % p)
        return 2
    runs = select_runs(sc, args)
    if args.dry_run:
        print_runs(sc, runs)
        return 0

    out = os.path.abspath(args.out)
    os.makedirs(os.path.join(out, 'runs'), exist_ok=True)
    shutil.copy(args.scenario, os.path.join(out, 'scenario.yaml'))

    import ray
    os.environ.setdefault('RAY_AUTH_MODE', 'disabled')  # a private local Ray; clusters set theirs
    wall0 = time.time()
    if args.address:
        ray.init(address=args.address, logging_level=logging.WARNING, log_to_driver=False)
    else:
        # address='local': always a Ray of its own, never one left running on this machine
        # (ray.init() with no address joins an existing local cluster, refusing num_cpus).
        ray.init(address='local', num_cpus=args.cpus or os.cpu_count(), include_dashboard=False,
                 logging_level=logging.WARNING, log_to_driver=False)
    try:
        cpus = ray.cluster_resources().get('CPU', 1.0)
        slots = max(1, int(cpus // args.cpus_per_run))
        note = '%s, %g CPUs, %g per run, up to %d at a time' % (
            'Ray cluster %s' % args.address if args.address else 'local Ray on %s' % socket.gethostname(),
            cpus, args.cpus_per_run, slots)
        print('==> [batch] %s: %d run(s); %s (Ray up in %.1f s)' % (
            sc.name, len(runs), note, time.time() - wall0), flush=True)
        runs_wall0 = time.time()
        # No retries by Ray: a lost run is submitted again here, so that its result says so.
        task = ray.remote(num_cpus=args.cpus_per_run, max_retries=0)(_remote_run)
        refs = {}  # ObjectRef -> (run, attempt)
        lost = {run.id: [] for run in runs}  # lost attempts of each run

        def submit(run):
            attempt = len(lost[run.id]) + 1
            run_dir = os.path.join(out, 'runs', run.id)
            if attempt > 1:
                run_dir = os.path.join(run_dir, 'retry_%d' % attempt)
            ref = task.remote(run.id, run.config, run_dir, attempt)
            refs[ref] = (run, attempt)
            return ref

        pending = [submit(run) for run in runs]
        results = {}
        failed = 0
        bar = None
        if not args.no_progress:
            from tqdm import tqdm
            bar = tqdm(total=len(runs), unit='run', dynamic_ncols=True, file=sys.stderr)
        try:
            while pending:
                ready, pending = ray.wait(pending, num_returns=1, timeout=1.0)
                for ref in ready:
                    run, attempt = refs.pop(ref)
                    try:
                        res = ray.get(ref)
                    except Exception as e:  # the task itself died (worker lost, node lost)
                        if lost_task_error(e):
                            lost[run.id].append({'attempt': attempt, 'error': _first_line(e),
                                                 'after_s': round(time.time() - runs_wall0, 1)})
                            if attempt <= args.retries:
                                pending.append(submit(run))
                                print('    %s %s: attempt %d lost (%s); submitted again' % (
                                    run.id, run.label, attempt, _first_line(e)), flush=True)
                                continue
                            reason = 'Ray task lost %d time(s), not retried again: %s' % (
                                attempt, _first_line(e))
                        else:
                            reason = 'Ray task failed: %s' % e
                        res = {'id': run.id, 'status': 'failed', 'reason': reason, 'metrics': None,
                               'attempt': attempt, 'run_dir': os.path.join(out, 'runs', run.id)}
                    if run.id in results:  # cannot happen: one live attempt per run at a time
                        raise RuntimeError('%s: a second result (attempt %d)' % (run.id, attempt))
                    res['lost_attempts'] = lost[run.id]
                    results[run.id] = res
                    if res['status'] != 'ok' or not (res.get('metrics') or {}).get('success'):
                        failed += 1
                    if bar is None:
                        print('    %s %s: %s (%s)%s' % (
                            run.id, run.label, res['status'], res['reason'],
                            ', attempt %d' % attempt if attempt > 1 else ''), flush=True)
                    else:
                        bar.update(1)
                if bar is not None:
                    bar.set_postfix_str('running %d, failed %d' % (min(len(pending), slots), failed),
                                        refresh=False)
                    bar.refresh()
        except KeyboardInterrupt:
            # Cancel without force: each run's own clean-up stops its processes.
            for ref in pending:
                ray.cancel(ref, force=False)
            raise
        finally:
            if bar is not None:
                bar.close()
    finally:
        ray.shutdown()
    wall = time.time() - wall0
    runs_wall = time.time() - runs_wall0
    ordered = [results[run.id] for run in runs]
    for res in ordered:
        path = os.path.join(out, 'runs', res['id'])
        os.makedirs(path, exist_ok=True)
        with open(os.path.join(path, 'result.json'), 'w') as f:
            json.dump(res, f, indent=1)
    from tianracer_bringup import report
    rows = report.write_all(out, sc, runs, ordered, wall, note)
    done = sum(1 for r in rows if r['completed'])
    sim = sum(r.get('sim_time') or 0.0 for r in rows)
    print('==> [batch] %d of %d run(s) completed in %.1f s wall (runs %.1f s: %.2f sim s per wall s); '
          'wrote %s' % (done, len(rows), wall, runs_wall, sim / max(runs_wall, 1e-9), ', '.join(
              sorted(n for n in os.listdir(out) if n.endswith(('.csv', '.md', '.png'))))))
    for r in rows:
        if not r['completed']:
            print('    %s (%s): %s' % (r['id'], r['label'], r['reason']))
    for res in ordered:
        for a in res['lost_attempts']:
            print('    %s: attempt %d lost after %.1f s (%s); %s' % (
                res['id'], a['attempt'], a['after_s'], a['error'],
                'the run was submitted again' if res.get('attempt', 1) > a['attempt'] else 'given up'))
    return 0 if done == len(rows) else 1
