"""The expectations of a scenario (scenario_format.py) checked on what a run did: a RunLog of
positions per tick, mission statuses, object moves and the recorder's mission metrics. Each
check returns (passed, measured): the measured value is printed beside pass / fail."""

import math

from swarm_transport import core_metrics
from swarm_transport.scenario_format import FINAL_STATES


class RunLog(object):
    """What a run did. positions: {tick: {robot id: (x, y, theta_deg)}} of physical robots;
    statuses: [(mission id, state name, tick)] as the robots reported them; unstamped: the
    indices of statuses that carried no tick of their own (their tick is the observer's latest,
    which depends on when the status arrived); objects: {tick:
    {mission id: (x, y, size_x, size_y)}}, the live objects as the simulator tracks them
    (/flock/objects); metrics: {mission id: {column: value}} from missions.csv; params:
    world_size_m, robot_radius_m, local_range_m."""

    def __init__(self, positions, statuses, objects=None, metrics=None, params=None,
                 robot_states=None, unstamped=()):
        self.unstamped = set(unstamped)
        self.robot_states = robot_states  # {id: (mission ids, zone ids, frozen)} at the end
        self.positions = positions
        self.statuses = list(statuses)
        self.objects = objects or {}
        self.metrics = metrics or {}
        self.params = dict({'world_size_m': 11.088889, 'robot_radius_m': 0.05,
                            'local_range_m': 1.0}, **(params or {}))

    def ticks(self):
        return sorted(self.positions)

    def first_state_tick(self, mission_id, state):
        ticks = [t for m, s, t in self.statuses if m == mission_id and s == state]
        return min(ticks) if ticks else None

    def end_tick(self, mission_id):
        ends = [t for m, s, t in self.statuses
                if m == mission_id and s in FINAL_STATES]
        return min(ends) if ends else None


def nearest_distances(points):
    """Each point's distance to its nearest other point (empty for fewer than two)."""
    if len(points) < 2:
        return []
    return [min(math.hypot(p[0] - q[0], p[1] - q[1]) for j, q in enumerate(points) if j != i)
            for i, p in enumerate(points)]


def _centroid(log, tick):
    """The robots' centroid (x, y) at `tick`, None without positions."""
    pts = log.positions.get(tick)
    if not pts:
        return None
    return (sum(p[0] for p in pts.values()) / len(pts), sum(p[1] for p in pts.values()) / len(pts))


def _spacing(e, log):
    pts = log.positions.get(e['at_tick'])
    if not pts or len(pts) < 2:
        return False, 'fewer than two robots at tick %d' % e['at_tick']
    nearest = nearest_distances(list(pts.values()))
    mean = sum(nearest) / len(nearest)
    cv = (math.sqrt(sum((d - mean) ** 2 for d in nearest) / len(nearest)) / mean
          if mean > 0 else float('inf'))
    ok = e['min_nn_m'] <= min(nearest) and max(nearest) <= e['max_nn_m'] and cv <= e['max_cv']
    return ok, 'nearest neighbours %.3f-%.3f m (mean %.3f, cv %.4f) at tick %d' % (
        min(nearest), max(nearest), mean, cv, e['at_tick'])


def check(e, log, scenario, second=None):
    kind = e['kind']
    if kind == 'mission_state':
        tick = log.first_state_tick(e['mission'], e['state'])
        reached = [s for m, s, _ in log.statuses if m == e['mission']]
        measured = '%s at tick %s (states %s)' % (e['state'], tick, ' '.join(reached) or 'none')
        return tick is not None and tick <= e['by_tick'], measured
    if kind == 'in_arena':
        lo, hi = e['inset_m'], log.params['world_size_m'] - e['inset_m']
        worst, where = _worst(log, lambda x, y: max(lo - x, lo - y, x - hi, y - hi, 0.0))
        return worst <= e['tolerance_m'], 'farthest outside %.4f m%s' % (worst, where)
    if kind == 'no_overlap':
        return _overlap(e, log)
    if kind == 'no_intrusion':
        return _intrusion(e, log, scenario)
    if kind == 'robot_count':
        pts = log.positions.get(e['at_tick'])
        if pts is None:
            return False, 'no positions at tick %d' % e['at_tick']
        return e['min'] <= len(pts) <= e['max'], '%d robot(s) at tick %d: %s' % (
            len(pts), e['at_tick'], _ids(sorted(pts)))
    if kind == 'swarm_count':
        pts = log.positions.get(e['at_tick'])
        if pts is None:
            return False, 'no positions at tick %d' % e['at_tick']
        count = core_metrics.components(list(pts.values()), log.params['local_range_m'])[0]
        return e['min'] <= count <= e['max'], '%d swarm(s) at tick %d' % (count,
                                                                         e['at_tick'])
    if kind == 'phases':
        reached = [s for m, s, _ in log.statuses if m == e['mission']]
        return reached == e['states'], 'states %s' % (' '.join(reached) or 'none')
    if kind == 'moved':
        ticks = log.ticks()
        if not ticks:
            return False, 'no positions'
        first, last = log.positions[ticks[0]], log.positions[ticks[-1]]
        least, who = float('inf'), None
        for rid, p in first.items():
            if rid in last:
                d = math.hypot(last[rid][0] - p[0], last[rid][1] - p[1])
                if d < least:
                    least, who = d, rid
        return who is not None and least > e['min_m'], \
            'least start-to-end displacement %.4f m (robot %s)' % (least, who)
    if kind == 'phase_order':
        tick = log.first_state_tick(e['mission'], e['state'])
        before = log.first_state_tick(e['after_mission'], e['after_state'])
        measured = 'mission %d %s at tick %s, mission %d %s at tick %s' % (
            e['mission'], e['state'], tick, e['after_mission'], e['after_state'], before)
        return tick is not None and before is not None and tick >= before, measured
    if kind == 'released':
        if log.robot_states is None:
            return False, 'no robot states were read'
        held = {rid: s for rid, s in log.robot_states.items() if s[0] or s[1] or s[2]}
        return not held, ('every robot of %d holds no mission, no zone and is not frozen'
                          % len(log.robot_states) if not held else
                          'robot(s) still holding: %s' % sorted(held.items())[:5])
    if kind == 'centroid_near':
        c = _centroid(log, e['at_tick'])
        if c is None:
            return False, 'no positions at tick %d' % e['at_tick']
        d = math.hypot(c[0] - e['x'], c[1] - e['y'])
        return e['min_m'] <= d <= e['max_m'], 'centroid (%.2f, %.2f) at tick %d, %.2f m away' % (
            c[0], c[1], e['at_tick'], d)
    if kind == 'centroid_approach':
        ends = [_centroid(log, e[t]) for t in ('from_tick', 'to_tick')]
        if None in ends:
            return False, 'no positions at tick %d' % e['to_tick' if ends[0] else 'from_tick']
        d = [math.hypot(c[0] - e['x'], c[1] - e['y']) for c in ends]
        came = d[0] - d[1]
        return e['min_m'] <= came <= e['max_m'], (
            'centroid %.2f m nearer from tick %d to %d (%.2f -> %.2f m away)'
            % (came, e['from_tick'], e['to_tick'], d[0], d[1]))
    if kind == 'spacing':
        return _spacing(e, log)
    if kind in ('robot_near', 'swarm_of'):
        return _at_a_tick(e, log)
    if kind in ('stands', 'drives'):
        return _paths(e, log)
    if kind == 'object_clear_of_zones':
        return _object_clear(e, log, scenario)
    if kind == 'robots_clear_of_zones':
        return _robots_clear(e, log, scenario)
    if kind == 'gathered':
        return _gathered(e, log, scenario)
    if kind == 'still_while_frozen':
        return _still(e, log, scenario)
    if kind in ('transport_ticks', 'slip_per_robot_m', 'object_error_m'):
        row = log.metrics.get(e['mission'], {})
        value = row.get(kind)
        if value is None or value == '' or (isinstance(value, float) and math.isnan(value)):
            return False, 'no %s for mission %d (it did not carry)' % (kind, e['mission'])
        value = float(value)
        return e['min'] <= value <= e['max'], '%s %.4g' % (kind, value)
    if kind == 'reproducible':
        if second is None:
            return False, 'no second run'
        diffs = [t for t in sorted(set(log.positions) | set(second.positions))
                 if log.positions.get(t) != second.positions.get(t)]
        status_diff = _status_difference(log, second)
        same_status = not status_diff
        measured = '%d of %d ticks differ%s' % (
            len(diffs), len(set(log.positions) | set(second.positions)),
            ('' if same_status else '; statuses differ: %s' % status_diff) +
            (' (first: tick %d)' % diffs[0] if diffs else ''))
        return not diffs and same_status and bool(log.positions), measured
    raise ValueError('unknown expectation %r' % kind)


def _reported(log):
    """{mission id: [(state, tick)]} in the order the statuses arrived; a status without a tick
    of its own has None: two runs of one scenario are compared on what their robots and
    dispatcher said, not on when an observer happened to hear it (statuses of different missions
    come over different connections, and an unstamped one takes the observer's latest tick)."""
    per_mission = {}
    for i, (mission_id, state, tick) in enumerate(log.statuses):
        per_mission.setdefault(mission_id, []).append(
            (state, None if i in log.unstamped else tick))
    return per_mission


def _status_difference(log, second):
    """'' when both runs reported the same statuses per mission, else the first difference."""
    a, b = _reported(log), _reported(second)
    for mission_id in sorted(set(a) | set(b)):
        ours, theirs = a.get(mission_id, []), b.get(mission_id, [])
        if ours != theirs:
            at = next((i for i, (x, y) in enumerate(zip(ours, theirs)) if x != y),
                      min(len(ours), len(theirs)))
            return 'mission %d, status %d: %s vs %s' % (
                mission_id, at + 1, ours[at] if at < len(ours) else 'none',
                theirs[at] if at < len(theirs) else 'none')
    return ''


def _ids(ids):
    """Robot ids as ranges: [0, 1, 2, 5] -> '0-2, 5'."""
    runs = []
    for i in ids:
        if runs and i == runs[-1][1] + 1:
            runs[-1][1] = i
        else:
            runs.append([i, i])
    return ', '.join('%d' % a if a == b else '%d-%d' % (a, b) for a, b in runs) or 'none'


def _at_a_tick(e, log):
    """robot_near / swarm_of: one robot at at_tick, or at the tick its mission first reported
    a state."""
    if e['at_tick'] is not None:
        tick, when = e['at_tick'], 'tick %d' % e['at_tick']
    else:
        tick = log.first_state_tick(e['mission'], e['state'])
        if tick is None:
            return False, 'mission %d never reported %s' % (e['mission'], e['state'])
        when = 'tick %d (mission %d %s)' % (tick, e['mission'], e['state'])
    pts = log.positions.get(tick)
    if not pts or e['robot'] not in pts:
        return False, 'no position of robot %d at %s' % (e['robot'], when)
    if e['kind'] == 'robot_near':
        p = pts[e['robot']]
        d = math.hypot(p[0] - e['x'], p[1] - e['y'])
        return e['min_m'] <= d <= e['max_m'], 'robot %d at (%.2f, %.2f) at %s, %.3f m away' % (
            e['robot'], p[0], p[1], when, d)
    ids = sorted(pts)
    labels = core_metrics.components([pts[i] for i in ids], log.params['local_range_m'])[1]
    own = labels[ids.index(e['robot'])]
    others = len(ids) - 1
    with_it = sum(1 for i, label in zip(ids, labels) if label == own and i != e['robot'])
    fraction = with_it / float(others) if others else 1.0
    return e['min_fraction'] <= fraction <= e['max_fraction'], (
        '%d of the %d other robots in robot %d\'s swarm at %s (%.2f)'
        % (with_it, others, e['robot'], when, fraction))


def _paths(e, log):
    """stands / drives: the path each robot of [from, to) drove over [from_tick, to_tick] (the
    sum of its per-tick moves; a tick missing from the log shortens it to a chord). stands with
    for_ticks N: the N consecutive ticks within them in which the most driven robot drove least."""
    lo, hi = e['robots']
    frames = [(t, log.positions[t]) for t in range(e['from_tick'], e['to_tick'] + 1)
              if t in log.positions]
    if len(frames) < 2 or frames[0][0] != e['from_tick'] or frames[-1][0] != e['to_tick']:
        return False, 'no positions over ticks %d..%d' % (e['from_tick'], e['to_tick'])
    # Each robot's path from from_tick up to each tick of the window (a tick missing from the
    # log: the path up to the tick before it), so that any stretch's path is a difference.
    upto = {}
    for rid in range(lo, hi):
        if any(rid not in pts for _, pts in frames):
            return False, 'robot %d missing in ticks %d..%d' % (rid, e['from_tick'], e['to_tick'])
        upto[rid] = {e['from_tick']: 0.0}
        for (ta, a), (tb, b) in zip(frames, frames[1:]):
            for t in range(ta + 1, tb):
                upto[rid][t] = upto[rid][ta]
            upto[rid][tb] = upto[rid][ta] + math.hypot(b[rid][0] - a[rid][0],
                                                       b[rid][1] - a[rid][1])

    def most(a, b):  # the most driven path over ticks a..b, and its robot
        rid = max(upto, key=lambda i: upto[i][b] - upto[i][a])
        return upto[rid][b] - upto[rid][a], rid
    span = 'robots [%d, %d) over ticks %d..%d' % (lo, hi, e['from_tick'], e['to_tick'])
    if e['kind'] == 'stands' and e.get('for_ticks') is not None:
        n, tol = e['for_ticks'], e['tolerance_m']
        best = min((most(a, a + n) + (a,) for a in range(e['from_tick'], e['to_tick'] - n + 1)),
                   key=lambda w: w[0])
        if best[0] > tol:
            return False, '%s: the stillest %d ticks %d..%d, the most driven %.4f m (robot %d)' % (
                span, n, best[2], best[2] + n, best[0], best[1])
        a, b = best[2], best[2] + n  # widened as far as they stay within the tolerance
        while a > e['from_tick'] and most(a - 1, b)[0] <= tol:
            a -= 1
        while b < e['to_tick'] and most(a, b + 1)[0] <= tol:
            b += 1
        path, rid = most(a, b)
        return True, '%s: still over ticks %d..%d (%d asked), the most driven %.4f m (robot %d)' % (
            span, a, b, n, path, rid)
    path = {rid: up[e['to_tick']] for rid, up in upto.items()}
    if e['kind'] == 'stands':
        rid = max(path, key=lambda i: path[i])
        return path[rid] <= e['tolerance_m'], '%s: the most driven %.4f m (robot %d)' % (
            span, path[rid], rid)
    rid = (max if e['any'] else min)(path, key=lambda i: path[i])
    return path[rid] > e['min_m'], '%s: the %s driven %.4f m (robot %d)' % (
        span, 'most' if e['any'] else 'least', path[rid], rid)


def _worst(log, badness):
    worst, where = 0.0, ''
    for tick, pts in log.positions.items():
        for rid, p in pts.items():
            b = badness(p[0], p[1])
            if b > worst:
                worst, where = b, ' (robot %d, tick %d)' % (rid, tick)
    return worst, where


def _overlap(e, log):
    two_r = 2.0 * log.params['robot_radius_m']
    worst, where = 0.0, ''
    for tick, pts in log.positions.items():
        items = sorted(pts.items())
        for i in range(len(items)):
            for j in range(i + 1, len(items)):
                (a, pa), (b, pb) = items[i], items[j]
                if abs(pa[0] - pb[0]) >= two_r or abs(pa[1] - pb[1]) >= two_r:
                    continue
                depth = two_r - math.hypot(pa[0] - pb[0], pa[1] - pb[1])
                if depth > worst:
                    worst, where = depth, ' (robots %d and %d, tick %d)' % (a, b, tick)
    return worst <= e['tolerance_m'], 'deepest overlap %.4f m%s' % (worst, where)


def _intrusion(e, log, scenario):
    """No robot a mission does not assign is inside its object (deeper than tolerance_m) while
    the object is live (the simulator lists it): it is a danger zone for them. grace_ticks: a
    robot caught inside when the object appears may take that long to leave; until_phase: stop
    at the tick the mission reported that phase (in TRANSPORT the object moves onto robots that
    then flee it)."""
    assigned = {m['id']: set(m['robot_ids']) for m in scenario['missions']}
    listed = {}  # the tick each object was first listed: a robot there may take grace_ticks
    for tick in sorted(log.objects):
        for mid in log.objects[tick]:
            listed.setdefault(mid, tick)
    worst, where = 0.0, ''
    for tick, objects in log.objects.items():
        pts = log.positions.get(tick, {})
        for mid, (cx, cy, sx, sy) in objects.items():
            if tick < listed[mid] + e['grace_ticks']:
                continue
            if e['until_phase']:
                until = log.first_state_tick(mid, e['until_phase'])
                if until is not None and tick >= until:
                    continue
            for rid, p in pts.items():
                if rid in assigned.get(mid, ()):
                    continue
                depth = min(sx / 2.0 - abs(p[0] - cx), sy / 2.0 - abs(p[1] - cy))
                if depth > worst:
                    worst, where = depth, ' (robot %d in mission %d\'s object, tick %d)' % (
                        rid, mid, tick)
    return worst <= e['tolerance_m'], 'deepest intrusion %.4f m%s' % (worst, where)


def _mission(scenario, mid):
    return next(m for m in scenario['missions'] if m['id'] == mid)


def _gathered(e, log, scenario):
    """Every assigned robot was inside the object (up to tolerance_m outside) at the tick the
    mission reported LOADING (the first leader froze them there)."""
    tick = log.first_state_tick(e['mission'], 'LOADING')
    if tick is None:
        return False, 'no LOADING'
    obj = log.objects.get(tick, {}).get(e['mission'])
    if obj is None:
        return False, 'no object listed at tick %d' % tick
    cx, cy, sx, sy = obj
    worst, where = 0.0, ''
    for rid in _mission(scenario, e['mission'])['robot_ids']:
        p = log.positions.get(tick, {}).get(rid)
        if p is None:
            continue  # lost or killed
        out = max(abs(p[0] - cx) - sx / 2.0, abs(p[1] - cy) - sy / 2.0, 0.0)
        if out > worst:
            worst, where = out, ' (robot %d)' % rid
    return worst <= e['tolerance_m'], 'farthest outside at LOADING (tick %d) %.4f m%s' % (
        tick, worst, where)


def _still(e, log, scenario):
    """The assigned robots did not move (more than tolerance_m) from settle_ticks after LOADING
    until TRANSPORT: they were frozen for loading."""
    loading = log.first_state_tick(e['mission'], 'LOADING')
    transport = log.first_state_tick(e['mission'], 'TRANSPORT')
    if loading is None or transport is None:
        return False, 'no LOADING or no TRANSPORT'
    a, b = log.positions.get(loading + e['settle_ticks'], {}), log.positions.get(transport, {})
    worst, where = 0.0, ''
    for rid in _mission(scenario, e['mission'])['robot_ids']:
        if rid in a and rid in b:
            d = math.hypot(a[rid][0] - b[rid][0], a[rid][1] - b[rid][1])
            if d > worst:
                worst, where = d, ' (robot %d)' % rid
    return worst <= e['tolerance_m'], 'moved at most %.4f m between ticks %d and %d%s' % (
        worst, loading + e['settle_ticks'], transport, where)


def _overlap_depth(obj, zone):
    """How deep the rectangle obj = (x, y, size_x, size_y) overlaps a zone of the world's
    danger_zones (rect or circle, as in config/obstacles.yaml); 0 when apart."""
    x, y, sx, sy = obj
    if zone.get('shape') == 'rect':
        dx = (sx + zone['size_x']) / 2.0 - abs(x - zone['x'])
        dy = (sy + zone['size_y']) / 2.0 - abs(y - zone['y'])
        return max(0.0, min(dx, dy))
    if zone.get('shape') == 'circle':
        nx = min(max(zone['x'], x - sx / 2.0), x + sx / 2.0)
        ny = min(max(zone['y'], y - sy / 2.0), y + sy / 2.0)
        return max(0.0, zone['radius'] - math.hypot(zone['x'] - nx, zone['y'] - ny))
    raise ValueError('object_clear_of_zones knows rect and circle zones, not %r' % zone)


def _object_clear(e, log, scenario):
    """The mission's object (as the simulator tracks it) never overlapped a static danger zone
    of the world by more than tolerance_m (paths around danger, SPEC 9.8)."""
    zones = scenario['world']['danger_zones'] or []
    worst, where = 0.0, ''
    for tick, objects in log.objects.items():
        obj = objects.get(e['mission'])
        if obj is None:
            continue
        for k, zone in enumerate(zones):
            d = _overlap_depth(obj, zone)
            if d > worst:
                worst, where = d, ' (danger_zones[%d], tick %d)' % (k, tick)
    listed = sum(1 for objects in log.objects.values() if e['mission'] in objects)
    return worst <= e['tolerance_m'] and listed > 0, 'deepest overlap %.4f m%s over %d ticks' % (
        worst, where, listed)


def _point_depth(x, y, zone):
    """How deep the point (x, y) lies inside a zone of the world's danger_zones; 0 outside."""
    return _overlap_depth((x, y, 0.0, 0.0), zone)


# Points checked along each tick's move (its ends included): a move is at most a robot's speed
# (0.1 m), so a zone is missed only where it is thinner than a hundredth of that.
_MOVE_SAMPLES = 100


def _robots_clear(e, log, scenario):
    """The mission's robots never went deeper than tolerance_m into a static danger zone from
    the first tick until the tick the mission first reported until_state (the whole run when it
    never did): their positions and the straight moves between them (gathering around danger,
    issue 27)."""
    zones = scenario['world']['danger_zones'] or []
    ids = set(_mission(scenario, e['mission'])['robot_ids'])
    end = log.first_state_tick(e['mission'], e['until_state'])
    ticks = [t for t in log.ticks() if end is None or t <= end]
    worst, where, moves = 0.0, '', 0
    for before, tick in zip(ticks, ticks[1:]):
        a, b = log.positions[before], log.positions[tick]
        for rid in ids & set(a) & set(b):
            moves += 1
            for k in range(_MOVE_SAMPLES + 1):
                f = k / float(_MOVE_SAMPLES)
                x = a[rid][0] + f * (b[rid][0] - a[rid][0])
                y = a[rid][1] + f * (b[rid][1] - a[rid][1])
                for z, zone in enumerate(zones):
                    d = _point_depth(x, y, zone)
                    if d > worst:
                        worst, where = d, ' (robot %d, danger_zones[%d], tick %d)' % (rid, z, tick)
    return worst <= e['tolerance_m'] and moves > 0, (
        'deepest %.4f m%s over %d moves until tick %s' % (worst, where, moves, ticks[-1] if ticks
                                                          else None))
