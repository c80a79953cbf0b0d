"""src/swarm_transport/experiment_stats.py without ROS: the thesis's trimmed mean, and the
aggregation of hand-made run files (flocking samples on the 10 s grid; an aborted transport)."""
import json
import os
import shutil
import tempfile
import unittest


from swarm_transport import experiment_presets as presets
from swarm_transport import experiment_stats as stats


class Stats(unittest.TestCase):

    def setUp(self):
        self.tmp = tempfile.mkdtemp(prefix='st_stats_')
        self.addCleanup(shutil.rmtree, self.tmp)

    def test_trimmed_mean_drops_the_thesis_outliers(self):
        self.assertEqual(presets.trim_each_end(10), 2)   # middle 6 of 10 (thesis 7.2)
        self.assertEqual(presets.trim_each_end(15), 2)   # middle 11 of 15 (thesis 7.4)
        self.assertEqual(presets.trim_each_end(4), 0)    # fewer than 5: plain mean
        vals = [100.0, 1, 2, 3, 4, 5, 6, 7, 8, -100.0]
        self.assertAlmostEqual(stats.trimmed_mean(vals), (2 + 3 + 4 + 5 + 6 + 7) / 6.0)
        agg = stats.aggregate([1.0, None, 3.0, float('nan')])
        self.assertEqual(agg['runs'], 2)
        self.assertAlmostEqual(agg['median'], 2.0)

    def test_aggregation_of_handmade_runs(self):
        """Flocking samples on the 10 s grid; a transport that hit the tick limit counts as
        aborted and adds no transport values."""
        base = os.path.join(self.tmp, 'handmade')
        flock = {'description': 'x', 'kind': 'flocking', 'runs': 2, 'base_config':
                 'thesis_flocking.yaml', 'max_ticks': 30, 'settings': [{'name': 's1'}]}
        p = presets.validate(flock, 'handmade_flocking')
        for k, counts in enumerate(([5, 4, 3, 2], [7, 6, 5, 4])):
            d = os.path.join(base, 'f', 'raw', 's1', 'run_%d' % k)
            os.makedirs(d)
            with open(os.path.join(d, 'result.json'), 'w') as f:
                json.dump({'status': 'ok', 'seed': k + 1, 'end': 'max_ticks'}, f)
            with open(os.path.join(d, 'swarm_count.csv'), 'w') as f:
                f.write('tick,sim_time_s,robots,swarm_count,largest_swarm\n')
                for i, c in enumerate(counts):
                    tick = [0, 10, 19, 28][i]
                    f.write('%d,%.1f,10,%d,3\n' % (tick, tick * 1.1, c))
        summary = {(r['setting'], r['metric']): r for r in
                   stats.summarize(p, stats.collect(p, os.path.join(base, 'f')))}
        self.assertAlmostEqual(summary[('s1', 'final_swarm_count')]['mean'], 3.0)
        self.assertAlmostEqual(summary[('s1', 'initial_swarm_count')]['mean'], 6.0)
        self.assertAlmostEqual(summary[('s1', 'swarm_count_t20')]['mean'], 4.0)
        self.assertAlmostEqual(summary[('s1', 'swarm_count_t30')]['mean'], 3.0)
        self.assertLess(summary[('s1', 'swarm_count_slope_per_h')]['mean'], 0.0)

        transport = {'description': 'x', 'kind': 'transport', 'runs': 2, 'base_config':
                     'thesis_transport.yaml', 'max_ticks': 100, 'robots': 6,
                     'mission': {'id': 7, 'object': [7, 7, 2, 2], 'target': [3, 3],
                                 'leaders': 1}, 'settings': [{'name': 't1'}]}
        p = presets.validate(transport, 'handmade_transport')
        header = ('mission_id,kind,assigned,leaders,final_state,queued_tick,gathering_tick,'
                  'loading_tick,transport_tick,unloading_tick,done_tick,transport_ticks,'
                  'slip_per_robot_m,distance_per_robot_m,leader_waits,path_fraction_attached,'
                  'leader_swarm_at_arrival,object_error_m,leader_contact\n')
        for k, end in enumerate(('DONE', 'TICK_LIMIT')):
            d = os.path.join(base, 't', 'raw', 't1', 'run_%d' % k)
            os.makedirs(d)
            with open(os.path.join(d, 'result.json'), 'w') as f:
                json.dump({'status': 'ok', 'seed': k + 1, 'end': end, 'mission_id': 7,
                           'gathering_swerves': 12}, f)
            with open(os.path.join(d, 'missions.csv'), 'w') as f:
                f.write(header)
                if end == 'DONE':
                    f.write('7,transport,6,1,DONE,0,0,40,42,110,112,68,2.5,6.1,0,,,0.04,0.25\n')
        summary = {(r['setting'], r['metric']): r for r in
                   stats.summarize(p, stats.collect(p, os.path.join(base, 't')))}
        self.assertEqual(summary[('t1', 'aborted')]['runs'], 2)
        self.assertAlmostEqual(summary[('t1', 'aborted')]['mean'], 0.5)
        self.assertEqual(summary[('t1', 'transport_ticks')]['runs'], 1)
        self.assertAlmostEqual(summary[('t1', 'transport_ticks')]['mean'], 68.0)
        self.assertAlmostEqual(summary[('t1', 'gathering_ticks')]['mean'], 40.0)
        self.assertAlmostEqual(summary[('t1', 'leader_contact')]['mean'], 0.25)
        self.assertAlmostEqual(summary[('t1', 'mission_ticks')]['mean'], 112.0)  # QUEUED->DONE
        self.assertAlmostEqual(summary[('t1', 'gathering_swerves')]['mean'], 12.0)
        self.assertEqual(summary[('t1', 'gathering_swerves')]['runs'], 1)  # the DONE run only

    def test_first_leader_waits_count_robot_0_as_the_thesis_plotted(self):
        """Ticks of the transport window in which robot 0 moved less than 1 mm since the tick
        before (the thesis's LeaderDidntMove without its baseline sample); other robots and
        ticks outside the window do not count."""
        d = os.path.join(self.tmp, 'traced')
        os.makedirs(d)
        x0 = [0.0, 0.0, 0.1, 0.1005, 0.2, 0.2, 0.2]   # ticks 0..6
        with open(os.path.join(d, 'trace.csv'), 'w') as f:
            f.write('tick,robot_id,x,y,heading_deg\n')
            for t, x in enumerate(x0):
                f.write('%d,0,%.4f,1.0,0\n%d,1,5.0,5.0,0\n' % (t, x, t))
        # Window (1, 5]: ticks 2 (moved 0.1), 3 (0.5 mm: waits), 4 (moved), 5 (waits).
        self.assertEqual(stats.first_leader_waits(d, 1, 5), 2.0)
        self.assertEqual(stats.first_leader_waits(d, 0, 6), 4.0)   # ticks 1 and 6 too
        self.assertIsNone(stats.first_leader_waits(d, 1, 9))       # the trace ends before
        self.assertIsNone(stats.first_leader_waits(d, None, 5))
        self.assertIsNone(stats.first_leader_waits(self.tmp, 1, 5))  # no trace


if __name__ == '__main__':
    unittest.main()
