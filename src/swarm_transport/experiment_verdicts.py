"""What the results page says about a preset beside its own numbers: the metric titles and
number format, the trend verdicts (the measured direction along the settings against what a
named source expects) and the table of the thesis's own measurements."""

from swarm_transport import experiment_presets as presets
from swarm_transport import experiment_stats as stats

# Short column titles and units of the metrics (tables and plot axes).
TITLES = {
    'final_swarm_count': 'final swarm count',
    'mean_swarm_count': 'mean swarm count',
    'swarm_count_slope_per_h': 'trend (swarms/h)',
    'initial_swarm_count': 'initial swarm count',
    'final_largest_swarm': 'largest swarm at end',
    'path_fraction_attached': 'path with whole swarm (%)',
    'leader_swarm_at_arrival': 'leader swarm at arrival',
    'leader_waits': 'leader waits',
    'leader_ticks': 'leader ticks to goal',
    'transport_ticks': 'transport ticks',
    'transport_ticks_median': 'median transport ticks',
    'runs_over_2x_median': 'runs > 2x median',
    'slip_per_robot_m': 'slip per robot (m)',
    'distance_per_robot_m': 'distance per robot (m)',
    'object_error_m': 'object error (m)',
    'gathering_ticks': 'gathering ticks',
    'leader_contact': 'leader contact (%)',
    'aborted': 'aborted (%)',
    'gathering_swerves': 'swerves while gathering',
    'gathering_interference': 'interference while gathering',
    'plan_unstable_pct': 'plans at the round cap (%)',
    'plan_cost_ratio': 'plan cost / optimal (median)',
    'plan_cost_ratio_max': 'plan cost / optimal (max)',
    'plan_arrival_error_ticks': 'arrival error (ticks, median)',
    'plan_arrival_error_max': 'arrival error (ticks, max)',
    'plan_arrival_late_ticks': 'arrival late (ticks, signed median)',
    'plan_unarrived': 'robots never on their slot',
    'plan_slot_changes': 'slot changes',
    'leaders_behind': 'robots ahead of a leader at transport start',
    'mission_ticks': 'mission ticks',
    'coverage_fraction': 'area covered (%)',
    'nn_spacing_mean_m': 'nearest neighbour (m)',
    'nn_spacing_cv': 'nearest-neighbour spread (CV)',
    'loading_nn_cv': 'spacing spread at transport start (CV)',
    'first_leader_waits': 'first leader waits (thesis count)',
}
PERCENT = {'path_fraction_attached', 'leader_contact', 'aborted', 'coverage_fraction'}   # stored as fractions, shown in %
FLAT_TOLERANCE = 0.10   # "flat": (max - min) / mean of the trimmed means at most this


def _scale(metric, v):
    return None if v is None else (100.0 * v if metric in PERCENT else v)


def views_with_data(preset, summary):
    have = {s for s, _ in summary}
    return [v for v in presets.settings(preset) if v['name'] in have]


def _setting_title(v):
    return ('%s %s' % (v['group'], v['label'])).strip() if v['group'] else v['label']


def _trim_text(preset):
    n = preset.get('runs', 0)
    k = presets.trim_each_end(n, preset.get('trim_each_end'))
    return 'mean of the middle %d of %d runs' % (n - 2 * k, n) if k else 'plain mean'


def _num(v):
    if v is None:
        return '–'
    a = abs(v)
    if a >= 100:
        return '%.0f' % v
    if a >= 10:
        return '%.1f' % v
    if a >= 0.1 or a == 0:
        return '%.2f' % v
    return '%.3g' % v


def high_at_last(ys):
    """The last value clearly above every other: by more than FLAT_TOLERANCE of the highest
    of the others."""
    return len(ys) >= 2 and ys[-1] > (1.0 + FLAT_TOLERANCE) * max(ys[:-1])


def classify(ys):
    """(direction, ρ, spread) of a series along the settings' order: 'flat' when
    (max - min) / mean |y| is at most FLAT_TOLERANCE, else 'increasing' (Spearman's ρ >= 0.5),
    'decreasing' (ρ <= -0.5) or 'mixed'."""
    rho = stats.spearman(list(range(len(ys))), ys)
    mean = sum(abs(y) for y in ys) / len(ys)
    spread = (max(ys) - min(ys)) / mean if mean > 0 else 0.0
    if spread <= FLAT_TOLERANCE:
        return 'flat', rho, spread
    return ('increasing' if rho >= 0.5 else 'decreasing' if rho <= -0.5 else 'mixed'), rho, spread


def _value(e, v, summary):
    """The trimmed mean of e's metric in setting v (per passive robot if e says so), or None."""
    t = summary.get((v['name'], e['metric']), {}).get('trimmed_mean')
    if t is None or not e.get('per_passive_robot'):
        return t
    return t / (v['robots'] - 1) if v['robots'] > 1 else None


def _series(preset, e, summary):
    """[(title, [(point label, value)])]: one series per group along its settings, or with
    across: groups one per setting label along the groups (presets.ACROSS)."""
    views = [v for v in views_with_data(preset, summary)
             if (not e.get('settings') or v['name'] in e['settings']) and
             (not e.get('groups') or v['group'] in [str(g) for g in e['groups']])]
    out = []
    if e.get('across', 'settings') == 'groups':
        labels = [str(x) for x in e['labels']] if e.get('labels') else []
        for v in views:
            if not e.get('labels') and v['label'] not in labels:
                labels.append(v['label'])
        x = preset.get('x_label') or 'setting'
        over = preset.get('group_label') or 'group'
        for label in labels:
            pts = [(v['group'], _value(e, v, summary)) for v in views if v['label'] == label]
            out.append(('%s %s, over %s' % (x, label, over),
                        [(g, t) for g, t in pts if t is not None]))
        return out
    for v in views:
        if not out or out[-1][0] != v['group']:
            out.append((v['group'], []))
        t = _value(e, v, summary)
        if t is not None:
            out[-1][1].append((v['label'], t))
    return out


def trend_results(preset, summary):
    """One dict per expected trend and series: 'text' (the line of the page), 'verdict' ('agrees'
    / 'differs') and 'measured' (the trend kind measured, e.g. 'increasing'). An expectation
    may name the source of what it expects (`source`: 'thesis text', 'thesis (text + fig.
    7.9)', 'raw file f5599e6', ...: it opens the line; without one the line says 'thesis') and
    may say why ours differs (`because`, shown only when it does). Its series run along each
    group's settings, or across the groups (_series)."""
    out = []
    for e in preset.get('expect', []):
        metric = e['metric']
        share = bool(e.get('per_passive_robot'))
        title = TITLES.get(metric, metric) + (' (% of the group)' if share else '')
        for group, pts in _series(preset, e, summary):
            if len(pts) < 2:
                continue
            ys = [t for _, t in pts]
            got, rho, spread = classify(ys)
            if e['trend'] == 'high_at_last' and high_at_last(ys):
                got = 'high_at_last'
            verdict = 'agrees' if got == e['trend'] else 'differs'
            seq = ' → '.join('%s %s' % (label, _num(100.0 * t if share else _scale(metric, t)))
                             for label, t in pts)
            # A named source opens the line; without one it is the thesis('s text).
            source = ' '.join(str(e.get('source', '')).split())
            text = ('%s%s%s: %s — measured %s (ρ = %+.2f, spread %.0f %%), %s %s: %s'
                    % ('%s — ' % source if source else '', '%s, ' % group if group else '',
                       title, seq, got.replace('_', ' '), rho,
                       100 * spread, 'expected' if source else 'thesis',
                       e['trend'].replace('_', ' '), verdict))
            if verdict == 'differs' and e.get('because'):
                text += ', because %s' % ' '.join(str(e['because']).split())
            out.append({'text': text, 'verdict': verdict, 'measured': got})
    return out


def trend_lines(preset, summary):
    """The lines of trend_results()."""
    return [r['text'] for r in trend_results(preset, summary)]


def measured_table(preset):
    """The thesis's own figures (its raw data where it survives, its published figure where
    not) beside ours: one row per setting it measured, the same metrics and units as the table
    above; a value a row does not have is shown as –."""
    m = preset.get('thesis_measured')
    if not m:
        return []
    cols = m['metrics']
    lines = ['**Thesis, measured** (%s):' % ' '.join(str(m.get('source', '')).split()), '',
             '| thesis setting | ' + ' | '.join(TITLES.get(c, c) for c in cols) + ' |',
             '|---|' + '---:|' * len(cols)]
    for row in m['rows']:
        # Whole numbers as the file gives them (a count of runs is 1, not 1.00).
        lines.append('| %s | %s |' % (row['label'], ' | '.join(
            str(row[c]) if isinstance(row.get(c), int) and not isinstance(row[c], bool)
            else _num(row.get(c)) for c in cols)))
    lines.append('')
    return lines
