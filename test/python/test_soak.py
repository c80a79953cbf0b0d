"""The pure parts of scripts/soak (issue 29): its fault schedule, the recorder rows it counts,
the memory and descriptor growth it reports and the checks of its bounded slice."""

import os
import tempfile
import unittest

from swarm_transport import soak, soak_faults, soak_missions


def result(**changes):
    base = {'ok': True, 'hung': 0, 'crashes': 0, 'lost_rows': 0, 'duplicate_rows': 0, 'done': 2,
            'fd_growth': 2, 'fd_growth_node': '/simulator',
            'fault_log': [{'kind': k, 'at_s': 1.0, 'effect': 'live missions: none'}
                          for k in soak_faults.KINDS]}
    base.update(changes)
    return base


class Schedule(unittest.TestCase):

    def test_every_kind_once_per_round_and_the_seed_repeats_it(self):
        a = soak_faults.Schedule(7, 12, 10.0, 20.0, first_s=30.0)
        b = soak_faults.Schedule(7, 12, 10.0, 20.0, first_s=30.0)
        first = [a.draw() for _ in range(12)]
        self.assertEqual(first, [b.draw() for _ in range(12)])
        n = len(soak_faults.KINDS)
        for r in range(2):
            self.assertEqual(sorted(f[1] for f in first[r * n:(r + 1) * n]),
                             sorted(soak_faults.KINDS))
        self.assertEqual(first[0][0], 30.0)
        gaps = [b_[0] - a_[0] for a_, b_ in zip(first, first[1:])]
        self.assertTrue(all(10.0 <= g <= 20.0 for g in gaps), gaps)
        self.assertTrue(all(0 <= f[2] < 12 for f in first))
        self.assertNotEqual(first, [soak_faults.Schedule(8, 12, 10.0, 20.0, 30.0).draw()
                                    for _ in range(12)])

    def test_only_the_kinds_asked_for(self):
        quiet = ('robot_stop', 'radio_loss', 'flood')
        s = soak_faults.Schedule(7, 12, 10.0, 20.0, first_s=30.0, kinds=quiet)
        drawn = [s.draw()[1] for _ in range(9)]
        for r in range(3):
            self.assertEqual(sorted(drawn[r * 3:(r + 1) * 3]), sorted(quiet))

    def test_the_faults_option(self):
        a = soak.parse_args(['--faults', 'flood, robot_stop', '--out', '/nonexistent/a'])
        self.assertEqual(a.faults, ('robot_stop', 'flood'))
        self.assertEqual(soak.parse_args(['--out', '/nonexistent/b']).faults,
                         soak_faults.KINDS)
        self.assertEqual(soak.parse_args(['--faults', 'leader_kill,flood', '--out',
                                          '/nonexistent/d']).faults, ('flood', 'leader_kill'))
        for bad in ('robot_kil', 'flood,flood', ',', 'leader_kil'):
            with self.assertRaises(SystemExit, msg=bad):
                soak.parse_args(['--faults', bad, '--out', '/nonexistent/c'])


class LeaderTarget(unittest.TestCase):

    def test_the_newest_gathering_mission_with_a_named_first_leader(self):
        m = soak_missions.Missions()
        self.assertIsNone(m.leader_target())
        # 1 gathers, 2 transports, 3 gathers but its first leader was not named, 4 gathers.
        for mid, state in ((1, 1), (2, 3), (3, 1), (4, 1), (5, 0)):
            m.states[mid] = [(0.0, state, '')]
        m.first_leader.update({1: 7, 2: 8, 4: 11, 5: 12})
        self.assertEqual(m.leader_target(), (4, 11, 'GATHERING'))
        self.assertEqual(m.leader_target(exclude={4}), (1, 7, 'GATHERING'))
        self.assertIsNone(m.leader_target(exclude={1, 4}))
        m.states[4].append((1.0, 2, ''))  # LOADING now
        self.assertEqual(m.leader_target(), (1, 7, 'GATHERING'))


class Kill(unittest.TestCase):

    def test_a_node_killed_before_and_not_back_is_not_signalled(self):
        with open('/proc/sys/kernel/pid_max') as f:
            gone = int(f.read()) + 1  # no process has it: the pid of a robot killed before
        w = soak_faults.Watch(warmup_s=10.0)
        w.current['/robot_3/robot'] = gone
        before = os.environ.get('ROS_MASTER_URI')
        os.environ['ROS_MASTER_URI'] = 'http://127.0.0.1:9'  # nothing there: not registered
        try:
            self.assertIsNone(w.kill('/robot_3/robot'))
        finally:
            if before is None:
                del os.environ['ROS_MASTER_URI']
            else:
                os.environ['ROS_MASTER_URI'] = before
        self.assertNotIn(gone, w.killed)


class Rows(unittest.TestCase):

    def test_rows_per_mission_skip_the_header_and_comments(self):
        with tempfile.TemporaryDirectory() as d:
            with open(os.path.join(d, 'missions.csv'), 'w') as f:
                f.write('mission_id,kind\n1,transport\n# a gap: the recorder was down\n'
                        '2,transport\n1,transport\n')
            self.assertEqual(soak_missions.recorded_rows(d), {1: 2, 2: 1})
            self.assertEqual(soak_missions.recorded_rows(os.path.join(d, 'none')), {})


class Growth(unittest.TestCase):

    def test_growth_from_the_first_sample_after_the_warm_up(self):
        w = soak_faults.Watch(warmup_s=10.0)
        w.incarnations = {
            1: {'name': '/a', 'start': 0.0, 'end': None,
                'samples': [(5.0, 50, 3), (10.0, 100, 10), (20.0, 110, 12), (30.0, 120, 11)]},
            # too young to judge (lived less than twice the warm-up)
            2: {'name': '/b', 'start': 0.0, 'end': None,
                'samples': [(10.0, 100, 10), (15.0, 500, 90)]},
        }
        by_node = {}
        rss, rss_node, fds, fds_node = w.growth(by_node)
        self.assertAlmostEqual(rss, 20.0)
        self.assertEqual((rss_node, fds, fds_node), ('/a', 1, '/a'))
        self.assertEqual(by_node, {'/a (1)': [100, 120]})


class Status(object):
    def __init__(self, mid, state, distance, inside=0):
        self.mission_id, self.state, self.reason = mid, state, ''
        self.distance_to_target, self.robots_inside = distance, inside


class Hung(unittest.TestCase):

    def test_a_mission_is_hung_only_without_progress(self):
        m = soak_missions.Missions()
        for mid in (1, 2, 3):
            m.states[mid] = []
            m.submitted[mid] = 0.0
        m.on_status(Status(1, 3, 5.0))   # TRANSPORT, then nearer and nearer
        m.on_status(Status(2, 3, 5.0))   # TRANSPORT, then stuck
        m.on_status(Status(3, 5, 0.1))   # DONE
        t0 = m.progress[1][0]
        m.progress[1] = (t0 - 100.0,) + m.progress[1][1:]
        m.progress[2] = (t0 - 100.0,) + m.progress[2][1:]
        m.on_status(Status(1, 3, 4.9))   # 10 cm nearer: progress
        m.on_status(Status(2, 3, 4.98))  # 2 cm: not progress
        self.assertEqual(m.hung(t0, 60.0), [2])
        self.assertEqual(m.hung(t0, 120.0), [])
        self.assertEqual(sorted(m.live()), [1, 2])


class LateReports(unittest.TestCase):

    def test_an_older_phase_heard_late_is_no_step_back(self):
        m = soak_missions.Missions()
        m.states[1] = []
        m.submitted[1] = 0.0
        m.on_status(Status(1, 4, 0.1))   # UNLOADING (a progress report)
        m.on_status(Status(1, 3, 0.5))   # TRANSPORT, taken late: ignored
        self.assertEqual(m.final(1), 4)
        m.on_status(Status(1, 5, 0.0))   # DONE (the status)
        m.on_status(Status(1, 4, 0.0))   # UNLOADING, taken after the DONE: ignored
        self.assertEqual(m.final(1), 5)
        self.assertEqual(m.live(), [])
        self.assertEqual([s for _, s, _ in m.states[1]], [4, 5])


class Checks(unittest.TestCase):

    def failures(self, r):
        return {name: why for name, why in soak.checks(r) if why}

    def test_a_clean_soak_passes(self):
        self.assertEqual(self.failures(result()), {})

    def test_each_finding_fails_its_check(self):
        self.assertIn('no_mission_hung', self.failures(result(hung=1)))
        self.assertNotIn('no_mission_hung', {n: w for n, w in soak.checks(result(hung=2), 2)
                                             if w})
        self.assertIn('no_mission_hung', {n: w for n, w in soak.checks(result(hung=3), 2) if w})
        self.assertIn('no_crash', self.failures(result(crashes=2)))
        self.assertIn('no_mission_row_lost', self.failures(result(lost_rows=1)))
        self.assertIn('no_mission_row_twice', self.failures(result(duplicate_rows=1)))
        self.assertIn('missions_done', self.failures(result(done=0)))
        self.assertIn('descriptors_flat', self.failures(result(fd_growth=21)))
        self.assertNotIn('descriptors_flat', {n: w for n, w in
                                              soak.checks(result(fd_growth=21), 0, 30) if w})
        self.assertIn('soak_ran', self.failures(result(ok=False, error='no master')))
        log = result()['fault_log'][:3]
        self.assertIn('every_fault_kind_injected', self.failures(result(fault_log=log)))
        asked = [f['kind'] for f in log]
        self.assertNotIn('every_fault_kind_injected',
                         self.failures(result(fault_log=log, fault_kinds=asked)))
        self.assertIn('every_fault_kind_injected',
                      self.failures(result(fault_log=log[:2], fault_kinds=asked)))
        log = result()['fault_log']
        log[2] = dict(log[2], effect='/recorder NOT back; live missions: none')
        self.assertIn('every_fault_had_its_effect', self.failures(result(fault_log=log)))


if __name__ == '__main__':
    unittest.main()
