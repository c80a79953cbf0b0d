"""The scenario format (docs/scenarios.md): a swarm scenario as data - the world, the missions
with the tick each is sent at, timed events and the expectations with their tolerances.

parse(text, path) returns the scenario as plain dicts, or raises ScenarioError with one message
naming the file, the line and the key ("thesis.yaml:12: missions[0].leaders: ..."), before
anything is started."""

import difflib
import math
import os

import yaml

# The package's config/ folder: world.base_config names a file of it, and its swarm.yaml lists
# every /swarm key (with the kind of its value) that world.config may set.
CONFIG_DIR = os.path.abspath(os.path.join(os.path.dirname(__file__), '..', '..', 'config'))
# /swarm keys the nodes read that config/swarm.yaml leaves out (their default applies).
EXTRA_CONFIG_KEYS = {'radio_loss': 0.0}

DEPLOYS = ('process', 'host', 'host_sim', 'hardware')
CLOCKS = ('lockstep', 'realtime')
PLACEMENTS = ('random', 'corner', 'file')
STATES = ('QUEUED', 'GATHERING', 'LOADING', 'TRANSPORT', 'UNLOADING', 'DONE', 'ABORTED',
          'REJECTED')
FINAL_STATES = ('DONE', 'ABORTED', 'REJECTED')  # a mission's end
EVENT_KINDS = ('freeze', 'continue', 'kill', 'spawn', 'object_update', 'signal', 'statist',
               'remove_statist', 'odom_stop')
# deploy: hardware - the stand-in's bases (docs/hardware.md): their keys with defaults, and the
# events they play.
BASES_KEYS = {'odom_rate_hz': 50.0, 'position_noise_m': 0.0, 'heading_noise_deg': 0.0,
              'heading_drift_deg': 0.0}
HARDWARE_EVENTS = ('odom_stop', 'freeze', 'continue')
SIGNALS = ('LOADED', 'UNLOADED')
# Expectation kind -> (required keys, optional keys with defaults).
EXPECTATIONS = {
    'mission_state': ({'mission', 'state', 'by_tick'}, {}),
    'no_intrusion': (set(), {'tolerance_m': 0.0, 'grace_ticks': 0, 'until_phase': None}),
    'no_overlap': (set(), {'tolerance_m': 0.0}),
    'in_arena': (set(), {'tolerance_m': 0.0, 'inset_m': 0.0}),
    'moved': (set(), {'min_m': 0.0}),
    'swarm_count': ({'at_tick'}, {'min': 1, 'max': 65535}),
    'robot_count': ({'at_tick'}, {'min': 0, 'max': 65535}),
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
    # The mission's robots' paths (each tick's move) until it reported until_state.
    'robots_clear_of_zones': ({'mission'}, {'tolerance_m': 0.0, 'until_state': 'LOADING'}),
    'centroid_near': ({'at_tick', 'x', 'y'}, {'min_m': 0.0, 'max_m': float('inf')}),
    # How much nearer (x, y) the robots' centroid came from from_tick to to_tick (its distance
    # then minus its distance at to_tick; negative when it went away): within [min_m, max_m].
    'centroid_approach': ({'x', 'y', 'from_tick', 'to_tick'},
                          {'min_m': -float('inf'), 'max_m': float('inf')}),
    # Each robot's distance to its nearest other robot at at_tick: every one of them within
    # [min_nn_m, max_nn_m], and their coefficient of variation (std / mean) at most max_cv.
    'spacing': ({'at_tick'}, {'min_nn_m': 0.0, 'max_nn_m': float('inf'),
                              'max_cv': float('inf')}),
    # At a tick: at_tick, or the tick `mission` first reported `state`.
    'robot_near': ({'robot', 'x', 'y'}, {'min_m': 0.0, 'max_m': float('inf'), 'at_tick': None,
                                         'mission': None, 'state': None}),
    'swarm_of': ({'robot'}, {'min_fraction': 0.0, 'max_fraction': 1.0, 'at_tick': None,
                             'mission': None, 'state': None}),
    # Robots [from, to) over the ticks [from_tick, to_tick]: each drives a path (the sum of its
    # per-tick moves) of at most tolerance_m (stands), of more than min_m (drives; any: true
    # when one of them is enough). stands with for_ticks N: over some N consecutive moves
    # (ticks t..t+N) within [from_tick, to_tick], the same for all of them.
    'stands': ({'robots', 'from_tick', 'to_tick'}, {'tolerance_m': 0.0, 'for_ticks': None}),
    'drives': ({'robots', 'from_tick', 'to_tick', 'min_m'}, {'any': False}),
}
# Expectations measured at one tick: at_tick or (mission, state), exactly one of them.
AT_A_TICK = ('robot_near', 'swarm_of')
TOP_KEYS = {'name', 'description', 'world', 'max_ticks', 'missions', 'events', 'expect'}
WORLD_KEYS = {'robots', 'seed', 'placement', 'placement_file', 'config', 'base_config',
              'danger_zones', 'deploy', 'clock', 'bases'}
MISSION_KEYS = {'at_tick', 'id', 'robots_from', 'robots_to', 'robot_ids', 'leaders', 'object',
                'target', 'mode', 'recruit'}


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
                if len(allowed) <= 20:
                    known = 'allowed: %s' % ', '.join(sorted(allowed))
                else:  # /swarm's keys: the near ones, and where the rest are
                    near = difflib.get_close_matches(str(key), sorted(allowed), 3)
                    known = '%sthe keys are those of config/swarm.yaml' % (
                        'did you mean %s? ' % ' or '.join(near) if near else '')
                self.fail(key_node, '%s.%s' % (where, key) if where else key,
                          'unknown key (%s)' % known)
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
    event_nodes = r.sequence(top['events'], 'events') if 'events' in top else []
    s['events'] = [_event(r, n, 'events[%d]' % i, robots, s['max_ticks'], ids)
                   for i, n in enumerate(event_nodes)]
    hardware = s['world']['deploy'] == 'hardware'
    for i, e in enumerate(s['events']):
        if (e['kind'] not in HARDWARE_EVENTS) if hardware else e['kind'] == 'odom_stop':
            r.fail(event_nodes[i], 'events[%d].%s' % (i, e['kind']),
                   'world.deploy: hardware plays only %s; odom_stop only there'
                   % ', '.join(HARDWARE_EVENTS))
    _robots_over_time(r, event_nodes, s['events'], robots)
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
           'config': {}, 'danger_zones': None, 'placement_file': '', 'bases': {}}
    if 'bases' in w:
        b = r.mapping(w['bases'], 'world.bases', set(BASES_KEYS))
        out['bases'] = {k: r.number(v, 'world.bases.' + k, 0.0, 1000.0) for k, v in b.items()}
    if 'bases' in w and out['deploy'] != 'hardware':
        r.fail(w['bases'], 'world.bases', 'only with deploy: hardware')
    if out['deploy'] == 'hardware' and out['clock'] != 'realtime':
        r.fail(w['deploy'], 'world.deploy', 'hardware runs on the wall clock: needs clock: realtime')
    base = os.path.join(CONFIG_DIR, out['base_config'])
    if not os.path.isfile(base):
        r.fail(w.get('base_config'), 'world.base_config',
               'no file %r in %s' % (out['base_config'], CONFIG_DIR))
    if 'config' in w:
        out['config'] = _config(r, w['config'], base)
    if 'danger_zones' in w:
        zones = r.sequence(w['danger_zones'], 'world.danger_zones')
        out['danger_zones'] = [_zone(r, z, 'world.danger_zones[%d]' % i)
                               for i, z in enumerate(zones)]
    if out['placement'] == 'file':
        if 'placement_file' not in w:
            r.fail(node, 'world.placement_file', 'required with placement: file')
        out['placement_file'] = str(r.value(w['placement_file'], 'world.placement_file'))
        path = out['placement_file']
        if not os.path.isabs(path) and r.path != '<scenario>':
            path = os.path.join(os.path.dirname(os.path.abspath(r.path)), path)
        if os.path.isabs(path) and not os.path.isfile(path):
            r.fail(w['placement_file'], 'world.placement_file', 'no file %s' % path)
    return out


def _zone(r, node, where):
    """A static danger zone as config/obstacles.yaml writes it: {shape: rect, x, y, size_x,
    size_y} or {shape: circle, x, y, radius}, sizes > 0."""
    if not isinstance(node, yaml.MappingNode):
        r.fail(node, where, 'must be a mapping with a shape of rect or circle')
    shape_node = dict((k.value, v) for k, v in node.value).get('shape')
    if shape_node is None:
        r.fail(node, where, "missing 'shape' (rect or circle)")
    shape = r.choice(shape_node, where + '.shape', ('rect', 'circle'))
    sizes = ('size_x', 'size_y') if shape == 'rect' else ('radius',)
    z = r.mapping(node, where, {'shape', 'x', 'y'} | set(sizes),
                  required=('shape', 'x', 'y') + sizes)
    out = {'shape': shape}
    for key in ('x', 'y'):
        out[key] = r.number(z[key], '%s.%s' % (where, key))
    for key in sizes:
        out[key] = r.number(z[key], '%s.%s' % (where, key), 1e-9)
    return out


def _kind(value):
    if isinstance(value, bool):
        return 'true or false'
    if isinstance(value, (int, float)):
        return 'a number'
    if isinstance(value, str):
        return 'a string'
    if isinstance(value, list):
        return 'a list'
    return 'a mapping'


def _config(r, node, base):
    """world.config: /swarm keys over the base config. A key neither config/swarm.yaml nor the
    base config knows, or a value of another kind than there (a number for a number, true /
    false for a flag, ...), is an error naming its line; the nodes check the ranges."""
    known = dict(EXTRA_CONFIG_KEYS)
    for path in (os.path.join(CONFIG_DIR, 'swarm.yaml'), base):
        with open(path) as f:
            known.update(yaml.safe_load(f) or {})
    fields = r.mapping(node, 'world.config', set(known))
    out = {}
    for key, n in fields.items():
        where = 'world.config.%s' % key
        if key == 'danger_zones':
            out[key] = [_zone(r, z, '%s[%d]' % (where, i))
                        for i, z in enumerate(r.sequence(n, where))]
            continue
        v = r.plain(n)
        want = _kind(known[key])
        if _kind(v) != want or (want == 'a number' and not math.isfinite(v)):
            r.fail(n, where, 'must be %s (as in config/swarm.yaml) but is %r'
                   % ('a finite number' if want == 'a number' else want, v))
        out[key] = v
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
    if 'recruit' in m:
        # Statist as dispatcher (SPEC 9.4): no robots named; the first N to enter the object.
        if 'robot_ids' in m or 'robots_from' in m or 'robots_to' in m:
            r.fail(m['recruit'], where + '.recruit', 'names no robots: give no robot_ids or range')
        if out['object'] is None:
            r.fail(node, where, 'recruit needs an object (the robots are those that enter it)')
        out['recruit'] = r.number(m['recruit'], where + '.recruit', 1, 65535, integer=True)
        out['robot_ids'] = []
        if out['leaders'] > out['recruit']:
            r.fail(m['leaders'], where + '.leaders', 'more leaders than recruit')
        return out
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
    elif kind == 'odom_stop':
        s = r.mapping(v, w, {'robot', 'ticks'}, required=('robot', 'ticks'))
        out.update(robot=r.number(s['robot'], w + '.robot', 0, 65535, integer=True),
                   ticks=r.number(s['ticks'], w + '.ticks', 1, 10 ** 7, integer=True))
    elif kind == 'signal':
        s = r.mapping(v, w, {'mission', 'event'}, required=('mission', 'event'))
        out.update(mission=_mission_ref(r, s['mission'], w + '.mission', mission_ids),
                   event=r.choice(s['event'], w + '.event', SIGNALS))
    return out


def _robots_over_time(r, nodes, events, robots):
    """A kill names a robot in the world at its tick, a spawn one that is not (robots 0..N-1
    from the start, then the spawns and kills in tick order, file order within a tick)."""
    alive = set(range(robots))
    order = sorted(range(len(events)), key=lambda i: (events[i]['at_tick'], i))
    for i in order:
        e = events[i]
        if e['kind'] not in ('spawn', 'kill'):
            continue
        where = 'events[%d].%s' % (i, e['kind'])
        node = dict((k.value, v) for k, v in nodes[i].value)[e['kind']]
        if e['kind'] == 'kill' and e['robot'] not in alive:
            r.fail(node, where, 'no robot %d in the world at tick %d (world.robots: 0..%d, then '
                   'the spawns and kills before it)' % (e['robot'], e['at_tick'], robots - 1))
        if e['kind'] == 'spawn' and e['robot'] in alive:
            r.fail(node, where, 'robot %d is in the world already at tick %d'
                   % (e['robot'], e['at_tick']))
        (alive.discard if e['kind'] == 'kill' else alive.add)(e['robot'])


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
        elif key in ('state', 'until_phase', 'after_state', 'until_state'):
            out[key] = r.choice(n, kw, STATES)
        elif key == 'states':
            out[key] = [r.choice(s, '%s[%d]' % (kw, i), STATES)
                        for i, s in enumerate(r.sequence(n, kw))]
        elif key in ('settle_ticks', 'grace_ticks'):
            out[key] = r.number(n, kw, 0, max_ticks, integer=True)
        elif key == 'for_ticks':
            out[key] = r.number(n, kw, 1, max_ticks, integer=True)
        elif key in ('by_tick', 'at_tick', 'from_tick', 'to_tick'):
            out[key] = r.number(n, kw, 0, max_ticks, integer=True)
        elif key == 'robots':
            out[key] = _range(r, n, kw, None)
        elif key == 'any':
            out[key] = r.value(n, kw)
            if not isinstance(out[key], bool):
                r.fail(n, kw, 'must be true or false but is %r' % out[key])
        elif key == 'robot':
            out[key] = r.number(n, kw, 0, 65535, integer=True)
        elif key in ('min_fraction', 'max_fraction'):
            out[key] = r.number(n, kw, 0.0, 1.0)
        elif kind == 'centroid_approach' and key in ('min_m', 'max_m'):
            out[key] = r.number(n, kw)  # negative: it went away
        else:
            out[key] = r.number(n, kw, 0)
    if 'min' in out and 'max' in out and out['min'] > out['max']:
        r.fail(node, w, 'min %s > max %s' % (out['min'], out['max']))
    for lo, hi in (('min_m', 'max_m'), ('min_fraction', 'max_fraction')):
        if lo in out and hi in out and out[lo] > out[hi]:
            r.fail(node, w, '%s %s > %s %s' % (lo, out[lo], hi, out[hi]))
    if 'from_tick' in out and out['from_tick'] >= out['to_tick']:
        r.fail(node, w, 'from_tick %d must be < to_tick %d' % (out['from_tick'], out['to_tick']))
    if out.get('for_ticks') is not None and out['for_ticks'] > out['to_tick'] - out['from_tick']:
        r.fail(node, w, 'for_ticks %d is longer than ticks %d..%d'
               % (out['for_ticks'], out['from_tick'], out['to_tick']))
    if kind in AT_A_TICK:
        by_state = out['mission'] is not None or out['state'] is not None
        if (out['at_tick'] is None) == (not by_state) or \
                (by_state and (out['mission'] is None or out['state'] is None)):
            r.fail(node, w, 'needs either at_tick or mission and state (the tick the mission '
                   'first reported that state)')
    return out


def describe(expectation):
    """One line naming an expectation, e.g. 'expect[0] mission_state mission 7 DONE by tick
    2000 (line 31)'."""
    e = dict(expectation)
    parts = [e.pop('kind')]
    line = e.pop('line', None)
    parts += ['%s=%s' % (k, e[k]) for k in sorted(e) if not k.startswith('_')]
    return ' '.join(parts) + (' (line %d)' % line if line else '')
