"""Per-run metrics from the raw files of a run (the recorder's CSVs and the runner's
result.json) and their aggregation per setting: mean, median and the thesis's trimmed mean
('the middle runs'). Pure python; `scripts/experiment report` recomputes everything from the
raw directories alone."""

import csv
import json
import math
import os
import re

from swarm_transport import core_metrics
from swarm_transport import experiment_presets as presets

SAMPLE_PERIOD_S = 10.0          # the recorder's swarm count period (thesis 7.2: every 10 s)
PATH_STEP_PERCENT = 5           # leader track: a point every 5 % of the path
SUMMARY_COLUMNS = ['setting', 'metric', 'mean', 'median', 'trimmed_mean', 'runs']


def read_csv(path):
    if not os.path.isfile(path):
        return []
    with open(path, newline='') as f:
        return [row for row in csv.DictReader(f)]


def number(text):
    """A CSV cell as a float, None when empty or not a finite number."""
    if text is None:
        return None
    text = str(text).strip()
    if not text:
        return None
    try:
        v = float(text)
    except ValueError:
        return None
    return v if math.isfinite(v) else None


def run_dirs(setting_dir):
    """run_<k> directories of a setting, by k."""
    found = []
    if os.path.isdir(setting_dir):
        for name in os.listdir(setting_dir):
            m = re.match(r'^run_(\d+)$', name)
            if m and os.path.isdir(os.path.join(setting_dir, name)):
                found.append((int(m.group(1)), os.path.join(setting_dir, name)))
    return sorted(found)


def run_metrics(kind, run_dir):
    """(metrics, series, info) of one run. metrics: name -> float or None (not applicable,
    e.g. an aborted transport has no transport_ticks); series: name -> {x: value};
    info: result.json plus warnings. Returns None when the run did not complete (no usable
    result: an infrastructure failure, not an experimental outcome)."""
    try:
        with open(os.path.join(run_dir, 'result.json')) as f:
            info = json.load(f)
    except (OSError, ValueError):
        return None
    if info.get('status') != 'ok':
        return None
    info['warnings'] = []
    if kind == 'flocking':
        metrics, series = _flocking(run_dir, info)
    else:
        metrics, series = _mission(kind, run_dir, info)
    if metrics is None:
        return None
    # The swarm's spread at the end (SPEC 9.5), from the recorder's run row.
    run = read_csv(os.path.join(run_dir, 'run.csv'))
    for name in presets.DISPERSION_METRICS:
        metrics[name] = number(run[-1].get(name)) if run else None
    return metrics, series, info


def _flocking(run_dir, info):
    rows = read_csv(os.path.join(run_dir, 'swarm_count.csv'))
    samples = [(number(r.get('sim_time_s')), number(r.get('swarm_count')),
                number(r.get('largest_swarm'))) for r in rows]
    samples = [s for s in samples if s[0] is not None and s[1] is not None]
    if not samples:
        info['warnings'].append('no swarm_count.csv samples')
        return None, None
    counts = [c for _, c, _ in samples]
    metrics = {
        'initial_swarm_count': counts[0],
        'final_swarm_count': counts[-1],
        'mean_swarm_count': sum(counts) / len(counts),
        'swarm_count_slope_per_h': _slope([t / 3600.0 for t, _, _ in samples], counts),
        'final_largest_swarm': samples[-1][2],
    }
    # The samples on the grid t = 0, 10, 20, ... s: the first sample at or after each time.
    series = {}
    last_t = samples[-1][0]
    k, i = 0, 0
    while k * SAMPLE_PERIOD_S <= last_t + 1e-6:
        t = k * SAMPLE_PERIOD_S
        while i < len(samples) and samples[i][0] < t - 1e-6:
            i += 1
        if i < len(samples) and samples[i][0] < t + SAMPLE_PERIOD_S - 1e-6:
            series[int(round(t))] = samples[i][1]
        k += 1
    run = read_csv(os.path.join(run_dir, 'run.csv'))
    if run:
        recorded = number(run[-1].get('mean_swarm_count'))
        if recorded is not None and abs(recorded - metrics['mean_swarm_count']) > 1e-3:
            info['warnings'].append('run.csv mean_swarm_count %.4f != %.4f from swarm_count.csv'
                                    % (recorded, metrics['mean_swarm_count']))
    return metrics, {'swarm_count_t': series}


def _slope(xs, ys):
    n = len(xs)
    if n < 2:
        return 0.0
    mx, my = sum(xs) / n, sum(ys) / n
    sxx = sum((x - mx) ** 2 for x in xs)
    if sxx <= 0:
        return 0.0
    return sum((x - mx) * (y - my) for x, y in zip(xs, ys)) / sxx


def _mission(kind, run_dir, info):
    names = presets.METRICS[kind] + presets.OPTIONAL_METRICS.get(kind, [])
    metrics = {name: None for name in names}
    end = info.get('end')
    mid = str(info.get('mission_id', ''))
    rows = [r for r in read_csv(os.path.join(run_dir, 'missions.csv'))
            if not mid or (r.get('mission_id') or '').strip() == mid]
    row = rows[-1] if rows else None
    state = (row.get('final_state') or '').strip() if row else ''
    done = end == 'DONE' and state == 'DONE'
    if end == 'DONE' and row is None:
        info['warnings'].append('mission DONE but no recorder row in missions.csv')
    metrics['aborted'] = 0.0 if done else 1.0
    series = {}
    if done:
        if kind == 'leader':
            for name in ('path_fraction_attached', 'leader_swarm_at_arrival', 'leader_waits'):
                metrics[name] = number(row.get(name))
            # The runner submits before tick 0 and a leader-only mission starts its transport
            # at the first tick: the leader's time to its goal is the DONE tick.
            metrics['leader_ticks'] = number(row.get('done_tick'))
        else:
            for name in ('transport_ticks', 'slip_per_robot_m', 'distance_per_robot_m',
                         'leader_waits', 'object_error_m', 'leader_contact',
                         'loading_nn_cv'):
                metrics[name] = number(row.get(name))
            start, stop = number(row.get('gathering_tick')), number(row.get('loading_tick'))
            metrics['gathering_ticks'] = (stop - start if start is not None and
                                          stop is not None else None)
            queued, done_tick = number(row.get('queued_tick')), number(row.get('done_tick'))
            metrics['mission_ticks'] = (done_tick - queued if queued is not None and
                                        done_tick is not None else None)
            # Counted by the batch engine only (result.json); launched runs leave it empty.
            metrics['gathering_swerves'] = number(info.get('gathering_swerves'))
            # Also the batch engine's (issue 27); the plan metrics only with a planner.
            for name in ['gathering_interference', 'plan_unstable_pct', 'plan_cost_ratio',
                         'plan_cost_ratio_max', 'leaders_behind'] + presets.PLAN_ARRIVAL_METRICS:
                if name in metrics:
                    metrics[name] = number(info.get(name))
            if 'first_leader_waits' in metrics:
                metrics['first_leader_waits'] = first_leader_waits(
                    run_dir, number(row.get('transport_tick')),
                    number(row.get('unloading_tick')))
    if kind == 'leader':
        track = read_csv(os.path.join(run_dir, 'leader_track.csv'))
        points = [(number(r['path_fraction']), number(r['leader_swarm'])) for r in track]
        points = [p for p in points if p[0] is not None and p[1] is not None]
        curve = {}
        i = 0
        for pct in range(0, 101, PATH_STEP_PERCENT):
            while i < len(points) and points[i][0] * 100.0 < pct - 1e-6:
                i += 1
            if i < len(points):
                curve[pct] = points[i][1]
        if curve:
            series['leader_swarm_p'] = curve
    return metrics, series


THESIS_WAIT_M = 0.001   # the thesis's LeaderDidntMove: robot 0 moved less than this


def first_leader_waits(run_dir, start, stop, robot=0, below_m=THESIS_WAIT_M):
    """Ticks in (start, stop] in which `robot` moved less than below_m since the tick before,
    from the run's trace.csv: the thesis's leader waits as its figure 7.9 plotted them (its
    LeaderDidntMove counted robot 0 in every sample, the baseline sample included, and the
    figure shows the count - 1). None without a trace or a window."""
    if start is None or stop is None:
        return None
    poses = {}
    for r in read_csv(os.path.join(run_dir, 'trace.csv')):
        if number(r.get('robot_id')) == robot:
            tick, x, y = number(r.get('tick')), number(r.get('x')), number(r.get('y'))
            if tick is not None and x is not None and y is not None and start <= tick <= stop:
                poses[int(tick)] = (x, y)
    if not poses or min(poses) > start or max(poses) < stop:
        return None
    waits = 0
    for t in range(int(start) + 1, int(stop) + 1):
        if t - 1 in poses and t in poses:
            (x0, y0), (x1, y1) = poses[t - 1], poses[t]
            waits += math.hypot(x1 - x0, y1 - y0) < below_m
    return float(waits)


def trimmed_mean(values, trim=None):
    return core_metrics.trimmed_mean(values, presets.trim_each_end(len(values), trim))


def median(values):
    v = sorted(values)
    n = len(v)
    return v[n // 2] if n % 2 else (v[n // 2 - 1] + v[n // 2]) / 2.0


def aggregate(values, trim=None):
    """mean, median, trimmed mean and count of the finite values (None when there are none)."""
    vals = [v for v in values if v is not None and math.isfinite(v)]
    if not vals:
        return {'mean': None, 'median': None, 'trimmed_mean': None, 'runs': 0}
    return {'mean': sum(vals) / len(vals), 'median': median(vals),
            'trimmed_mean': trimmed_mean(vals, trim), 'runs': len(vals)}


def collect(preset, out_dir):
    """Every completed run of the preset's settings under out_dir/raw: a list of
    {setting, run, seed, metrics, series, info} in setting order, then by run."""
    runs = []
    for view in presets.settings(preset):
        for k, path in run_dirs(os.path.join(out_dir, 'raw', view['name'])):
            got = run_metrics(preset['kind'], path)
            if got is None:
                continue
            metrics, series, info = got
            runs.append({'setting': view['name'], 'run': k, 'seed': info.get('seed'),
                         'metrics': metrics, 'series': series, 'info': info})
    return runs


def summarize(preset, runs):
    """summary rows (dicts with SUMMARY_COLUMNS) in setting order: the kind's metrics, then
    the series points as metrics named <series><x> (swarm_count_t<seconds>,
    leader_swarm_p<percent of the path>)."""
    trim = preset.get('trim_each_end')
    rows = []
    for view in presets.settings(preset):
        mine = [r for r in runs if r['setting'] == view['name']]
        if not mine:
            continue
        for metric in presets.metrics_of(preset):
            agg = aggregate([r['metrics'].get(metric) for r in mine], trim)
            rows.append(dict(agg, setting=view['name'], metric=metric))
        names = sorted({s for r in mine for s in r['series']})
        for name in names:
            xs = sorted({x for r in mine for x in r['series'].get(name, {})})
            for x in xs:
                agg = aggregate([r['series'].get(name, {}).get(x) for r in mine], trim)
                rows.append(dict(agg, setting=view['name'], metric='%s%d' % (name, x)))
    return rows


def write_summary(path, rows):
    with open(path, 'w', newline='') as f:
        w = csv.writer(f)
        w.writerow(SUMMARY_COLUMNS)
        for r in rows:
            w.writerow([r['setting'], r['metric']] + [_fmt(r[c]) for c in
                                                      ('mean', 'median', 'trimmed_mean')] +
                       [r['runs']])


def write_runs(path, preset, runs):
    """One row per completed run: setting, run, seed, how it ended, every metric."""
    names = presets.metrics_of(preset)
    with open(path, 'w', newline='') as f:
        w = csv.writer(f)
        w.writerow(['setting', 'run', 'seed', 'end', 'ticks', 'wall_s'] + names)
        for r in runs:
            i = r['info']
            w.writerow([r['setting'], r['run'], r['seed'], i.get('end', ''), i.get('ticks', ''),
                        _fmt(i.get('wall_s'))] + [_fmt(r['metrics'].get(n)) for n in names])


def read_summary(path):
    """{(setting, metric): {'mean','median','trimmed_mean','runs'}} from summary.csv."""
    out = {}
    for r in read_csv(path):
        out[(r['setting'], r['metric'])] = {
            'mean': number(r['mean']), 'median': number(r['median']),
            'trimmed_mean': number(r['trimmed_mean']), 'runs': int(r['runs'])}
    return out


def series_of(summary, setting, prefix):
    """[(x, row)] of a series (metric names prefix<x>) from a read_summary() dict, by x."""
    pts = []
    for (s, metric), row in summary.items():
        if s == setting and metric.startswith(prefix) and metric[len(prefix):].isdigit():
            pts.append((int(metric[len(prefix):]), row))
    return sorted(pts, key=lambda p: p[0])


def spearman(xs, ys):
    """Rank correlation of two equally long lists (average ranks for ties); 0 when constant."""
    def ranks(v):
        order = sorted(range(len(v)), key=lambda i: v[i])
        r = [0.0] * len(v)
        i = 0
        while i < len(order):
            j = i
            while j + 1 < len(order) and v[order[j + 1]] == v[order[i]]:
                j += 1
            for m in range(i, j + 1):
                r[order[m]] = (i + j) / 2.0
            i = j + 1
        return r
    if len(xs) < 2:
        return 0.0
    rx, ry = ranks(xs), ranks(ys)
    mx, my = sum(rx) / len(rx), sum(ry) / len(ry)
    sxy = sum((a - mx) * (b - my) for a, b in zip(rx, ry))
    sxx = sum((a - mx) ** 2 for a in rx)
    syy = sum((b - my) ** 2 for b in ry)
    return sxy / math.sqrt(sxx * syy) if sxx > 0 and syy > 0 else 0.0


def _fmt(v):
    if v is None:
        return ''
    if isinstance(v, float):
        return repr(round(v, 9))
    return str(v)
