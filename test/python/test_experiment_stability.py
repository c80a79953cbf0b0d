"""scripts/experiment stability without ROS: blocks of the preset's run count judged as the
results page judges the whole, on made-up runs."""
import copy
import unittest

from swarm_transport import experiment
from swarm_transport import experiment_presets as presets
from swarm_transport import experiment_stability as stability

PRESET = {'description': 'x', 'kind': 'flocking', 'runs': 3, 'base_config': 'thesis_flocking.yaml',
          'max_ticks': 30, 'settings': [{'name': n} for n in 'abcd'],
          'expect': [{'metric': 'final_swarm_count', 'trend': 'increasing'},
                     {'metric': 'final_swarm_count', 'trend': 'decreasing',
                      'source': 'made-up source'}]}

# Per block of 3 runs, the value of every run in settings a, b, c, d (invented numbers):
# two blocks rise, one falls.
BLOCKS = [[1.0, 2.0, 3.0, 4.0], [1.0, 3.0, 2.5, 5.0], [4.0, 3.0, 2.0, 1.0]]


def runs(blocks, size=3):
    out = []
    for b, values in enumerate(blocks):
        for setting, v in zip('abcd', values):
            for k in range(size):
                run = b * size + k
                out.append({'setting': setting, 'run': run, 'seed': 1 + run,
                            'metrics': {'final_swarm_count': v}, 'series': {}, 'info': {}})
    return out


class Stability(unittest.TestCase):

    def setUp(self):
        self.preset = presets.validate(copy.deepcopy(PRESET), 'made_up')

    def test_each_block_is_judged_like_the_page(self):
        rows = stability.stability(self.preset, runs(BLOCKS), 3)
        self.assertEqual(len(rows), 2)
        up, down = rows
        self.assertEqual((up['blocks'], up['agree']), (3, 2))
        self.assertEqual(up['counts'], {'increasing': 2, 'decreasing': 1})
        self.assertEqual(down['agree'], 1)
        self.assertTrue(down['line'].startswith('made-up source — '))
        # Over all 9 runs per setting: a 2.0, b 2.67, c 2.5, d 3.33 (ρ = +0.8).
        self.assertEqual((up['all'], down['all']), ('agrees', 'differs'))

    def test_blocks_are_by_run_index_and_only_complete_ones_count(self):
        all_runs = runs(BLOCKS)
        self.assertEqual([sorted({r['run'] for r in blk}) for blk in stability.blocks(all_runs, 3)],
                         [[0, 1, 2], [3, 4, 5], [6, 7, 8]])
        gap = [r for r in all_runs if not (r['setting'] == 'c' and r['run'] == 7)]
        self.assertEqual(len(stability.blocks(gap, 3)), 2)  # block 2 lacks a run of c
        self.assertEqual(len(stability.blocks(all_runs, 4)), 2)  # runs 8.. do not fill a third
        rows = stability.stability(self.preset, gap, 3)
        self.assertEqual((rows[0]['blocks'], rows[0]['agree']), (2, 2))

    def test_block_below_two_is_refused(self):
        with self.assertRaises(SystemExit):
            experiment.parse_args(['stability', '/tmp/x', '--block', '1'])


if __name__ == '__main__':
    unittest.main()
