"""The experiment, benchmark, demo and mission command lines without ROS (issue 10): they list what
there is and refuse bad arguments with one clear message and a non-zero exit, before starting
anything. The entry points are run directly (scripts/* would build first)."""
import os
import subprocess
import unittest

from swarm_transport import experiment_presets as presets

PY = '/usr/bin/python3'


def run(script, *args):
    # The package as the scripts run it (python3 -m swarm_transport.<module>), with this
    # process's environment: the devel space's PYTHONPATH.
    module = 'swarm_transport.' + os.path.splitext(script)[0]
    proc = subprocess.run([PY, '-m', module] + list(args),
                          stdout=subprocess.PIPE, stderr=subprocess.STDOUT, timeout=60,
                          universal_newlines=True)
    return proc.returncode, proc.stdout


class CommandLines(unittest.TestCase):

    def test_experiment_list_names_every_preset(self):
        code, out = run('experiment.py', 'list')
        self.assertEqual(code, 0, out)
        listed = [line.split()[0] for line in out.splitlines() if line.strip()]
        self.assertEqual(sorted(listed), presets.preset_names())

    def test_experiment_refuses_an_unknown_preset_and_bad_counts(self):
        code, out = run('experiment.py', 'run', 'no_such_preset')
        self.assertNotEqual(code, 0)
        self.assertIn('no_such_preset', out)
        self.assertIn('smoke', out)  # what there is
        for bad in (['--runs', '0'], ['--jobs', '0']):
            code, out = run('experiment.py', 'run', 'smoke', *bad)
            self.assertNotEqual(code, 0, bad)
            self.assertIn(bad[0], out)

    def test_bench_refuses_bad_arguments(self):
        for bad, words in ((['--robots', '0'], '--robots'), (['--robots', '5', '--clock', 'x'],
                                                                '--clock')):
            code, out = run('bench.py', *bad)
            self.assertEqual(code, 2, out)
            self.assertIn(words, out)

    def test_demo_refuses_an_impossible_mission(self):
        code, out = run('demo.py', '--robots', '5', '--group', '3', '--leaders', '4')
        self.assertEqual(code, 2, out)
        self.assertIn('--leaders', out)

    def test_mission_refuses_bad_orders_before_sending(self):
        mission = os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', '..',
                               'scripts', 'nodes', 'mission')
        order = ['transport', '--object', '7', '7', '2', '2', '--target', '3', '3']
        for bad, words in ((['--count', '3', '--leader-ids', '1'], '--leader-ids'),
                           (['--robots', '0:4', '--leader-ids', 'x'], '--leader-ids'),
                           ([], '--robots'),
                           (['--robots', '0:4', '--recruit'], '--recruit')):
            proc = subprocess.run([PY, mission] + order + bad, stdout=subprocess.PIPE,
                                  stderr=subprocess.STDOUT, timeout=60,
                                  universal_newlines=True)
            self.assertEqual(proc.returncode, 2, (bad, proc.stdout))
            self.assertIn(words, proc.stdout, bad)


if __name__ == '__main__':
    unittest.main()
