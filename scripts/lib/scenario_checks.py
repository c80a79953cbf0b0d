"""The expectations of a scenario (scenario_format.py) checked on what a run did: a RunLog of
positions per tick, mission statuses, object moves and the recorder's mission metrics. Each
check returns (passed, measured): the measured value is printed beside pass / fail."""

import math

import experiment_presets as presets


class RunLog(object):
    """What a run did. positions: {tick: {robot id: (x, y, theta_deg)}} of physical robots;
    statuses: [(mission id, state name, tick)] as the robots reported them; object_moves:
    [(tick, mission id, x, y)]; metrics: {mission id: {column: value}} from missions.csv;
    params: world_size_m, robot_radius_m, local_range_m."""

    def __init__(self, positions, statuses, object_moves=(), metrics=None, params=None):
        self.positions = positions
        self.statuses = list(statuses)
        self.object_moves = sorted(object_moves)
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
                if m == mission_id and s in ('DONE', 'ABORTED', 'REJECTED')]
        return min(ends) if ends else None


def check(e, log, scenario, second=None):
    kind = e['kind']
    if kind == 'mission_state':
        tick = log.first_state_tick(e['mission'], e['state'])
        reached = [s for m, s, _ in log.statuses if m == e['mission']]
        measured = '%s at tick %s (states %s)' % (e['state'], tick, ' '.join(reached) or 'none')
        return tick is not None and tick <= e['by_tick'], measured
    if kind == 'in_arena':
        size = log.params['world_size_m']
        worst, where = _worst(log, lambda x, y: max(-x, -y, x - size, y - size, 0.0))
        return worst <= e['tolerance_m'], 'farthest outside %.4f m%s' % (worst, where)
    if kind == 'no_overlap':
        return _overlap(e, log)
    if kind == 'no_intrusion':
        return _intrusion(e, log, scenario)
    if kind == 'swarm_count':
        pts = log.positions.get(e['at_tick'])
        if pts is None:
            return False, 'no positions at tick %d' % e['at_tick']
        count = presets.components(list(pts.values()), log.params['local_range_m'])[0]
        return e['min'] <= count <= e['max'], '%d swarm(s) at tick %d' % (count,
                                                                         e['at_tick'])
    if kind in ('transport_ticks', 'slip_per_robot_m'):
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
        same_status = log.statuses == second.statuses
        measured = '%d of %d ticks differ%s' % (
            len(diffs), len(set(log.positions) | set(second.positions)),
            ('' if same_status else '; statuses differ') +
            (' (first: tick %d)' % diffs[0] if diffs else ''))
        return not diffs and same_status and bool(log.positions), measured
    raise ValueError('unknown expectation %r' % kind)


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
    """No robot a mission does not assign is inside its object (deeper than tolerance_m) from
    the tick the order is given until the mission ended: the object is a danger zone for them."""
    worst, where = 0.0, ''
    for m in scenario['missions']:
        if not m['object']:
            continue
        cx, cy, sx, sy = m['object']
        start = m['at_tick']
        end = log.end_tick(m['id'])
        moves = [(t, x, y) for t, mid, x, y in log.object_moves if mid == m['id']]
        assigned = set(m['robot_ids'])
        k = 0
        for tick in log.ticks():
            if tick < start or (end is not None and tick >= end):
                continue
            while k < len(moves) and moves[k][0] <= tick:
                _, cx, cy = moves[k]
                k += 1
            for rid, p in log.positions[tick].items():
                if rid in assigned:
                    continue
                depth = min(sx / 2.0 - abs(p[0] - cx), sy / 2.0 - abs(p[1] - cy))
                if depth > worst:
                    worst, where = depth, ' (robot %d in mission %d\'s object, tick %d)' % (
                        rid, m['id'], tick)
    return worst <= e['tolerance_m'], 'deepest intrusion %.4f m%s' % (worst, where)
