"""results.csv, report.md and the pictures of a batch, from the runs' results (run.run_one)."""
import csv
import math
import os
import xml.etree.ElementTree as ET

# (column, heading, format) of the metrics summarised per matrix axis and in the runs table.
SUMMARY = [
    ('distance', 'distance m', '%.2f'),
    ('mean_speed', 'mean speed m/s', '%.3f'),
    ('max_speed', 'max speed m/s', '%.3f'),
    ('laps', 'laps', '%d'),
    ('best_lap', 'best lap s', '%.2f'),
    ('collisions', 'collisions', '%d'),
    ('min_clearance', 'min clearance m', '%.3f'),
    ('odom_drift', 'odom drift m', '%.3f'),
    ('rtf', 'RTF', '%.1f'),
]
BASE_COLUMNS = ['id', 'label', 'status', 'completed', 'reason', 'sim_time', 'wall_time',
                'run_wall_time', 'startup_wall_time', 'stop_wall_time', 'rtf', 'distance', 'mean_speed', 'max_speed',
                'laps', 'lap_times', 'best_lap', 'goal_time', 'collisions', 'first_collision_time',
                'first_collision_with', 'min_clearance', 'odom_drift', 'odom_drift_max',
                'odom_drift_pct', 'leftover_processes', 'host', 'attempts']


def flatten(run, result):
    """One CSV row: matrix values, status and metrics."""
    m = result.get('metrics') or {}
    row = {'id': result['id'], 'label': run.label, 'status': result['status'],
           'reason': result['reason'], 'wall_time': result.get('wall_time'),
           'run_wall_time': result.get('run_wall_time'),
           'startup_wall_time': result.get('startup_wall_time'),
           'stop_wall_time': result.get('stop_wall_time'),
           'leftover_processes': result.get('leftover_processes'), 'host': result.get('host'),
           'attempts': result.get('attempt', 1)}
    row['completed'] = bool(result['status'] == 'ok' and m.get('success'))
    for k in BASE_COLUMNS:
        if k in m and k not in row:
            row[k] = m[k]
    if m.get('sim_time') and result.get('run_wall_time'):
        row['rtf'] = m['sim_time'] / result['run_wall_time']
    for name in run.config['metrics']:
        row[name['name']] = m.get(name['name'])
    for k, v in run.values.items():
        row[k] = v
    if isinstance(row.get('lap_times'), list):
        row['lap_times'] = ' '.join('%.2f' % x for x in row['lap_times'])
    return row


def columns(scenario):
    user = [m['name'] for m in scenario.runs[0].config['metrics']] if scenario.runs else []
    return list(scenario.matrix) + BASE_COLUMNS + user


def write_csv(path, scenario, rows):
    cols = columns(scenario)
    with open(path, 'w', newline='') as f:
        w = csv.DictWriter(f, fieldnames=cols, extrasaction='ignore')
        w.writeheader()
        for row in rows:
            w.writerow({k: _csv_value(row.get(k)) for k in cols})


def _csv_value(v):
    if v is None:
        return ''
    if isinstance(v, float):
        return '%.6g' % v
    return v


def _num(v):
    return isinstance(v, (int, float)) and not isinstance(v, bool) and math.isfinite(v)


def _cell(v, fmt):
    if v is None:
        return '–'
    if isinstance(v, float) and fmt == '%d':
        fmt = '%.1f'
    return fmt % v


def axis_table(scenario, rows, axis, metrics):
    """Markdown table: per value of `axis`, mean / min / max of each metric over its runs."""
    head = '| %s | runs | completed | %s |' % (axis, ' | '.join(h for _, h, _ in metrics))
    lines = [head, '|' + '---|' * (3 + len(metrics))]
    for value in scenario.matrix[axis]:
        sel = [r for r in rows if r.get(axis) == value]
        cells = []
        for key, _, fmt in metrics:
            vals = [r[key] for r in sel if _num(r.get(key))]
            if not vals:
                cells.append('–')
                continue
            mean = sum(vals) / len(vals)
            if _cell(min(vals), fmt) == _cell(max(vals), fmt):
                cells.append(_cell(vals[0], fmt))
            else:
                cells.append('%s (%s – %s)' % (_cell(mean, fmt if fmt != '%d' else '%.1f'),
                                                _cell(min(vals), fmt), _cell(max(vals), fmt)))
        done = sum(1 for r in sel if r['completed'])
        lines.append('| %s | %d | %d | %s |' % (value, len(sel), done, ' | '.join(cells)))
    return '\n'.join(lines)


def write_report(path, scenario, runs, results, rows, pictures, wall, cpus_note):
    ok = [r for r in rows if r['status'] == 'ok']
    done = [r for r in rows if r['completed']]
    metrics = [m for m in SUMMARY if any(_num(r.get(m[0])) for r in rows)]
    if not any(_num(r.get('collisions')) for r in rows):
        metrics = [m for m in metrics if m[0] != 'collisions']
    user = [(m['name'], m['name'], '%.4g') for m in (runs[0].config['metrics'] if runs else [])]
    out = ['# Batch report: %s' % scenario.name, '']
    if scenario.description:
        out += [scenario.description.strip(), '']
    out += ['Scenario file: `%s`. %d runs: %d completed, %d ran but missed a success condition, '
            '%d failed to run. Wall time %.1f s (%s).' % (
                scenario.path, len(rows), len(done), len(ok) - len(done), len(rows) - len(ok), wall,
                cpus_note), '']
    collisions_measured = any(r.get('collisions') is not None for r in ok)
    if not collisions_measured and ok:
        out += ['Collisions: not measured (this simulator build publishes no contacts).', '']
    for axis in scenario.matrix:
        out += ['## By %s' % axis, '', 'Mean, and (min – max) where the runs differ.', '',
                axis_table(scenario, rows, axis, metrics + user), '']
    out += ['## Runs', '', '| run | %s | completed | reason | sim s | wall s | %s |' % (
        'values', ' | '.join(h for _, h, _ in metrics + user)),
        '|' + '---|' * (6 + len(metrics) + len(user))]
    for r in rows:
        out.append('| %s | %s | %s | %s | %s | %s | %s |' % (
            r['id'], r['label'], 'yes' if r['completed'] else '**no**', r['reason'].replace('|', '/'),
            _cell(r.get('sim_time'), '%.1f'), _cell(r.get('wall_time'), '%.1f'),
            ' | '.join(_cell(r.get(k), f) for k, _, f in metrics + user)))
    out.append('')
    if pictures:
        out += ['## Pictures', '']
        for title, name in pictures:
            out += ['**%s**' % title, '', '![%s](%s)' % (title, name), '']
    failed = [(run, res) for run, res in zip(runs, results) if res['status'] != 'ok'
              or not (res.get('metrics') or {}).get('success')]
    if failed:
        out += ['## Failed runs', '']
        for run, res in failed:
            out += ['### %s (%s)' % (res['id'], run.label), '', '%s. Logs: `%s`.' % (
                res['reason'], os.path.join(res['run_dir'], 'logs')), '']
            for name, tail in (res.get('log_tails') or {}).items():
                if tail.strip():
                    out += ['%s, last lines:' % name, '', '```', tail.rstrip(), '```', '']
    lost = [(run, res) for run, res in zip(runs, results) if res.get('lost_attempts')]
    if lost:
        out += ['## Lost and retried runs', '',
                'A Ray task lost with its worker or node is submitted again; its lost attempts '
                'gave no result (each run is counted once, by its last attempt).', '',
                '| run | lost attempt | after s | error | outcome |', '|---|---|---|---|---|']
        for run, res in lost:
            for a in res['lost_attempts']:
                retried = res.get('attempt', 1) > a['attempt']
                out.append('| %s | %d | %.1f | %s | %s |' % (
                    res['id'], a['attempt'], a['after_s'], a['error'].replace('|', '/'),
                    ('retried: attempt %d %s' % (res['attempt'], 'completed' if flatten(run, res)['completed']
                                                 else res['status'])) if retried else 'not retried'))
        out.append('')
    leftover = sum(r.get('leftover_processes') or 0 for r in rows)
    out += ['Processes left after the runs ended (killed by the runner): %d.' % leftover, '']
    with open(path, 'w') as f:
        f.write('\n'.join(out))


# --- pictures ---------------------------------------------------------------------------------
def _pose(elem):
    p = elem.find('pose') if elem is not None else None
    v = [float(x) for x in p.text.split()] if p is not None and p.text else [0.0] * 6
    return v[0], v[1], v[5]


def world_shapes(world_file):
    """(kind, x, y, yaw, a, b) of every box (a, b = half sizes) and cylinder (a = radius) seen
    from above; what the world's collision geometry covers."""
    out = []
    try:
        root = ET.parse(world_file).getroot()
    except (OSError, ET.ParseError):
        return out
    for model in root.iter('model'):
        mx, my, myaw = _pose(model)
        for link in model.findall('link'):
            lx, ly, lyaw = _pose(link)
            for col in link.findall('collision'):
                cx, cy, cyaw = _pose(col)
                c, s = math.cos(myaw), math.sin(myaw)
                x1, y1 = mx + c * lx - s * ly, my + s * lx + c * ly
                c1, s1 = math.cos(myaw + lyaw), math.sin(myaw + lyaw)
                x, y = x1 + c1 * cx - s1 * cy, y1 + s1 * cx + c1 * cy
                yaw = myaw + lyaw + cyaw
                box = col.find('geometry/box/size')
                cyl = col.find('geometry/cylinder/radius')
                if box is not None:
                    sx, sy, _ = [float(v) for v in box.text.split()]
                    out.append(('box', x, y, yaw, sx / 2, sy / 2))
                elif cyl is not None:
                    out.append(('cyl', x, y, yaw, float(cyl.text), 0.0))
    return out


def world_file_of(world):
    if world.endswith('.world') or '/' in world:
        return world
    import rospkg
    return os.path.join(rospkg.RosPack().get_path('tianracer_sim'), 'worlds', world + '.world')


def plot_paths(path, world, entries):
    """Bird's-eye view of a world with the ground-truth path of each run; entries: (label, path
    [(t, x, y)], completed)."""
    import matplotlib
    matplotlib.use('Agg')
    import matplotlib.pyplot as plt
    from matplotlib.patches import Circle, Polygon
    fig, ax = plt.subplots(figsize=(8, 6))
    try:
        shapes = world_shapes(world_file_of(world))
    except Exception:  # rospkg missing: the paths alone
        shapes = []
    for kind, x, y, yaw, a, b in shapes:
        if kind == 'box':
            c, s = math.cos(yaw), math.sin(yaw)
            pts = [(x + c * u - s * v, y + s * u + c * v) for u, v in ((-a, -b), (a, -b), (a, b), (-a, b))]
            ax.add_patch(Polygon(pts, closed=True, color='0.55'))
        else:
            ax.add_patch(Circle((x, y), a, color='0.55'))
    cmap = plt.get_cmap('tab10' if len(entries) <= 10 else 'viridis')
    for i, (label, pts, completed) in enumerate(entries):
        if not pts:
            continue
        xs, ys = [p[1] for p in pts], [p[2] for p in pts]
        colour = cmap(i % 10) if len(entries) <= 10 else cmap(i / max(1, len(entries) - 1))
        ax.plot(xs, ys, '-' if completed else '--', color=colour, lw=1.2, label=label)
        ax.plot(xs[-1:], ys[-1:], 'o' if completed else 'x', color=colour, ms=4)
    ax.set_aspect('equal')
    ax.set_xlabel('x (m)')
    ax.set_ylabel('y (m)')
    ax.set_title('%s: ground-truth paths (dashed: not completed)' % world)
    ax.grid(True, lw=0.3)
    if entries and len(entries) <= 12:
        ax.legend(fontsize=7, loc='best')
    fig.tight_layout()
    fig.savefig(path, dpi=100)
    plt.close(fig)


def plot_metric_vs(path, axis, rows, metrics):
    """One panel per metric: its value in every run against the axis' value."""
    import matplotlib
    matplotlib.use('Agg')
    import matplotlib.pyplot as plt
    metrics = [m for m in metrics if any(_num(r.get(m[0])) for r in rows)]
    if not metrics:
        return False
    values = []
    for r in rows:
        if r.get(axis) not in values:
            values.append(r.get(axis))
    numeric = all(_num(v) for v in values)
    cols = min(4, len(metrics))
    nrows = (len(metrics) + cols - 1) // cols
    fig, axes = plt.subplots(nrows, cols, figsize=(3.2 * cols, 2.8 * nrows), squeeze=False)
    for ax in axes.flat[len(metrics):]:
        ax.set_visible(False)
    for ax, (key, heading, _) in zip(axes.flat, metrics):
        xs, ys, cs = [], [], []
        for r in rows:
            if _num(r.get(key)):
                xs.append(r[axis] if numeric else values.index(r.get(axis)))
                ys.append(r[key])
                cs.append('tab:blue' if r['completed'] else 'tab:red')
        ax.scatter(xs, ys, c=cs, s=18)
        means = []
        for v in values:
            sel = [r[key] for r in rows if r.get(axis) == v and _num(r.get(key))]
            if sel:
                means.append((v if numeric else values.index(v), sum(sel) / len(sel)))
        if means:
            ax.plot([m[0] for m in means], [m[1] for m in means], '-', color='0.4', lw=1)
        if not numeric:
            ax.set_xticks(range(len(values)))
            ax.set_xticklabels([str(v) for v in values], fontsize=7)
        ax.set_xlabel(axis, fontsize=8)
        ax.set_title(heading, fontsize=9)
        ax.grid(True, lw=0.3)
    fig.suptitle('metrics against %s (red: not completed; line: mean)' % axis, fontsize=9)
    fig.tight_layout()
    fig.savefig(path, dpi=90)
    plt.close(fig)
    return True


def safe_name(s):
    return ''.join(c if c.isalnum() else '_' for c in s).strip('_')


def write_all(out_dir, scenario, runs, results, wall, cpus_note):
    rows = [flatten(run, res) for run, res in zip(runs, results)]
    write_csv(os.path.join(out_dir, 'results.csv'), scenario, rows)
    pictures = []
    worlds = []
    for run in runs:
        if run.config['world'] not in worlds:
            worlds.append(run.config['world'])
    for world in worlds:
        entries = [(run.label, (res.get('metrics') or {}).get('path') or [], row['completed'])
                   for run, res, row in zip(runs, results, rows) if run.config['world'] == world]
        name = 'paths_%s.png' % safe_name(os.path.splitext(os.path.basename(world))[0])
        plot_paths(os.path.join(out_dir, name), world, entries)
        pictures.append(("Bird's-eye paths in %s" % world, name))
    user = [(m['name'], m['name'], '%.4g') for m in (runs[0].config['metrics'] if runs else [])]
    for axis in scenario.matrix:
        name = 'metrics_vs_%s.png' % safe_name(axis)
        if plot_metric_vs(os.path.join(out_dir, name), axis, rows,
                          [m for m in SUMMARY if m[0] != 'rtf'] + user):
            pictures.append(('Metrics against %s' % axis, name))
    write_report(os.path.join(out_dir, 'report.md'), scenario, runs, results, rows, pictures, wall,
                 cpus_note)
    return rows
