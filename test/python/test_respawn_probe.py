"""scripts/respawn_probe (issue 29, docs/reliability.md): a short run respawns a robot's process
and prints its RESULT line with robot 1's heap read from its smaps; bad arguments get one clear
message and exit 2 before anything starts."""
import os
import subprocess
import unittest

SCRIPT = os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', '..', 'scripts',
                      'respawn_probe')


def run(*args, timeout=240):
    proc = subprocess.run([SCRIPT] + list(args), stdout=subprocess.PIPE,
                          stderr=subprocess.STDOUT, timeout=timeout, universal_newlines=True)
    return proc.returncode, proc.stdout


class RespawnProbe(unittest.TestCase):

    def test_a_short_run_measures_robot_1_and_the_simulator(self):
        code, out = run('--respawns', '2', '--dead-s', '0.5', '--robots', '3')
        self.assertEqual(code, 0, out)
        self.assertIn('respawns of robot 2', out)
        result = [line for line in out.splitlines() if line.startswith('RESULT ')]
        self.assertEqual(len(result), 1, out)
        fields = dict(kv.split('=', 1) for kv in result[0].split()[1:])
        self.assertEqual((fields['robots'], fields['respawns']), ('3', '2'), result)
        # A live robot's heap: more than a MB, read from its smaps (not a made-up zero).
        self.assertGreater(int(fields['robot1_heap_kb_after_warmup']), 500, result)
        self.assertGreater(int(fields['robot1_heap_kb_end']), 500, result)
        for key in ('robot1_heap_kb_per_respawn', 'simulator_heap_kb_per_respawn'):
            self.assertRegex(fields[key], r'^-?[0-9]+\.[0-9]+$', result)

    def test_bad_arguments_are_refused(self):
        for bad, words in ((['--respawns', '0'], '--respawns'),
                           (['--robots', '2'], '--robots'),
                           (['--robots', 'x'], '--robots'),
                           (['--dead-s', '-1'], '--dead-s'),
                           (['--nonsense'], 'unknown argument')):
            code, out = run(*bad, timeout=60)
            self.assertEqual(code, 2, (bad, out))
            self.assertIn(words, out, bad)
            self.assertNotIn('RESULT', out, bad)


if __name__ == '__main__':
    unittest.main()
