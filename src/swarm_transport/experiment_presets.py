"""Experiment presets (config/experiments/*.yaml): loading, validation and expansion into the
runs of an experiment. Pure python (no ROS): the runner, the report and the tests share it."""

import copy
import glob
import math
import os
import random

import yaml

from swarm_transport import core_metrics

ROOT = os.path.realpath(os.path.join(os.path.dirname(os.path.realpath(__file__)), '..', '..'))
PRESET_DIR = os.path.join(ROOT, 'config', 'experiments')
CONFIG_DIR = os.path.join(ROOT, 'config')

KINDS = ('flocking', 'leader', 'transport')
PLACEMENTS = ('random', 'corner', 'cluster')
# An expectation's trend: the direction its source gives along the settings. 'mixed': neither
# flat nor monotone by the page's classifier (what a source's own numbers can show);
# 'high_at_last': clearly higher at the last setting than at every other (an extra line beside
# a direction, for a source that says "only at the last value do they stay high").
TRENDS = ('increasing', 'decreasing', 'flat', 'mixed', 'high_at_last')
EXPECT_KEYS = {'metric', 'trend', 'settings', 'groups', 'source', 'because', 'across', 'labels',
               'per_passive_robot'}
# An expectation's series runs along the settings of each group (across: settings, the default)
# or, across: groups, along the groups for each setting label (labels: which ones, default all):
# "success falls with group size at 5 % cohesion". per_passive_robot (leader presets): each
# value divided by the setting's passive robots (robots - 1), a count made a share of the group.
ACROSS = ('settings', 'groups')
# The metrics of each kind, in the order of the tables (SPEC 8; docs/experiments.md).
METRICS = {
    'flocking': ['final_swarm_count', 'mean_swarm_count', 'swarm_count_slope_per_h',
                 'initial_swarm_count', 'final_largest_swarm'],
    'leader': ['path_fraction_attached', 'leader_swarm_at_arrival', 'leader_waits',
               'leader_ticks', 'aborted'],
    'transport': ['transport_ticks', 'slip_per_robot_m', 'distance_per_robot_m', 'leader_waits',
                  'object_error_m', 'gathering_ticks', 'leader_contact', 'aborted',
                  'gathering_swerves', 'mission_ticks'],
}
# (ext, SPEC 9.5) How the swarm spreads at a run's end (the recorder's run.csv, from its last
# frame): any preset may name them in its `table:`; they then join its runs.csv and summary.
DISPERSION_METRICS = ['coverage_fraction', 'nn_spacing_mean_m', 'nn_spacing_cv']
# (ext, SPEC 9.5) Metrics of a kind that join a preset's runs.csv and summary only when its
# `table:` names them: loading_nn_cv, the mission robots' nearest-neighbour spacing CV at the
# transport's first frame (the recorder's missions.csv; loading_spread).
# first_leader_waits: the leader waits as the thesis plotted them (fig. 7.9: its file's
# LeaderDidntMove - 1): transport ticks in which robot 0, the first leader, moved less than
# 1 mm, from the run's trace.csv (a preset whose table names it is run with --trace).
# (ext, issue 27; counted by the batch engine, result.json) gathering_interference: moves of
# mission robots not yet placed (on their slot; without one, inside the object) while gathering
# that swerved, slowed or stood for a robot in the way; plan_unstable_pct: the share (%) of a
# planned gathering's plans that hit the round cap; plan_cost_ratio / plan_cost_ratio_max: the
# median / largest over a run's plans of sum X (its pairs) / sum X (Hungarian, the least);
# plan_arrival_error_ticks / plan_arrival_error_max: the median / largest over a run's robots of
# |actual - planned arrival| on their slots (ticks; the first plan of each robot's final slot,
# core/plan_arrival.h), plan_arrival_late_ticks the signed median (> 0: later than planned),
# plan_unarrived the robots that never stood on their final slot, plan_slot_changes the plans
# that gave a robot another slot.
PLAN_ARRIVAL_METRICS = ['plan_arrival_error_ticks', 'plan_arrival_error_max',
                        'plan_arrival_late_ticks', 'plan_unarrived', 'plan_slot_changes']
# leaders_behind (issue 27, item 6): at the transport's start, the non-leaders standing more than
# a robot radius further toward the target than the rearmost leader (0: the leaders lead from
# the front).
OPTIONAL_METRICS = {'transport': ['loading_nn_cv', 'first_leader_waits', 'gathering_interference',
                                  'plan_unstable_pct', 'plan_cost_ratio', 'plan_cost_ratio_max',
                                  'leaders_behind'] + PLAN_ARRIVAL_METRICS}
TRACED_METRICS = {'first_leader_waits'}
TOP_KEYS = {'description', 'kind', 'order', 'section', 'figures', 'runs', 'seed_base',
            'base_config', 'config', 'robots', 'placement', 'cluster', 'max_ticks',
            'trim_each_end', 'x_label', 'group_label', 'thesis', 'note', 'expect', 'mission',
            'settings', 'jobs', 'name', 'thesis_measured', 'table'}
# thesis_measured: the thesis's own figures per setting where its raw data survives, and its
# published values where they do not ({source: text, metrics: [metric, ...], rows: [{label:
# text, <metric>: value}]}; a row may lack a metric: shown as -).
MEASURED_KEYS = {'source', 'metrics', 'rows'}
SETTING_KEYS = {'name', 'label', 'x', 'group', 'robots', 'config', 'mission', 'placement',
                'max_ticks'}
# group: the robots [0, group); count (ext): the dispatcher picks that many (robot_count).
MISSION_KEYS = {'id', 'object', 'target', 'leaders', 'group', 'leader', 'mode', 'count'}
CLUSTER_KEYS = {'origin', 'spacing_m', 'side_m', 'min_distance_m', 'heading_deg'}


class PresetError(ValueError):
    pass


def metrics_of(preset):
    """The metrics of a preset's runs.csv and summary: its kind's, then the dispersion metrics
    its table names."""
    table = preset.get('table') or []
    return METRICS[preset['kind']] + [
        m for m in OPTIONAL_METRICS.get(preset['kind'], []) + DISPERSION_METRICS if m in table]


def needs_trace(preset):
    """Whether a preset's runs must write trace.csv: its table names a metric taken from it."""
    return any(m in TRACED_METRICS for m in metrics_of(preset))


def preset_path(name):
    return os.path.join(PRESET_DIR, name + '.yaml')


def preset_names():
    return sorted(os.path.splitext(os.path.basename(p))[0]
                  for p in glob.glob(os.path.join(PRESET_DIR, '*.yaml')))


def load_preset(name_or_path):
    """The validated preset as a dict, with defaults filled in and 'name' set."""
    path = name_or_path if name_or_path.endswith('.yaml') else preset_path(name_or_path)
    if not os.path.isfile(path):
        raise PresetError('no preset %r (have: %s)' % (name_or_path, ', '.join(preset_names())))
    with open(path) as f:
        preset = yaml.safe_load(f)
    name = os.path.splitext(os.path.basename(path))[0]
    return validate(preset, name)


def validate(preset, name):
    if not isinstance(preset, dict):
        raise PresetError('%s: a preset is a mapping' % name)
    p = copy.deepcopy(preset)
    p['name'] = name

    def fail(msg):
        raise PresetError('preset %s: %s' % (name, msg))

    unknown = set(preset) - TOP_KEYS
    if unknown:
        fail('unknown keys %s' % sorted(unknown))
    for key in ('description', 'kind', 'runs', 'base_config', 'settings'):
        if key not in p:
            fail('missing %r' % key)
    if p['kind'] not in KINDS:
        fail('kind must be one of %s' % (KINDS,))
    if not isinstance(p['runs'], int) or p['runs'] < 1:
        fail('runs must be an integer >= 1')
    if 'table' in p:
        # The metrics of the preset's table on the results page (default: its kind's).
        known = METRICS[p['kind']] + OPTIONAL_METRICS.get(p['kind'], []) + DISPERSION_METRICS
        if (not isinstance(p['table'], list) or not p['table'] or
                any(m not in known for m in p['table'])):
            fail('table must be a non-empty list of %s metrics (%s)'
                 % (p['kind'], ', '.join(known)))
    p.setdefault('seed_base', 1)
    p.setdefault('order', 1000)
    p.setdefault('section', '')
    p.setdefault('figures', [])
    p.setdefault('config', {})
    p.setdefault('robots', 25)
    p.setdefault('placement', 'random')
    p.setdefault('max_ticks', 0)
    p.setdefault('x_label', 'setting')
    p.setdefault('group_label', '')
    p.setdefault('thesis', '')
    p.setdefault('note', '')  # ours: what explains a difference from the thesis
    for key in ('thesis', 'note'):
        if not isinstance(p[key], str):
            fail('%s must be a text' % key)
    p.setdefault('expect', [])
    p.setdefault('trim_each_end', None)
    base = os.path.join(CONFIG_DIR, p['base_config'])
    if not os.path.isfile(base):
        fail('base_config %s does not exist' % base)
    if p['kind'] == 'flocking' and not p['max_ticks'] > 0:
        fail('a flocking preset needs max_ticks > 0 (the run length)')
    if p['kind'] != 'flocking':
        if 'mission' not in p:
            fail('a %s preset needs a mission block' % p['kind'])
        if not p['max_ticks'] > 0:
            fail('a mission preset needs max_ticks > 0 (the tick limit: ABORTED beyond it)')
    if not isinstance(p['settings'], list) or not p['settings']:
        fail('settings must be a non-empty list')
    names = set()
    for s in p['settings']:
        if not isinstance(s, dict) or 'name' not in s:
            fail('every setting needs a name')
        bad = set(s) - SETTING_KEYS
        if bad:
            fail('setting %s: unknown keys %s' % (s['name'], sorted(bad)))
        if s['name'] in names or not str(s['name']).replace('_', '').replace('-', '').isalnum():
            fail('setting names must be unique and [A-Za-z0-9_-]: %r' % s['name'])
        names.add(s['name'])
        s.setdefault('label', str(s['name']))
        s.setdefault('group', '')
        s.setdefault('config', {})
        s['label'] = str(s['label'])
        s['group'] = str(s['group'])
        st = setting_view(p, s)
        if st['placement'] not in PLACEMENTS:
            fail('placement must be one of %s' % (PLACEMENTS,))
        if st['robots'] < 1:
            fail('setting %s: robots must be >= 1' % s['name'])
        if p['kind'] != 'flocking':
            m = st['mission']
            bad = set(m) - MISSION_KEYS
            if bad:
                fail('setting %s: unknown mission keys %s' % (s['name'], sorted(bad)))
            if 'target' not in m:
                fail('setting %s: the mission needs a target' % s['name'])
            if p['kind'] == 'transport':
                if 'group' in m and 'count' in m:
                    fail('setting %s: a mission has a group or a count, not both' % s['name'])
                group = m.get('count', m.get('group', st['robots']))
                if 'object' not in m or not 1 <= m.get('leaders', 0) <= group <= st['robots']:
                    fail('setting %s: a transport needs an object and 1 <= leaders <= group '
                         '<= robots' % s['name'])
    for e in p['expect']:
        if not isinstance(e, dict) or e.get('trend') not in TRENDS or \
                e.get('metric') not in metrics_of(p) + ['swarm_count_slope_per_h']:
            fail('expect entries need metric (one of the kind\'s) and trend %s' % (TRENDS,))
        if set(e) - EXPECT_KEYS:
            fail('expect: unknown keys %s' % sorted(set(e) - EXPECT_KEYS))
        for key in ('source', 'because'):
            if key in e and not (isinstance(e[key], str) and e[key].strip()):
                fail('expect: %s must be a text' % key)
        _check_across(p, e, fail)
    measured = p.get('thesis_measured')
    if measured is not None:
        if not isinstance(measured, dict) or set(measured) - MEASURED_KEYS or \
                not isinstance(measured.get('metrics'), list) or \
                not isinstance(measured.get('rows'), list):
            fail('thesis_measured: a mapping of source, metrics (a list) and rows (a list)')
        for row in measured['rows']:
            if not isinstance(row, dict) or 'label' not in row:
                fail('thesis_measured: every row is a mapping with a label')
            if not any(m in row for m in measured['metrics']):
                fail('thesis_measured: row %s has none of the metrics' % row.get('label'))
            for m in measured['metrics']:
                if m in row and (not isinstance(row[m], (int, float)) or
                                 isinstance(row[m], bool)):
                    fail('thesis_measured: row %s: %s is not a number' % (row.get('label'), m))
    if p.get('cluster') is not None and set(p['cluster']) - CLUSTER_KEYS:
        fail('unknown cluster keys %s' % sorted(set(p['cluster']) - CLUSTER_KEYS))
    for key, ok in (('side_m', lambda v: v > 0.0), ('heading_deg', lambda v: 0.0 <= v <= 360.0)):
        value = (p.get('cluster') or {}).get(key)
        if value is not None and (isinstance(value, bool) or not isinstance(value, (int, float))
                                  or not math.isfinite(value) or not ok(value)):
            fail('cluster %s must be a number %s but is %r'
                 % (key, '> 0' if key == 'side_m' else 'in [0, 360]', value))
    return p


def _check_across(p, e, fail):
    """An expectation's across / labels / per_passive_robot keys (see ACROSS)."""
    across = e.get('across', 'settings')
    if across not in ACROSS:
        fail('expect: across must be one of %s' % (ACROSS,))
    if 'labels' in e:
        known = [str(s['label']) for s in p['settings']]
        if across != 'groups':
            fail('expect: labels only with across: groups')
        if (not isinstance(e['labels'], list) or not e['labels'] or
                any(str(x) not in known for x in e['labels'])):
            fail('expect: labels must be a non-empty list of setting labels (%s)'
                 % ', '.join(sorted(set(known))))
    if across == 'groups' and len({str(s.get('group', '')) for s in p['settings']}) < 2:
        fail('expect: across: groups needs settings in at least 2 groups')
    if 'per_passive_robot' in e and (not isinstance(e['per_passive_robot'], bool) or
                                     p['kind'] != 'leader'):
        fail('expect: per_passive_robot is true or false, for a leader preset only')


def setting_view(preset, setting):
    """The effective parameters of one setting: preset values with the setting's overrides."""
    mission = dict(preset.get('mission') or {})
    mission.update(setting.get('mission') or {})
    config = dict(preset.get('config') or {})
    config.update(setting.get('config') or {})
    return {
        'name': setting['name'],
        'label': setting.get('label', setting['name']),
        'group': setting.get('group', ''),
        'x': setting.get('x'),
        'robots': int(setting.get('robots', preset['robots'])),
        'placement': setting.get('placement', preset['placement']),
        'max_ticks': int(setting.get('max_ticks', preset['max_ticks'])),
        'config': config,
        'mission': mission,
    }


def settings(preset):
    return [setting_view(preset, s) for s in preset['settings']]


def swarm_config(preset, view):
    """The YAML dict handed to swarm.launch as extra_config: the preset's base config file with
    the preset's and the setting's overrides."""
    with open(os.path.join(CONFIG_DIR, preset['base_config'])) as f:
        config = yaml.safe_load(f) or {}
    config.update(view['config'])
    return config


def trim_each_end(n, override=None):
    """Runs dropped at each end before averaging ('the middle runs', thesis 7.1): the 2 lowest
    and the 2 highest, as the thesis did (10 runs -> middle 6, 15 -> middle 11) and as the
    core's TrimmedMean does; fewer than 5 runs -> plain mean. A preset may override it."""
    if override is not None:
        return max(0, min(int(override), (n - 1) // 2))
    return 2 if n >= 5 else 0


def cluster_placement(robots, seed, local_range_m, radius_m, world_size_m, cluster=None):
    """Random poses 'close enough to count as one swarm but otherwise random' in the arena's
    bottom-left corner (thesis 7.3): uniform in a square that grows with the group, at least
    min_distance_m apart, redrawn until the within-local-range graph is connected. Lines
    'x y theta_deg' for placement:=file. Headings are uniform random, or with heading_deg every
    robot faces that way (the thesis's §7.3 leader code teleported each robot facing the
    leader's course: RobotSwarms 68b2ba6, robot/nodes/Leader.cpp 112-130)."""
    cluster = cluster or {}
    heading = cluster.get('heading_deg')
    origin = cluster.get('origin', [0.3, 0.3])
    spacing = float(cluster.get('spacing_m', 0.3))
    min_d = float(cluster.get('min_distance_m', 2.0 * radius_m * 1.1 * 1.5))
    # side_m: a square of that side for every group size (the thesis's leader code: +-(local
    # range - 0.1) around the leader's start, 68b2ba6 Leader.cpp 59-60, 112-128).
    side = (float(cluster['side_m']) if 'side_m' in cluster else
            max(spacing, spacing * math.sqrt(robots)))
    lo = (max(origin[0], radius_m), max(origin[1], radius_m))
    hi = (min(lo[0] + side, world_size_m - radius_m), min(lo[1] + side, world_size_m - radius_m))
    rng = random.Random(seed * 7919 + robots)
    for _ in range(1000):
        pts = []
        for _ in range(robots):
            for _ in range(1000):
                p = (rng.uniform(lo[0], hi[0]), rng.uniform(lo[1], hi[1]))
                if all(math.hypot(p[0] - q[0], p[1] - q[1]) >= min_d for q in pts):
                    pts.append(p)
                    break
            else:
                raise PresetError('cannot place %d robots %.3f m apart in a %.2f m square'
                                  % (robots, min_d, side))
        if core_metrics.components(pts, local_range_m)[0] == 1:
            poses = [(x, y, rng.uniform(0.0, 360.0)) for x, y in pts]
            return poses if heading is None else [(x, y, float(heading)) for x, y, _ in poses]
    raise PresetError('no connected cluster of %d robots found (local range %.2f)'
                      % (robots, local_range_m))


def leader_of(seed, robots):
    """The robot that gets the leader-only mission in a run: random per run (thesis 7.3
    'einem der Roboter wurde zufällig ... zugeteilt'), fixed by the run's seed."""
    return random.Random(seed * 104729 + 17).randrange(robots)
