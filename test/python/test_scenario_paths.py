#!/usr/bin/env python3
"""Unit tests of the scenario checks `stands` and `drives` (swarm_transport.scenario_checks): the
path each robot of a range drove over ticks, and a still stretch of N ticks within them."""

import os
import sys
import unittest

# nosetests runs with -P (no path adjustment): the scenario tests' module by its path.
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import test_scenario  # noqa: E402
from test_scenario import MINIMAL, log_of  # noqa: E402


class Paths(unittest.TestCase):

    # The scenario tests' own: the minimal scenario, and one expectation checked on run logs.
    setUp = test_scenario.Checks.setUp
    run_check = test_scenario.Checks.run_check
    expect_error = test_scenario.Format.expect_error

    def test_stands_and_drives_over_ticks(self):
        # robots 0, 1 frozen over ticks 10..12 (robot 1 pushed 0.0005 m); robot 2 drives 0.2 m
        # and back (a path of 0.4 m, no displacement); robot 3 creeps 0.01 m.
        log = log_of({10: {0: (1.0, 1.0, 0), 1: (2.0, 1.0, 0), 2: (5.0, 5.0, 0), 3: (8, 8, 0)},
                      11: {0: (1.0, 1.0, 0), 1: (2.0005, 1.0, 0), 2: (5.2, 5.0, 0),
                           3: (8.005, 8, 0)},
                      12: {0: (1.0, 1.0, 0), 1: (2.0005, 1.0, 0), 2: (5.0, 5.0, 0),
                           3: (8.01, 8, 0)}})
        stands = '  - stands: {robots: [%d, %d], from_tick: 10, to_tick: 12, tolerance_m: %s}\n'
        self.assertTrue(self.run_check(stands % (0, 2, 0.001), log)[0])
        ok, measured = self.run_check(stands % (0, 2, 0.0001), log)
        self.assertFalse(ok)
        self.assertIn('robots [0, 2) over ticks 10..12: the most driven 0.0005 m (robot 1)',
                      measured)
        ok, measured = self.run_check(stands % (0, 3, 0.001), log)  # a path, not a displacement
        self.assertFalse(ok)
        self.assertIn('0.4000 m (robot 2)', measured)
        drives = '  - drives: {robots: [2, 4], from_tick: 10, to_tick: 12, min_m: 0.05%s}\n'
        ok, measured = self.run_check(drives % '', log)
        self.assertFalse(ok)  # robot 3 drove 0.01 m only
        self.assertIn('the least driven 0.0100 m (robot 3)', measured)
        self.assertTrue(self.run_check(drives % ', any: true', log)[0])
        self.assertFalse(self.run_check(
            '  - drives: {robots: [0, 2], from_tick: 10, to_tick: 12, min_m: 0.05, any: true}\n',
            log)[0])
        ok, measured = self.run_check(
            '  - drives: {robots: [2, 4], from_tick: 10, to_tick: 13, min_m: 0.05}\n', log)
        self.assertFalse(ok)
        self.assertIn('no positions over ticks 10..13', measured)
        for bad, words in (('{robots: [3, 2], from_tick: 1, to_tick: 5}', '.robots: must be'),
                           ('{robots: [0, 2], from_tick: 5, to_tick: 5}',
                            'from_tick 5 must be < to_tick 5')):
            self.expect_error(MINIMAL + '  - stands: %s\n' % bad, 13, 'expect[1].stands', words)

    def test_stands_for_some_ticks_within_a_window(self):
        # robot 0 drives 0.1 m a tick until tick 3, stands over ticks 3..6, drives on from 7;
        # robot 1 stands over ticks 2..5 only (0.001 m a tick otherwise)
        x0 = {0: 0.0, 1: 0.1, 2: 0.2, 3: 0.3, 4: 0.3, 5: 0.3, 6: 0.3, 7: 0.4, 8: 0.5}
        x1 = {0: 5.0, 1: 5.001, 2: 5.002, 3: 5.002, 4: 5.002, 5: 5.002, 6: 5.003, 7: 5.004,
              8: 5.005}
        log = log_of({t: {0: (x0[t], 1.0, 0), 1: (x1[t], 2.0, 0)} for t in range(9)})
        stands = ('  - stands: {robots: [%d, %d], from_tick: 0, to_tick: 8, for_ticks: %d, '
                  'tolerance_m: 0.0005}\n')
        ok, measured = self.run_check(stands % (0, 1, 3), log)
        self.assertTrue(ok, measured)
        self.assertIn('still over ticks 3..6 (3 asked), the most driven 0.0000 m (robot 0)',
                      measured)
        self.assertFalse(self.run_check(stands % (0, 1, 4), log)[0])  # 3 moves only
        # both together: ticks 3..5 are the only still ones of both
        ok, measured = self.run_check(stands % (0, 2, 2), log)
        self.assertTrue(ok, measured)
        self.assertIn('still over ticks 3..5 (2 asked)', measured)
        ok, measured = self.run_check(stands % (0, 2, 3), log)
        self.assertFalse(ok)
        self.assertIn('the stillest 3 ticks 3..6, the most driven 0.0010 m (robot 1)', measured)
        # the widening stays within the tolerance: two of robot 1's 0.001 m moves fit 0.0025
        ok, measured = self.run_check(stands.replace('0.0005', '0.0025') % (1, 2, 2), log)
        self.assertTrue(ok, measured)
        self.assertIn('still over ticks 0..5 (2 asked), the most driven 0.0020 m', measured)
        # without for_ticks the whole window counts
        self.assertFalse(self.run_check(
            '  - stands: {robots: [0, 1], from_tick: 0, to_tick: 8, tolerance_m: 0.0005}\n',
            log)[0])
        bad = MINIMAL + '  - stands: {robots: [0, 2], from_tick: 5, to_tick: 8, for_ticks: %d}\n'
        self.expect_error(bad % 4, 13, 'for_ticks 4 is longer than ticks 5..8')
        self.expect_error(bad % 0, 13, 'expect[1].stands.for_ticks')


if __name__ == '__main__':
    unittest.main()
