"""Aggregation of an experiment's output directory (summary.csv, runs.csv), its plots shaped
like the thesis's figures, the table, and the results page (docs/results.md)."""

import json
import os
import shutil
import sys

from swarm_transport import experiment_presets as presets
from swarm_transport import experiment_stats as stats
from swarm_transport.experiment_verdicts import (  # noqa: F401 (used by the tests too)
    FLAT_TOLERANCE, PERCENT, TITLES, _num, _scale, _setting_title, _trim_text, high_at_last,
    measured_table, trend_lines, trend_results, views_with_data)

PANELS = {   # the metrics drawn as bars, in the thesis's order of diagrams
    'flocking': ['final_swarm_count', 'mean_swarm_count', 'swarm_count_slope_per_h'],
    'leader': ['path_fraction_attached', 'leader_swarm_at_arrival', 'leader_waits'],
    'transport': ['transport_ticks', 'slip_per_robot_m', 'distance_per_robot_m',
                  'leader_waits', 'object_error_m', 'aborted'],
}
TABLE = {
    'flocking': ['initial_swarm_count', 'final_swarm_count', 'mean_swarm_count',
                 'swarm_count_slope_per_h'],
    'leader': ['path_fraction_attached', 'leader_swarm_at_arrival', 'leader_waits',
               'leader_ticks', 'aborted'],
    'transport': ['transport_ticks', 'slip_per_robot_m', 'distance_per_robot_m',
                  'leader_waits', 'leader_contact', 'object_error_m', 'aborted'],
}


def log(msg=''):
    sys.stdout.write(msg + '\n')
    sys.stdout.flush()


def aggregate_dir(out, preset, print_table=False):
    """Recomputes summary.csv and runs.csv from out/raw, draws the plots; returns
    (summary dict, plot paths)."""
    runs = stats.collect(preset, out)
    rows = stats.summarize(preset, runs)
    stats.write_summary(os.path.join(out, 'summary.csv'), rows)
    stats.write_runs(os.path.join(out, 'runs.csv'), preset, runs)
    summary = stats.read_summary(os.path.join(out, 'summary.csv'))
    warnings = sorted({w for r in runs for w in r['info'].get('warnings', [])})
    for w in warnings:
        log('warning: %s' % w)
    plots = plot(preset, summary, out)
    if print_table:
        log('')
        for line in text_table(preset, summary):
            log(line)
        for line in trend_lines(preset, summary):
            log(line)
        log('plots: %s' % ', '.join(plots))
        log('summary: %s' % os.path.join(out, 'summary.csv'))
    return summary, plots


def table_metrics(preset):
    """The metrics of a preset's table: its own `table`, else its kind's."""
    return preset.get('table') or TABLE[preset['kind']]


def text_table(preset, summary):
    cols = table_metrics(preset)
    views = views_with_data(preset, summary)
    head = ['setting', 'runs'] + [TITLES[c] for c in cols]
    body = []
    for v in views:
        n = max((summary.get((v['name'], c), {}).get('runs', 0) for c in cols), default=0)
        if preset['kind'] != 'flocking':
            n = summary.get((v['name'], 'aborted'), {}).get('runs', n)
        body.append([_setting_title(v), str(n)] + [
            _num(_scale(c, summary.get((v['name'], c), {}).get('trimmed_mean'))) for c in cols])
    widths = [max(len(r[i]) for r in [head] + body) for i in range(len(head))]
    lines = ['trimmed means (%s):' % _trim_text(preset)]
    lines.append('  '.join(h.ljust(w) for h, w in zip(head, widths)))
    for r in body:
        lines.append('  '.join(c.ljust(w) if i == 0 else c.rjust(w)
                               for i, (c, w) in enumerate(zip(r, widths))))
    return lines


def markdown_table(preset, summary):
    cols = table_metrics(preset)
    views = views_with_data(preset, summary)
    lines = ['| setting | runs | ' + ' | '.join(TITLES[c] for c in cols) + ' |',
             '|---|---:|' + '---:|' * len(cols)]
    for v in views:
        n = summary.get((v['name'], cols[0]), {}).get('runs', 0)
        if preset['kind'] != 'flocking':
            n = summary.get((v['name'], 'aborted'), {}).get('runs', n)
        cells = []
        for c in cols:
            row = summary.get((v['name'], c), {})
            t = _scale(c, row.get('trimmed_mean'))
            cells.append('%s <sub>(%s / %s)</sub>' % (_num(t), _num(_scale(c, row.get('mean'))),
                                                       _num(_scale(c, row.get('median'))))
                         if t is not None else '–')
        lines.append('| %s | %d | %s |' % (_setting_title(v), n, ' | '.join(cells)))
    return lines


def _pyplot():
    import matplotlib
    matplotlib.use('Agg')
    import matplotlib.pyplot as plt
    return plt


def plot(preset, summary, out):
    plt = _pyplot()
    kind = preset['kind']
    views = views_with_data(preset, summary)
    if not views:
        return []
    paths = []
    figs = ', '.join(preset.get('figures') or [])
    if kind == 'flocking':
        paths.append(_plot_series(plt, preset, summary, views, 'swarm_count_t',
                                  os.path.join(out, 'swarm_count.png'),
                                  x_scale=1 / 60.0, x_label='simulated time (min)',
                                  y_label='swarm count (trimmed mean)',
                                  title='Swarm count over time (thesis Fig. %s)' % figs,
                                  trend=True))
    if kind == 'leader' and not any(v['group'] for v in views):
        p = _plot_series(plt, preset, summary, views, 'leader_swarm_p',
                         os.path.join(out, 'leader_swarm.png'), x_scale=1.0,
                         x_label='leader\'s path travelled (%)',
                         y_label='robots in the leader\'s swarm (trimmed mean)',
                         title='Leader\'s swarm along its path (thesis Fig. %s)' % figs)
        if p:
            paths.append(p)
    groups = []
    for v in views:
        if not groups or groups[-1][0] != v['group']:
            groups.append((v['group'], []))
        groups[-1][1].append(v)
    for group, members in groups:
        name = 'metrics_%s.png' % _slug(group) if group else 'metrics.png'
        paths.append(_plot_bars(plt, preset, summary, members, preset.get('table') or PANELS[kind],
                                os.path.join(out, name), group))
    return paths


def _slug(text):
    return ''.join(c if c.isalnum() else '_' for c in text).strip('_').lower()


def _plot_series(plt, preset, summary, views, prefix, path, x_scale, x_label, y_label, title,
                 trend=False):
    fig, ax = plt.subplots(figsize=(9, 5))
    drawn = False
    for i, v in enumerate(views):
        pts = [(x * x_scale, row['trimmed_mean']) for x, row in
               stats.series_of(summary, v['name'], prefix) if row['trimmed_mean'] is not None]
        if not pts:
            continue
        drawn = True
        colour = 'C%d' % (i % 10)
        xs, ys = [p[0] for p in pts], [p[1] for p in pts]
        ax.plot(xs, ys, color=colour, linewidth=1.2, label=v['label'])
        if trend and len(xs) > 1:
            slope = stats._slope(xs, ys)
            mx, my = sum(xs) / len(xs), sum(ys) / len(ys)
            ax.plot([xs[0], xs[-1]], [my + slope * (xs[0] - mx), my + slope * (xs[-1] - mx)],
                    color=colour, linestyle='--', linewidth=1.0)
    if not drawn:
        plt.close(fig)
        return None
    ax.set_xlabel(x_label)
    ax.set_ylabel(y_label)
    ax.set_ylim(bottom=0)
    ax.set_title('%s: %s' % (preset['name'], title), fontsize=10)
    ax.legend(title=preset.get('x_label', ''), fontsize=8, title_fontsize=8)
    ax.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(path, dpi=90)
    plt.close(fig)
    return path


def _plot_bars(plt, preset, summary, views, metrics, path, group):
    n = len(metrics)
    cols = 3 if n > 3 else n
    rows = (n + cols - 1) // cols
    fig, axes = plt.subplots(rows, cols, figsize=(4.2 * cols, 3.6 * rows), squeeze=False)
    labels = [v['label'] for v in views]
    xs = list(range(len(views)))
    width = 0.27
    for i, metric in enumerate(metrics):
        ax = axes[i // cols][i % cols]
        for j, (stat, colour) in enumerate((('mean', 'C0'), ('median', 'C1'),
                                            ('trimmed_mean', 'C2'))):
            ys = [_scale(metric, summary.get((v['name'], metric), {}).get(stat)) for v in views]
            ax.bar([x + (j - 1) * width for x in xs], [y if y is not None else 0 for y in ys],
                   width=width, color=colour, label=stat.replace('_', ' '))
        ax.set_xticks(xs)
        ax.set_xticklabels(labels, rotation=45 if len(labels) > 5 else 0, fontsize=8,
                           ha='right' if len(labels) > 5 else 'center')
        ax.set_title(TITLES.get(metric, metric), fontsize=9)
        ax.set_xlabel(preset.get('x_label', ''), fontsize=8)
        ax.grid(axis='y', alpha=0.3)
        if i == 0:
            ax.legend(fontsize=7)
    for i in range(n, rows * cols):
        axes[i // cols][i % cols].axis('off')
    title = '%s%s (thesis Fig. %s; %s)' % (preset['name'], ', %s' % group if group else '',
                                           ', '.join(preset.get('figures') or []),
                                           _trim_text(preset))
    fig.suptitle(title, fontsize=10)
    fig.tight_layout()
    fig.savefig(path, dpi=90)
    plt.close(fig)
    return path


# ---------------------------------------------------------------------------------------------
# results page

def find_outputs(dirs):
    """Preset output directories (holding experiment.json) in or directly under dirs."""
    found = []
    for d in dirs:
        d = os.path.abspath(d)
        if os.path.isfile(os.path.join(d, 'experiment.json')):
            found.append(d)
        elif os.path.isdir(d):
            for name in sorted(os.listdir(d)):
                sub = os.path.join(d, name)
                if os.path.isfile(os.path.join(sub, 'experiment.json')):
                    found.append(sub)
    return found


def _engine_text(meta):
    """How the runs were made: the batch engine, or launched with a deployment."""
    if meta.get('engine', 'launch') == 'batch' or meta.get('deploy') == 'batch':
        return '--engine batch'
    return '--engine launch --deploy %s' % meta.get('deploy', 'process')


def cmd_report(dirs, out_md):
    outputs = find_outputs(dirs)
    if not outputs:
        log('report: no experiment output (a directory with experiment.json) in %s'
            % ', '.join(dirs))
        return 2
    entries = []
    for d in outputs:
        with open(os.path.join(d, 'experiment.json')) as f:
            meta = json.load(f)
        preset = presets.validate(meta['preset'], meta['preset']['name'])
        preset['runs'] = meta.get('runs', preset['runs'])
        # The prose (the thesis's claim, our note) and the expectations judged against it may
        # have been written after the run: take them from the preset as it is now, when it
        # still exists.
        try:
            current = presets.load_preset(preset['name'])
            preset['thesis'], preset['note'] = current['thesis'], current['note']
            preset['expect'] = current['expect']
            if current.get('thesis_measured'):
                preset['thesis_measured'] = current['thesis_measured']
        except presets.PresetError:
            pass
        summary, plots = aggregate_dir(d, preset)
        entries.append((preset, meta, summary, plots, d))
    entries.sort(key=lambda e: (e[0].get('order', 1000), e[0]['name']))
    out_md = os.path.abspath(out_md)
    img_root = os.path.join(os.path.dirname(out_md), 'results')
    lines = ['# Results: the thesis\'s chapter 7, reproduced', '',
             'Generated by `scripts/experiment report` (see docs/experiments.md for the presets, '
             'the metrics and how to regenerate this page). Every table cell is the thesis\'s '
             '"mean of the middle runs" (trimmed mean) with <sub>(mean / median)</sub>; bars '
             'show all three. Each trend line compares the measured direction along the '
             'settings with what its source says, and names the source when it is more than '
             '"thesis" (the thesis\'s text): its published figure, or its own raw measurement '
             'where that survives (then tabled as "Thesis, measured"). An expectation is what '
             'its source says, never chosen to fit our result; "differs" is an answer.', '']
    for preset, meta, summary, plots, d in entries:
        t = meta.get('timing', {})
        lines.append('## `%s`: %s' % (preset['name'], preset['description']))
        lines.append('')
        full = meta.get('preset_runs') or _preset_runs(preset['name'])
        fewer = (' — **fewer than the thesis\'s %d**: `scripts/experiment run %s` repeats it '
                 'in full' % (full, preset['name'])) if full and meta.get('runs', 0) < full else ''
        lines.append('Runs: %d per setting (seeds %d..%d), %s%s. Measured: %d runs in %s wall '
                     '(%d simulated ticks, %.0f ticks/s overall, %d in parallel, `%s`).'
                     % (meta.get('runs', 0), meta.get('seed_base', 0),
                        meta.get('seed_base', 0) + meta.get('runs', 1) - 1, _trim_text(preset),
                        fewer,
                        t.get('runs', 0), _hms(t.get('wall_s', 0)), t.get('sim_ticks', 0),
                        t.get('sim_ticks', 0) / t['wall_s'] if t.get('wall_s') else 0,
                        meta.get('jobs', 1), _engine_text(meta)))
        lines.append('')
        dest = os.path.join(img_root, preset['name'])
        os.makedirs(dest, exist_ok=True)
        for p in plots:
            shutil.copyfile(p, os.path.join(dest, os.path.basename(p)))
            rel = os.path.relpath(os.path.join(dest, os.path.basename(p)),
                                  os.path.dirname(out_md))
            lines.append('![%s](%s)' % (os.path.basename(p), rel))
            lines.append('')
        lines.extend(markdown_table(preset, summary))
        lines.append('')
        if preset.get('thesis'):
            lines.append('**Thesis:** %s' % preset['thesis'].strip())
            lines.append('')
        lines.extend(measured_table(preset))
        trends = trend_results(preset, summary)
        if trends:
            lines.append('**Measured trend:**')
            lines.append('')
            lines.extend('- %s' % t['text'] for t in trends)
            lines.append('')
        if preset.get('note'):
            # "Why it differs" only above a section with a trend line that differs.
            differs = any(t['verdict'] == 'differs' for t in trends)
            lines.append('**%s:** %s' % ('Why it differs' if differs else 'Note',
                                         ' '.join(preset['note'].split())))
            lines.append('')
    with open(out_md, 'w') as f:
        f.write('\n'.join(lines))
    log('results page: %s (%d experiments, images in %s)' % (out_md, len(entries), img_root))
    return 0


def _preset_runs(name):
    """The runs per setting of the preset as shipped (the thesis's number), if it exists."""
    try:
        return presets.load_preset(name)['runs']
    except presets.PresetError:
        return None


def _hms(s):
    s = int(round(s))
    return '%d:%02d:%02d' % (s // 3600, s % 3600 // 60, s % 60)
