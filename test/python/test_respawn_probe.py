"""scripts/respawn_probe (issue 29, docs/reliability.md): a short run respawns a robot's process
and prints its RESULT line with robot 1's heap read from its smaps; bad arguments get one clear
message and exit 2 before anything starts."""
import os
import sys
import unittest

# nosetests runs with -P (no path adjustment): this folder's helper module by its path.
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import script_runs  # noqa: E402


def run(*args, timeout=240):
    return script_runs.run('respawn_probe', *args, timeout=timeout)


class RespawnProbe(unittest.TestCase):

    def test_a_short_run_measures_robot_1_and_the_simulator(self):
        code, out = run('--respawns', '2', '--dead-s', '0.5', '--robots', '3', '--no-build')
        self.assertEqual(code, 0, out)
        self.assertIn('respawns of robot 2', out)
        fields = script_runs.result_fields(self, out)
        self.assertEqual((fields['robots'], fields['respawns']), ('3', '2'), fields)
        # A live robot's heap: more than a MB, read from its smaps (not a made-up zero).
        self.assertGreater(int(fields['robot1_heap_kb_after_warmup']), 500, fields)
        self.assertGreater(int(fields['robot1_heap_kb_end']), 500, fields)
        for key in ('robot1_heap_kb_per_respawn', 'simulator_heap_kb_per_respawn'):
            self.assertRegex(fields[key], r'^-?[0-9]+\.[0-9]+$', fields)
        # The nodes' ConnectionReaper: robot 1 and the simulator keep no dropped connection
        # (their own /diagnostics; roscpp alone keeps a few per respawn, --reaper off).
        self.assertEqual(fields['reaper'], 'on', fields)
        for node in ('robot1', 'simulator'):
            self.assertEqual(fields[node + '_dropped_connections_held'], '0', fields)
            self.assertRegex(fields[node + '_dropped_connections_reaped'], r'^[0-9]+$', fields)

    def test_bad_arguments_are_refused(self):
        for bad, words in ((['--respawns', '0'], '--respawns'),
                           (['--robots', '2'], '--robots'),
                           (['--robots', 'x'], '--robots'),
                           (['--dead-s', '-1'], '--dead-s'),
                           (['--reaper', 'maybe'], '--reaper'),
                           (['--nonsense'], 'unknown argument')):
            code, out = run(*bad, timeout=60)
            self.assertEqual(code, 2, (bad, out))
            self.assertIn(words, out, bad)
            self.assertNotIn('RESULT', out, bad)


if __name__ == '__main__':
    unittest.main()
