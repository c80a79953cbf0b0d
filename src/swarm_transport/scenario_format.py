"""The scenario format (docs/scenarios.md): a swarm scenario as data - the world, the missions
with the tick each is sent at, timed events and the expectations with their tolerances.

parse(text, path) returns the scenario as plain dicts, or raises ScenarioError with one message
naming the file, the line and the key ("thesis.yaml:12: missions[0].leaders: ..."), before
anything is started."""

import math

import yaml

DEPLOYS = ('process', 'host', 'host_sim')
CLOCKS = ('lockstep', 'realtime')
PLACEMENTS = ('random', 'corner', 'file')
STATES = ('QUEUED', 'GATHERING', 'LOADING', 'TRANSPORT', 'UNLOADING', 'DONE', 'ABORTED',
          'REJECTED')
EVENT_KINDS = ('freeze', 'continue', 'kill', 'spawn', 'object_update', 'signal', 'statist',
               'remove_statist')
SIGNALS = ('LOADED', 'UNLOADED')
# Expectation kind -> (required keys, optional keys with defaults).
EXPECTATIONS = {
    'mission_state': ({'mission', 'state', 'by_tick'}, {}),
    'no_intrusion': (set(), {'tolerance_m': 0.0, 'grace_ticks': 0, 'until_phase': None}),
    'no_overlap': (set(), {'tolerance_m': 0.0}),
    'in_arena': (set(), {'tolerance_m': 0.0, 'inset_m': 0.0}),
    'moved': (set(), {'min_m': 0.0}),
    'swarm_count': ({'at_tick'}, {'min': 1, 'max': 65535}),
    'transport_ticks': ({'mission'}, {'min': 0, 'max': float('inf')}),
    'slip_per_robot_m': ({'mission'}, {'min': 0.0, 'max': float('inf')}),
    'reproducible': (set(), {}),
    'phases': ({'mission', 'states'}, {}),
    'object_error_m': ({'mission'}, {'min': 0.0, 'max': float('inf')}),
    'gathered': ({'mission'}, {'tolerance_m': 0.0}),
    'still_while_frozen': ({'mission'}, {'settle_ticks': 3, 'tolerance_m': 0.001}),
    'phase_order': ({'mission', 'state', 'after_mission', 'after_state'}, {}),
    'released': (set(), {}),
    'object_clear_of_zones': ({'mission'}, {'tolerance_m': 0.0}),
    'centroid_near': ({'at_tick', 'x', 'y'}, {'min_m': 0.0, 'max_m': float('inf')}),
}
TOP_KEYS = {'name', 'description', 'world', 'max_ticks', 'missions', 'events', 'expect'}
WORLD_KEYS = {'robots', 'seed', 'placement', 'placement_file', 'config', 'base_config',
              'danger_zones', 'deploy', 'clock'}
MISSION_KEYS = {'at_tick', 'id', 'robots_from', 'robots_to', 'robot_ids', 'leaders', 'object',
                'target', 'mode'}


class ScenarioError(ValueError):
    pass


class _Reader(object):
    """Walks the YAML node tree, so that every error names the line of what it is about."""

    def __init__(self, path):
        self.path = path

    def fail(self, node, where, msg):
        line = node.start_mark.line + 1 if node is not None else 0
        raise ScenarioError('%s:%d: %s: %s' % (self.path, line, where, msg))

    def mapping(self, node, where, allowed, required=()):
        if not isinstance(node, yaml.MappingNode):
            self.fail(node, where, 'must be a mapping')
        out = {}
        for key_node, value_node in node.value:
            key = key_node.value
            if key in out:
                self.fail(key_node, '%s.%s' % (where, key), 'given twice')
            if key not in allowed:
                self.fail(key_node, '%s.%s' % (where, key) if where else key,
                          'unknown key (allowed: %s)' % ', '.join(sorted(allowed)))
            out[key] = value_node
        for key in required:
            if key not in out:
                self.fail(node, where or 'the scenario', 'missing %r' % key)
        return out

    def sequence(self, node, where):
        if not isinstance(node, yaml.SequenceNode):
            self.fail(node, where, 'must be a list')
        return node.value

    def value(self, node, where):
        if not isinstance(node, yaml.ScalarNode):
            self.fail(node, where, 'must be a single value')
        return yaml.safe_load(yaml.serialize(node))

    def number(self, node, where, lo=-math.inf, hi=math.inf, integer=False):
        v = self.value(node, where)
        ok = isinstance(v, int) and not isinstance(v, bool) if integer else \
            isinstance(v, (int, float)) and not isinstance(v, bool)
        if not ok or not math.isfinite(v) or not lo <= v <= hi:
            self.fail(node, where, 'must be %s in [%s, %s] but is %r'
                      % ('an integer' if integer else 'a finite number', lo, hi, v))
        return v

    def choice(self, node, where, choices):
        v = self.value(node, where)
        if v not in choices:
            self.fail(node, where, 'must be one of %s but is %r' % (', '.join(choices), v))
        return v

    def numbers(self, node, where, count, lo=-math.inf, hi=math.inf):
        items = self.sequence(node, where)
        if len(items) != count:
            self.fail(node, where, 'must be a list of %d numbers' % count)
        return [self.number(n, '%s[%d]' % (where, i), lo, hi) for i, n in enumerate(items)]

    def plain(self, node):
        return yaml.safe_load(yaml.serialize(node))


def parse(text, path='<scenario>'):
    try:
        root = yaml.compose(text, Loader=yaml.SafeLoader)
    except yaml.YAMLError as e:
        mark = getattr(e, 'problem_mark', None)
        raise ScenarioError('%s:%d: not YAML: %s' % (path, mark.line + 1 if mark else 0,
                                                       getattr(e, 'problem', e)))
    r = _Reader(path)
    if root is None:
        raise ScenarioError('%s:1: the scenario is empty' % path)
    top = r.mapping(root, '', TOP_KEYS, required=('world', 'max_ticks', 'expect'))
    s = {'path': path}
    s['name'] = str(r.value(top['name'], 'name')) if 'name' in top else path
    s['description'] = str(r.value(top['description'], 'description')) \
        if 'description' in top else ''
    s['max_ticks'] = r.number(top['max_ticks'], 'max_ticks', 1, 10 ** 7, integer=True)
    s['world'] = _world(r, top['world'])
    robots = s['world']['robots']
    s['missions'] = [_mission(r, n, 'missions[%d]' % i, robots, s['max_ticks'])
                     for i, n in enumerate(r.sequence(top['missions'], 'missions'))] \
        if 'missions' in top else []
    ids = [m['id'] for m in s['missions']]
    if len(set(ids)) != len(ids):
        r.fail(top['missions'], 'missions', 'mission ids must be unique: %s' % ids)
    s['events'] = [_event(r, n, 'events[%d]' % i, robots, s['max_ticks'], ids)
                   for i, n in enumerate(r.sequence(top['events'], 'events'))] \
        if 'events' in top else []
    s['expect'] = [_expectation(r, n, 'expect[%d]' % i, ids, s['max_ticks'])
                   for i, n in enumerate(r.sequence(top['expect'], 'expect'))]
    if not s['expect']:
        r.fail(top['expect'], 'expect', 'a scenario needs at least one expectation')
    return s


def load(path):
    with open(path) as f:
        return parse(f.read(), path)


def _world(r, node):
    w = r.mapping(node, 'world', WORLD_KEYS, required=('robots',))
    out = {'robots': r.number(w['robots'], 'world.robots', 1, 65535, integer=True),
           'seed': r.number(w['seed'], 'world.seed', 0, 2 ** 31 - 1, integer=True)
           if 'seed' in w else 1,
           'placement': r.choice(w['placement'], 'world.placement', PLACEMENTS)
           if 'placement' in w else 'random',
           'deploy': r.choice(w['deploy'], 'world.deploy', DEPLOYS)
           if 'deploy' in w else 'host_sim',
           'clock': r.choice(w['clock'], 'world.clock', CLOCKS) if 'clock' in w else 'lockstep',
           'base_config': str(r.value(w['base_config'], 'world.base_config'))
           if 'base_config' in w else 'swarm.yaml',
           'config': {}, 'danger_zones': None, 'placement_file': ''}
    if 'config' in w:
        # Keys of /swarm (config/swarm.yaml); the nodes validate them before the run starts.
        if not isinstance(w['config'], yaml.MappingNode):
            r.fail(w['config'], 'world.config', 'must be a mapping of /swarm keys')
        out['config'] = r.plain(w['config'])
    if 'danger_zones' in w:
        zones = r.sequence(w['danger_zones'], 'world.danger_zones')
        out['danger_zones'] = [r.plain(z) for z in zones]
    if out['placement'] == 'file':
        if 'placement_file' not in w:
            r.fail(node, 'world.placement_file', 'required with placement: file')
        out['placement_file'] = str(r.value(w['placement_file'], 'world.placement_file'))
    return out


def _range(r, node, where, robots):
    lo, hi = r.numbers(node, where, 2, 0, 65535)
    if not (int(lo) == lo and int(hi) == hi and lo < hi):
        r.fail(node, where, 'must be [from, to) with integers from < to')
    return [int(lo), int(hi)]


def _mission(r, node, where, robots, max_ticks):
    m = r.mapping(node, where, MISSION_KEYS, required=('id', 'leaders', 'target'))
    out = {'at_tick': r.number(m['at_tick'], where + '.at_tick', 0, max_ticks, integer=True)
           if 'at_tick' in m else 0,
           'id': r.number(m['id'], where + '.id', 1, 65535, integer=True),
           'leaders': r.number(m['leaders'], where + '.leaders', 1, 255, integer=True),
           'target': r.numbers(m['target'], where + '.target', 2),
           'object': r.numbers(m['object'], where + '.object', 4) if 'object' in m else None,
           'mode': r.number(m['mode'], where + '.mode', 0, 1, integer=True) if 'mode' in m else 0}
    if 'robot_ids' in m:
        ids = [r.number(n, '%s.robot_ids[%d]' % (where, i), 0, 65535, integer=True)
               for i, n in enumerate(r.sequence(m['robot_ids'], where + '.robot_ids'))]
        if not ids:
            r.fail(m['robot_ids'], where + '.robot_ids', 'must name at least one robot')
        out['robot_ids'] = ids
    elif 'robots_from' in m and 'robots_to' in m:
        lo = r.number(m['robots_from'], where + '.robots_from', 0, 65535, integer=True)
        hi = r.number(m['robots_to'], where + '.robots_to', 0, 65535, integer=True)
        if lo >= hi:
            r.fail(m['robots_to'], where + '.robots_to', 'must be > robots_from (%d)' % lo)
        out['robot_ids'] = list(range(lo, hi))
    else:
        r.fail(node, where, "needs robot_ids or robots_from and robots_to")
    if out['leaders'] > len(out['robot_ids']):
        r.fail(m['leaders'], where + '.leaders', 'more leaders than robots')
    return out


def _event(r, node, where, robots, max_ticks, mission_ids):
    e = r.mapping(node, where, {'at_tick'} | set(EVENT_KINDS), required=('at_tick',))
    kinds = [k for k in e if k != 'at_tick']
    if len(kinds) != 1:
        r.fail(node, where, 'needs exactly one of %s' % ', '.join(EVENT_KINDS))
    kind = kinds[0]
    out = {'at_tick': r.number(e['at_tick'], where + '.at_tick', 0, max_ticks, integer=True),
           'kind': kind}
    v = e[kind]
    w = '%s.%s' % (where, kind)
    if kind in ('freeze', 'continue'):
        out['range'] = _range(r, v, w, robots)
    elif kind == 'kill':
        out['robot'] = r.number(v, w, 0, 65535, integer=True)
    elif kind == 'spawn':
        s = r.mapping(v, w, {'id', 'x', 'y', 'theta_deg'}, required=('id', 'x', 'y'))
        out.update(robot=r.number(s['id'], w + '.id', 0, 65535, integer=True),
                   x=r.number(s['x'], w + '.x'), y=r.number(s['y'], w + '.y'),
                   theta_deg=r.number(s['theta_deg'], w + '.theta_deg')
                   if 'theta_deg' in s else 0.0)
    elif kind == 'object_update':
        s = r.mapping(v, w, {'mission', 'x', 'y'}, required=('mission', 'x', 'y'))
        out.update(mission=_mission_ref(r, s['mission'], w + '.mission', mission_ids),
                   x=r.number(s['x'], w + '.x'), y=r.number(s['y'], w + '.y'))
    elif kind in ('statist', 'remove_statist'):
        keys = {'id', 'sub_id', 'x', 'y'} if kind == 'statist' else {'id', 'sub_id'}
        s = r.mapping(v, w, keys, required=tuple(sorted(keys - {'sub_id'})))
        out.update(robot=r.number(s['id'], w + '.id', 0, 65535, integer=True),
                   sub_id=r.number(s['sub_id'], w + '.sub_id', 0, 255, integer=True)
                   if 'sub_id' in s else 0)
        if kind == 'statist':
            out.update(x=r.number(s['x'], w + '.x'), y=r.number(s['y'], w + '.y'))
    elif kind == 'signal':
        s = r.mapping(v, w, {'mission', 'event'}, required=('mission', 'event'))
        out.update(mission=_mission_ref(r, s['mission'], w + '.mission', mission_ids),
                   event=r.choice(s['event'], w + '.event', SIGNALS))
    return out


def _mission_ref(r, node, where, mission_ids):
    mid = r.number(node, where, 1, 65535, integer=True)
    if mid not in mission_ids:
        r.fail(node, where, 'no mission %d in missions (%s)' % (mid, mission_ids))
    return mid


def _expectation(r, node, where, mission_ids, max_ticks):
    e = r.mapping(node, where, set(EXPECTATIONS))
    if len(e) != 1:
        r.fail(node, where, 'needs exactly one of %s' % ', '.join(sorted(EXPECTATIONS)))
    kind, v = next(iter(e.items()))
    required, optional = EXPECTATIONS[kind]
    w = '%s.%s' % (where, kind)
    if isinstance(v, yaml.ScalarNode) and v.value in ('', 'null', '~') and not required:
        fields = {}
    else:
        fields = r.mapping(v, w, required | set(optional), required=tuple(sorted(required)))
    out = {'kind': kind, 'line': node.start_mark.line + 1}
    out.update(optional)
    for key, n in fields.items():
        kw = '%s.%s' % (w, key)
        if key in ('mission', 'after_mission'):
            out[key] = _mission_ref(r, n, kw, mission_ids)
        elif key in ('state', 'until_phase', 'after_state'):
            out[key] = r.choice(n, kw, STATES)
        elif key == 'states':
            out[key] = [r.choice(s, '%s[%d]' % (kw, i), STATES)
                        for i, s in enumerate(r.sequence(n, kw))]
        elif key in ('settle_ticks', 'grace_ticks'):
            out[key] = r.number(n, kw, 0, max_ticks, integer=True)
        elif key in ('by_tick', 'at_tick'):
            out[key] = r.number(n, kw, 0, max_ticks, integer=True)
        else:
            out[key] = r.number(n, kw, 0)
    if 'min' in out and 'max' in out and out['min'] > out['max']:
        r.fail(node, w, 'min %s > max %s' % (out['min'], out['max']))
    return out


def describe(expectation):
    """One line naming an expectation, e.g. 'expect[0] mission_state mission 7 DONE by tick
    2000 (line 31)'."""
    e = dict(expectation)
    parts = [e.pop('kind')]
    line = e.pop('line', None)
    parts += ['%s=%s' % (k, e[k]) for k in sorted(e) if not k.startswith('_')]
    return ' '.join(parts) + (' (line %d)' % line if line else '')
