#!/usr/bin/env python3
"""Unit tests of the scenario check `reproducible` (swarm_transport.scenario_checks): two runs of
one scenario are the same when every tick's poses and every mission's statuses are."""

import os
import sys
import unittest

from swarm_transport import scenario_checks as checks

# nosetests runs with -P (no path adjustment): the scenario tests' module by its path.
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import test_scenario  # noqa: E402
from test_scenario import log_of  # noqa: E402


class Reproducible(unittest.TestCase):

    # The scenario tests' own: the minimal scenario, and one expectation checked on run logs.
    setUp = test_scenario.Checks.setUp
    run_check = test_scenario.Checks.run_check

    def test_reproducible_compares_every_tick_and_status(self):
        a = log_of({0: {0: (1.0, 1.0, 0)}, 1: {0: (1.1, 1.0, 0)}}, [(7, 'DONE', 1)])
        b = log_of({0: {0: (1.0, 1.0, 0)}, 1: {0: (1.1, 1.0, 0)}}, [(7, 'DONE', 1)])
        self.assertTrue(self.run_check('  - reproducible: {}\n', a, b)[0])
        c = log_of({0: {0: (1.0, 1.0, 0)}, 1: {0: (1.1, 1.0 + 1e-9, 0)}}, [(7, 'DONE', 1)])
        ok, measured = self.run_check('  - reproducible: {}\n', a, c)
        self.assertFalse(ok)
        self.assertIn('first: tick 1', measured)
        self.assertFalse(self.run_check('  - reproducible: {}\n', a, None)[0])

    def test_reproducible_compares_statuses_per_mission_and_by_their_own_ticks(self):
        poses = {0: {0: (1.0, 1.0, 0)}}
        # Two missions' statuses come over different connections: their interleaving is the
        # observer's, not the run's; a status without a tick of its own took the observer's
        # latest tick, which is when it arrived.
        a = checks.RunLog(poses, [(4, 'GATHERING', 45), (5, 'REJECTED', 50), (4, 'DONE', 90)],
                          unstamped=[1])
        b = checks.RunLog(poses, [(4, 'GATHERING', 45), (4, 'DONE', 90), (5, 'REJECTED', 52)],
                          unstamped=[2])
        self.assertTrue(self.run_check('  - reproducible: {}\n', a, b)[0])
        # A stamped tick that differs, a state that differs, a status missing: each says where.
        c = checks.RunLog(poses, [(4, 'GATHERING', 45), (5, 'REJECTED', 50), (4, 'DONE', 91)],
                          unstamped=[1])
        ok, measured = self.run_check('  - reproducible: {}\n', a, c)
        self.assertFalse(ok)
        self.assertIn("statuses differ: mission 4, status 2: ('DONE', 90) vs ('DONE', 91)",
                      measured)
        d = checks.RunLog(poses, [(4, 'GATHERING', 45), (5, 'REJECTED', 50)], unstamped=[1])
        ok, measured = self.run_check('  - reproducible: {}\n', a, d)
        self.assertFalse(ok)
        self.assertIn("mission 4, status 2: ('DONE', 90) vs none", measured)
        e = checks.RunLog(poses, [(4, 'GATHERING', 45), (5, 'REJECTED', 50), (4, 'DONE', 90)])
        ok, measured = self.run_check('  - reproducible: {}\n', a, e)
        self.assertFalse(ok, 'a stamped tick is compared even where the other run had none')
        self.assertIn("mission 5, status 1: ('REJECTED', None) vs ('REJECTED', 50)", measured)



if __name__ == '__main__':
    unittest.main()
