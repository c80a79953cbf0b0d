"""src/swarm_transport/experiment_presets.py without ROS: every shipped preset is valid, a bad
preset is refused with the key named, and the swarm count's connected components (SPEC 8, the
core's SwarmComponents through experiment_batch --metrics)."""
import copy
import unittest

import yaml

from swarm_transport import core_metrics
from swarm_transport import experiment_presets as presets

GOOD = {'description': 'x', 'kind': 'flocking', 'runs': 2, 'base_config': 'thesis_flocking.yaml',
        'max_ticks': 30, 'settings': [{'name': 's1'}]}


class Presets(unittest.TestCase):

    def test_every_shipped_preset_is_valid(self):
        names = presets.preset_names()
        self.assertIn('smoke', names)
        for name in names:
            p = presets.load_preset(name)
            self.assertTrue(p['description'].strip(), name)
            for view in presets.settings(p):
                config = presets.swarm_config(p, view)
                self.assertAlmostEqual(config['world_size_m'], 11.088889, msg=name)

    def test_a_bad_preset_is_refused_naming_what_is_wrong(self):
        self.assertEqual(presets.validate(copy.deepcopy(GOOD), 'good')['name'], 'good')
        cases = [
            ({'colour': 'red'}, 'unknown keys'),
            ({'runs': 0}, 'runs must be an integer >= 1'),
            ({'kind': 'dance'}, 'kind must be one of'),
            ({'base_config': 'nosuch.yaml'}, 'does not exist'),
            ({'max_ticks': 0}, 'needs max_ticks > 0'),
            ({'settings': []}, 'settings must be a non-empty list'),
            ({'settings': [{'name': 'a'}, {'name': 'a'}]}, 'must be unique'),
            ({'settings': [{'name': 'a', 'speed': 3}]}, "unknown keys ['speed']"),
            ({'table': ['no_such_metric']}, 'table must be a non-empty list'),
            ({'table': []}, 'table must be a non-empty list'),
        ]
        for change, words in cases:
            p = copy.deepcopy(GOOD)
            p.update(change)
            with self.assertRaises(presets.PresetError) as cm:
                presets.validate(p, 'bad')
            self.assertIn(words, str(cm.exception), change)
            self.assertIn('preset bad', str(cm.exception))
        p = copy.deepcopy(GOOD)
        del p['runs']
        with self.assertRaises(presets.PresetError):
            presets.validate(p, 'bad')
        with self.assertRaises(presets.PresetError) as cm:
            presets.load_preset('no_such_preset')
        self.assertIn('smoke', str(cm.exception))  # it lists what there is

    def test_dispersion_metrics_join_a_preset_whose_table_names_them(self):
        plain = presets.validate(copy.deepcopy(GOOD), 'good')
        self.assertEqual(presets.metrics_of(plain), presets.METRICS['flocking'])
        p = copy.deepcopy(GOOD)
        p['table'] = ['nn_spacing_cv', 'final_swarm_count', 'coverage_fraction']
        p = presets.validate(p, 'good')
        self.assertEqual(presets.metrics_of(p), presets.METRICS['flocking'] +
                         ['coverage_fraction', 'nn_spacing_cv'])
        # The shipped balloon preset reports them; a dispersion metric may carry an expectation.
        balloon = presets.load_preset('balloon_dispersion')
        self.assertIn('coverage_fraction', presets.metrics_of(balloon))
        self.assertIn('coverage_fraction', [e['metric'] for e in balloon['expect']])
        q = copy.deepcopy(GOOD)
        q['expect'] = [{'metric': 'coverage_fraction', 'trend': 'increasing'}]
        with self.assertRaises(presets.PresetError):
            presets.validate(q, 'bad')  # not in its table: not among its metrics

    def test_trend_kinds_on_made_up_series(self):
        """The page's classifier and its trend kinds on invented numbers (never measured
        ones: a test must not fix what a measurement happens to give)."""
        from swarm_transport import experiment_verdicts as verdicts
        self.assertEqual(verdicts.classify([1.0, 2.0, 3.0, 4.0])[0], 'increasing')
        self.assertEqual(verdicts.classify([4.0, 3.0, 2.0, 1.0])[0], 'decreasing')
        self.assertEqual(verdicts.classify([10.0, 10.5, 10.2, 10.9])[0], 'flat')  # 8 % spread
        got, rho, _ = verdicts.classify([2.0, 3.0, 1.0, 4.0])  # ranks 1, 2, 0, 3
        self.assertEqual(got, 'mixed')
        self.assertAlmostEqual(rho, 0.4)
        self.assertTrue(verdicts.high_at_last([1.0, 2.0, 1.5, 2.0, 5.0]))
        self.assertFalse(verdicts.high_at_last([1.0, 2.0, 1.5, 4.7, 5.0]))  # not clearly
        self.assertFalse(verdicts.high_at_last([5.0, 2.0, 1.5, 2.0, 1.0]))

    def test_a_verdict_names_its_source_and_says_why_it_differs(self):
        from swarm_transport import experiment_verdicts as verdicts
        p = copy.deepcopy(GOOD)
        p['settings'] = [{'name': n} for n in 'abcd']
        p['expect'] = [
            {'metric': 'final_swarm_count', 'trend': 'increasing'},
            {'metric': 'final_swarm_count', 'trend': 'decreasing', 'source': 'thesis fig. 9',
             'because': 'ours gathers less'},
            {'metric': 'final_swarm_count', 'trend': 'high_at_last', 'source': 'thesis text'},
            {'metric': 'final_swarm_count', 'trend': 'mixed', 'source': 'raw file'}]
        p = presets.validate(p, 'good')

        def results(values):
            summary = {(n, 'final_swarm_count'): {'trimmed_mean': v}
                       for n, v in zip('abcd', values)}
            return verdicts.trend_results(p, summary)

        rs = results([1.0, 2.0, 2.5, 5.0])
        self.assertTrue(rs[0]['text'].endswith('thesis increasing: agrees'))
        self.assertEqual(rs[1]['verdict'], 'differs')
        self.assertTrue(rs[1]['text'].startswith('thesis fig. 9 — final swarm count: a 1.00'))
        self.assertTrue(rs[1]['text'].endswith(
            'expected decreasing: differs, because ours gathers less'))
        self.assertTrue(rs[2]['text'].startswith('thesis text — '))
        self.assertTrue(rs[2]['text'].endswith('expected high at last: agrees'))
        self.assertTrue(rs[3]['text'].startswith('raw file — '))
        self.assertTrue(rs[3]['text'].endswith('expected mixed: differs'))
        rs = results([4.0, 3.0, 2.0, 1.0])
        self.assertEqual([r['verdict'] for r in rs], ['differs', 'agrees', 'differs', 'differs'])
        self.assertNotIn('because', rs[1]['text'])   # only a verdict that differs says why
        self.assertEqual(results([2.0, 3.0, 1.0, 4.0])[3]['verdict'], 'agrees')
        for bad in ({'metric': 'final_swarm_count', 'trend': 'upwards'},
                    {'metric': 'final_swarm_count', 'trend': 'flat', 'colour': 1},
                    {'metric': 'final_swarm_count', 'trend': 'flat', 'source': ''}):
            q = copy.deepcopy(GOOD)
            q['expect'] = [bad]
            with self.assertRaises(presets.PresetError):
                presets.validate(q, 'bad')

    def test_a_verdict_across_groups_on_made_up_series(self):
        """across: groups judges one series per setting label along the groups, optionally as
        a share of each group's passive robots (invented numbers)."""
        from swarm_transport import experiment_verdicts as verdicts
        p = {'description': 'x', 'kind': 'leader', 'runs': 2, 'base_config': 'thesis_leader.yaml',
             'max_ticks': 30, 'mission': {'target': [8.0, 8.0]}, 'x_label': 'cohesion',
             'group_label': 'passive robots', 'settings': [
                 {'name': '%s_%s' % (g, c), 'group': '%d passive' % g, 'label': '%d %%' % c,
                  'robots': g + 1} for g in (5, 10, 20) for c in (0, 10)]}
        p['expect'] = [
            {'metric': 'path_fraction_attached', 'trend': 'decreasing', 'across': 'groups',
             'labels': ['10 %'], 'source': 'thesis text'},
            {'metric': 'leader_swarm_at_arrival', 'trend': 'decreasing', 'across': 'groups',
             'per_passive_robot': True}]
        p = presets.validate(p, 'good')
        path = {0: [0.5, 0.4, 0.6], 10: [0.9, 0.7, 0.2]}
        # Counts that rise with the group while the share falls: 4/5, 6/10, 8/20.
        arrived = {0: [1.0, 1.0, 1.0], 10: [4.0, 6.0, 8.0]}
        summary = {}
        for i, g in enumerate((5, 10, 20)):
            for c in (0, 10):
                summary[('%d_%d' % (g, c), 'path_fraction_attached')] = {
                    'trimmed_mean': path[c][i]}
                summary[('%d_%d' % (g, c), 'leader_swarm_at_arrival')] = {
                    'trimmed_mean': arrived[c][i]}
        rs = verdicts.trend_results(p, summary)
        self.assertEqual(len(rs), 3)  # one label for the path, both for the arrivals
        self.assertEqual(rs[0]['text'],
                         'thesis text — cohesion 10 %, over passive robots, path with whole '
                         'swarm (%): 5 passive 90.0 → 10 passive 70.0 → 20 passive 20.0 — '
                         'measured decreasing (ρ = -1.00, spread 117 %), expected decreasing: '
                         'agrees')
        self.assertEqual(rs[1]['verdict'], 'agrees')   # 20, 10, 5 % of the group at 0 %
        self.assertIn('leader swarm at arrival (% of the group): 5 passive 20.0', rs[1]['text'])
        self.assertEqual(rs[2]['verdict'], 'agrees')   # 80, 60, 40 %: the counts rose
        summary[('20_10', 'leader_swarm_at_arrival')] = {'trimmed_mean': 19.0}   # 95 %
        self.assertEqual(verdicts.trend_results(p, summary)[2]['verdict'], 'differs')
        for bad, words in (({'across': 'robots'}, 'across must be one of'),
                           ({'labels': ['10 %']}, 'labels only with across: groups'),
                           ({'across': 'groups', 'labels': ['7 %']}, 'setting labels'),
                           ({'per_passive_robot': 'yes'}, 'per_passive_robot')):
            q = copy.deepcopy(p)
            del q['name']
            q['expect'] = [dict({'metric': 'leader_waits', 'trend': 'flat'}, **bad)]
            with self.assertRaises(presets.PresetError) as cm:
                presets.validate(q, 'bad')
            self.assertIn(words, str(cm.exception))
        q = copy.deepcopy(GOOD)   # a flocking preset: no groups, no passive robots
        q['expect'] = [{'metric': 'final_swarm_count', 'trend': 'flat', 'across': 'groups'}]
        with self.assertRaises(presets.PresetError) as cm:
            presets.validate(q, 'bad')
        self.assertIn('at least 2 groups', str(cm.exception))
        q['expect'] = [{'metric': 'final_swarm_count', 'trend': 'flat',
                        'per_passive_robot': True}]
        with self.assertRaises(presets.PresetError):
            presets.validate(q, 'bad')

    def test_the_thesis_measured_table_is_checked_and_rendered(self):
        from swarm_transport import experiment_report as report
        p = copy.deepcopy(GOOD)
        p['thesis_measured'] = {'source': 'a file', 'metrics': ['transport_ticks'],
                                'rows': [{'label': '10R 2L', 'transport_ticks': 60.7}]}
        lines = report.measured_table(presets.validate(p, 'good'))
        self.assertIn('a file', lines[0])
        self.assertIn('| 10R 2L | 60.7 |', lines)
        p['thesis_measured']['metrics'] = ['transport_ticks', 'runs_over_2x_median']
        p['thesis_measured']['rows'][0]['runs_over_2x_median'] = 1
        self.assertIn('| 10R 2L | 60.7 | 1 |', report.measured_table(presets.validate(p, 'good')))
        # A published value whose runs are lost: the row lacks the other metrics.
        p['thesis_measured']['rows'].append({'label': '5R 1L, fig.', 'transport_ticks': 65.6})
        self.assertIn('| 5R 1L, fig. | 65.6 | – |',
                      report.measured_table(presets.validate(p, 'good')))
        self.assertEqual(report.measured_table(copy.deepcopy(GOOD)), [])
        for bad in ({'rows': []}, {'source': 'x', 'metrics': ['transport_ticks'],
                                   'rows': [{'label': 'a'}]},
                    {'source': 'x', 'metrics': ['transport_ticks'],
                     'rows': [{'label': 'a', 'transport_ticks': 'many'}]},
                    {'source': 'x', 'metrics': [], 'rows': [], 'colour': 1}):
            q = copy.deepcopy(p)
            q['thesis_measured'] = bad
            with self.assertRaises(presets.PresetError) as cm:
                presets.validate(q, 'bad')
            self.assertIn('thesis_measured', str(cm.exception))
        # The shipped composition preset carries the evaluated code's raw statistics and the
        # figure's three published values whose runs are not in it.
        rows = presets.load_preset('transport_composition')['thesis_measured']['rows']
        labels = [r['label'] for r in rows]
        self.assertEqual(len([l for l in labels if 'published' in l]), 3)  # fig. 7.9's lost runs

    def test_components_link_hop_by_hop_within_range(self):
        # A chain 0.9 m apart is one swarm though its ends are 1.8 m apart; a robot 1.01 m
        # from the nearest is a swarm of its own; exactly the range links.
        count, labels = core_metrics.components([(0, 0), (0.9, 0), (1.8, 0), (2.81, 0)], 1.0)
        self.assertEqual(count, 2)
        self.assertEqual(len({labels[0], labels[1], labels[2]}), 1)
        self.assertNotEqual(labels[3], labels[0])
        self.assertEqual(core_metrics.components([(0, 0), (1.0, 0)], 1.0)[0], 1)
        self.assertEqual(core_metrics.components([], 1.0), (0, []))
        self.assertEqual(core_metrics.components([(5, 5)] * 3, 1.0)[0], 1)

    def test_a_cluster_placement_is_connected_and_reproducible(self):
        a = presets.cluster_placement(12, 3, 1.0, 0.05, 11.088889)
        self.assertEqual(a, presets.cluster_placement(12, 3, 1.0, 0.05, 11.088889))
        self.assertNotEqual(a, presets.cluster_placement(12, 4, 1.0, 0.05, 11.088889))
        self.assertEqual(len(a), 12)
        self.assertEqual(core_metrics.components([(x, y) for x, y, _ in a], 1.0)[0], 1)
        for x, y, theta in a:
            self.assertTrue(0.05 <= x <= 11.088889 - 0.05 and 0.05 <= y <= 11.088889 - 0.05)
            self.assertTrue(0.0 <= theta <= 360.0)

    def test_a_cluster_may_fix_its_side_and_every_heading(self):
        # The thesis's leader code: every robot facing the course in one square of fixed side.
        cluster = {'origin': [1.1, 1.1], 'side_m': 1.8, 'heading_deg': 45.0,
                   'min_distance_m': 0.2}
        for n in (6, 26):
            poses = presets.cluster_placement(n, 5, 1.0, 0.05, 11.088889, cluster)
            self.assertEqual(len(poses), n)
            for x, y, theta in poses:
                self.assertTrue(1.1 <= x <= 2.9 and 1.1 <= y <= 2.9, (x, y))
                self.assertEqual(theta, 45.0)
        # Without them: the same positions as before, random headings.
        plain = presets.cluster_placement(12, 3, 1.0, 0.05, 11.088889)
        facing = presets.cluster_placement(12, 3, 1.0, 0.05, 11.088889, {'heading_deg': 90.0})
        self.assertEqual([p[:2] for p in plain], [p[:2] for p in facing])
        self.assertNotEqual(plain, facing)
        with open(presets.preset_path('leader_group_cohesion')) as f:
            shipped = yaml.safe_load(f)
        for bad in ({'side_m': 0.0}, {'side_m': 'big'}, {'heading_deg': 400.0},
                    {'heading_deg': True}):
            preset = copy.deepcopy(shipped)
            preset['cluster'].update(bad)
            with self.assertRaisesRegex(presets.PresetError, 'cluster'):
                presets.validate(preset, 'bad')

    def test_the_leader_of_a_run_is_fixed_by_its_seed(self):
        leaders = [presets.leader_of(seed, 25) for seed in range(1, 41)]
        self.assertEqual(leaders, [presets.leader_of(seed, 25) for seed in range(1, 41)])
        self.assertTrue(all(0 <= r < 25 for r in leaders))
        self.assertGreater(len(set(leaders)), 5)  # random per run, not always the same robot

if __name__ == '__main__':
    unittest.main()
