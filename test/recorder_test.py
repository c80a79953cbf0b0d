#!/usr/bin/env python3
"""The recorder end to end: a lock-step swarm with recorder:=true runs a transport mission and
then a leader-only mission to DONE; /flock/stats arrives; after shutdown the CSV files have the documented columns and
values that are finite, in range and consistent with the mission's reported phases."""

import csv
import math
import os
import shutil
import sys
import tempfile
import threading
import unittest

import rospy
import rostest
from swarm_transport.msg import Swarm_Stats
from swarm_transport.srv import Submit_Mission

import swarm_testing as st

SWARM_HEADER = ['tick', 'sim_time_s', 'robots', 'swarm_count', 'largest_swarm']
MISSIONS_HEADER = [
    'mission_id', 'kind', 'assigned', 'leaders', 'final_state', 'queued_tick', 'gathering_tick',
    'loading_tick', 'transport_tick', 'unloading_tick', 'done_tick', 'transport_ticks',
    'slip_per_robot_m', 'distance_per_robot_m', 'leader_waits', 'path_fraction_attached',
    'leader_swarm_at_arrival', 'object_error_m', 'leader_contact', 'loading_nn_cv']
RUN_HEADER = ['run_name', 'seed', 'robots', 'ticks', 'sim_time_s', 'samples',
              'mean_swarm_count', 'final_swarm_count', 'missions_done', 'missions_aborted',
              'coverage_fraction', 'nn_spacing_mean_m', 'nn_spacing_cv']


def read_csv(path):
    """(header, rows as dicts); (None, []) when the file is missing."""
    if not os.path.exists(path):
        return None, []
    with open(path) as f:
        rows = list(csv.reader(f))
    if not rows:
        return None, []
    return rows[0], [dict(zip(rows[0], r)) for r in rows[1:]]


def number(text):
    value = float(text)
    if not math.isfinite(value):
        raise ValueError('not finite: %r' % text)
    return value


class StatsLog(object):
    def __init__(self):
        self.lock = threading.Lock()
        self.items = []
        self.sub = rospy.Subscriber('/flock/stats', Swarm_Stats, self._cb, queue_size=100)

    def _cb(self, msg):
        with self.lock:
            self.items.append(msg)

    def all(self):
        with self.lock:
            return list(self.items)


class Recorder(unittest.TestCase):

    def setUp(self):
        self.dir = tempfile.mkdtemp(prefix='recorder_test_')

    def tearDown(self):
        shutil.rmtree(self.dir, ignore_errors=True)

    def test_transport_mission_is_recorded(self):
        g = lambda k: rospy.get_param('~' + k)  # noqa: E731
        robots, timeout, mid = g('robots'), g('timeout_s'), g('mission_id')
        obj = (g('object_x'), g('object_y'), g('object_size_x'), g('object_size_y'))
        target = (g('target_x'), g('target_y'))
        run_dir = os.path.join(self.dir, g('run_name'))
        missions_csv = os.path.join(run_dir, 'missions.csv')
        log, status, stats = st.PositionLog(), st.StatusLog(), StatsLog()
        # Observers: this test's PositionLog and the recorder see every tick from the first.
        swarm = st.launch_swarm(robots=robots, seed=g('seed'), lockstep=True, max_ticks=0,
                                observers=1, recorder=True, record_dir=self.dir,
                                run_name=g('run_name'))
        try:
            self.assertTrue(log.wait_tick(3, timeout), 'the swarm never ticked')
            submit = rospy.ServiceProxy('/mission_dispatcher/submit', Submit_Mission)
            submit.wait_for_service(timeout)
            answer = submit(st.mission(mid, g('from'), g('to'), g('leaders'), obj, target))
            self.assertEqual(answer.code, 0, answer.message)
            self.assertTrue(st.wait_for(lambda: status.final(mid), timeout),
                            'mission %d did not finish; states so far %s'
                            % (mid, status.states(mid)))
            self.assertIsNotNone(status.first(mid, 5), 'mission ended %s' % status.states(mid))
            # The row is written once the DONE status and the frames up to arrival are in.
            self.assertTrue(st.wait_for(lambda: len(read_csv(missions_csv)[1]) >= 1, timeout),
                            'no row in missions.csv')
            # Then a leader-only mission [T7.3] for a robot outside the transport group.
            leader = g('leader/robot')
            only = st.mission(g('leader/mission_id'), leader, leader + 1, 1, (0.0, 0.0, 0.0, 0.0),
                              (g('leader/target_x'), g('leader/target_y')))
            answer = submit(only)
            self.assertEqual(answer.code, 0, answer.message)
            self.assertTrue(st.wait_for(lambda: len(read_csv(missions_csv)[1]) >= 2, timeout),
                            'no row of the leader-only mission in missions.csv; states %s'
                            % status.states(g('leader/mission_id')))
            done_tick = log.latest_tick()
            self.assertTrue(st.wait_for(
                lambda: any(s.tick >= done_tick for s in stats.all()), timeout),
                'no /flock/stats after the mission')
        finally:
            swarm.shutdown()
            log.close()
        # The recorder rewrites run.csv at shutdown (SIGINT): its final row has the mission.
        run_csv = os.path.join(run_dir, 'run.csv')
        self.assertTrue(st.wait_for(
            lambda: any(r.get('missions_done') == '2' for r in read_csv(run_csv)[1]), timeout))

        # /flock/stats
        received = stats.all()
        self.assertTrue(received)
        for s in received:
            self.assertEqual(s.robots, robots)
            self.assertTrue(1 <= s.swarm_count <= robots, s)
            self.assertTrue(1 <= s.largest_swarm <= robots, s)
            self.assertTrue(math.isfinite(s.sim_time), s)

        # swarm_count.csv: a sample at the first tick, then every sample_period_s.
        header, rows = read_csv(os.path.join(run_dir, 'swarm_count.csv'))
        self.assertEqual(header, SWARM_HEADER)
        self.assertGreaterEqual(len(rows), 2)
        previous = None
        for r in rows:
            tick, time_s = int(r['tick']), number(r['sim_time_s'])
            self.assertEqual(int(r['robots']), robots)
            self.assertTrue(1 <= int(r['swarm_count']) <= robots, r)
            self.assertTrue(int(r['swarm_count']) <= robots - int(r['largest_swarm']) + 1, r)
            self.assertTrue(1 <= int(r['largest_swarm']) <= robots, r)
            self.assertGreaterEqual(time_s, 0.0)
            if previous is not None:
                self.assertGreater(tick, previous[0])
                self.assertGreaterEqual(time_s - previous[1],
                                        g('sample_period_s') - g('float_tolerance'))
            previous = (tick, time_s)
        self.assertLessEqual(number(rows[0]['sim_time_s']), 3 * g('tick_period_s'),
                             'the first sample is not the first tick')
        samples = len(rows)

        # missions.csv: the transport mission, its phases as reported, then the leader's.
        header, rows = read_csv(missions_csv)
        self.assertEqual(header, MISSIONS_HEADER)
        self.assertEqual(len(rows), 2, rows)
        r, lead = rows
        self.assertEqual(int(r['mission_id']), mid)
        self.assertEqual(r['kind'], 'transport')
        self.assertEqual(int(r['assigned']), g('to') - g('from'))
        self.assertEqual(int(r['leaders']), g('leaders'))
        self.assertEqual(r['final_state'], 'DONE')
        phases = [int(r[k]) for k in ('queued_tick', 'gathering_tick', 'loading_tick',
                                      'transport_tick', 'unloading_tick', 'done_tick')]
        self.assertEqual(phases, sorted(phases), r)
        for name, state in (('gathering_tick', 1), ('loading_tick', 2), ('transport_tick', 3),
                            ('unloading_tick', 4), ('done_tick', 5)):
            self.assertEqual(int(r[name]), status.first(mid, state).tick, name)
        ticks = int(r['transport_ticks'])
        self.assertGreater(ticks, 0)
        self.assertEqual(ticks, int(r['unloading_tick']) - int(r['transport_tick']))
        slip, distance = number(r['slip_per_robot_m']), number(r['distance_per_robot_m'])
        self.assertGreaterEqual(slip, 0.0)
        # Robots carried the object from its start to the target: each drove at least its
        # share of the centroid's displacement.
        carried = math.hypot(obj[0] - target[0], obj[1] - target[1])
        self.assertGreaterEqual(distance, carried - g('goal_tolerance_m') - g('float_tolerance'))
        self.assertGreaterEqual(int(r['leader_waits']), 0)
        self.assertEqual(r['path_fraction_attached'], '')  # leader-only metrics
        self.assertEqual(r['leader_swarm_at_arrival'], '')
        error = number(r['object_error_m'])
        self.assertTrue(0.0 <= error <= g('goal_tolerance_m') + g('float_tolerance'), r)
        contact = number(r['leader_contact'])  # a fraction of the passive robots' ticks
        self.assertTrue(0.0 <= contact <= 1.0, r)

        # The leader-only row: leader metrics, no transport metrics.
        self.assertEqual(int(lead['mission_id']), g('leader/mission_id'))
        self.assertEqual(lead['kind'], 'leader')
        self.assertEqual((lead['assigned'], lead['leaders'], lead['final_state']),
                         ('1', '1', 'DONE'))
        for key in ('transport_ticks', 'slip_per_robot_m', 'distance_per_robot_m',
                    'leader_contact'):
            self.assertEqual(lead[key], '', key)
        self.assertLessEqual(int(lead['queued_tick']), int(lead['done_tick']))
        self.assertGreaterEqual(int(lead['leader_waits']), 0)
        self.assertTrue(0.0 <= number(lead['path_fraction_attached']) <= 1.0, lead)
        self.assertTrue(0 <= int(lead['leader_swarm_at_arrival']) <= robots - 1, lead)
        self.assertTrue(0.0 <= number(lead['object_error_m'])
                        <= g('goal_tolerance_m') + g('float_tolerance'), lead)

        # run.csv: one summary row.
        header, rows = read_csv(run_csv)
        self.assertEqual(header, RUN_HEADER)
        self.assertEqual(len(rows), 1, rows)
        r = rows[0]
        self.assertEqual(r['run_name'], g('run_name'))
        self.assertEqual(int(r['seed']), g('seed'))
        self.assertEqual(int(r['robots']), robots)
        self.assertGreaterEqual(int(r['ticks']), phases[-1])
        self.assertGreaterEqual(number(r['sim_time_s']), 0.0)
        self.assertEqual(int(r['samples']), samples)
        self.assertTrue(1.0 <= number(r['mean_swarm_count']) <= robots, r)
        self.assertTrue(1 <= int(r['final_swarm_count']) <= robots, r)
        self.assertEqual(int(r['missions_done']), 2)
        self.assertEqual(int(r['missions_aborted']), 0)
        rospy.loginfo('recorder: mission row %s', rows)


if __name__ == '__main__':
    rospy.init_node('recorder_test')
    rostest.rosrun('swarm_transport', 'recorder_files', Recorder, sys.argv)
