"""scripts/roscpp_probe (issue 29, docs/reliability.md): a short run prints its RESULT line with
the listener's heap before and after the peer's restarts, and bad arguments get one clear
message and exit 2 before anything starts."""
import os
import re
import subprocess
import unittest

SCRIPT = os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', '..', 'scripts',
                      'roscpp_probe')


def run(*args, timeout=180):
    proc = subprocess.run([SCRIPT] + list(args), stdout=subprocess.PIPE,
                          stderr=subprocess.STDOUT, timeout=timeout, universal_newlines=True)
    return proc.returncode, proc.stdout


class RoscppProbe(unittest.TestCase):

    def test_a_short_run_measures_the_listener(self):
        code, out = run('--restarts', '6', '--topics', '2', '--dead-s', '0.5')
        self.assertEqual(code, 0, out)
        result = [line for line in out.splitlines() if line.startswith('RESULT ')]
        self.assertEqual(len(result), 1, out)
        fields = dict(kv.split('=', 1) for kv in result[0].split()[1:])
        self.assertEqual((fields['side'], fields['trim'], fields['restarts'], fields['topics']),
                         ('subscriber', 'False', '6', '2'), result)
        # A live listener's heap: hundreds of KB, read from its smaps (not a made-up zero).
        self.assertGreater(int(fields['heap_kb_after_warmup']), 100, result)
        self.assertGreater(int(fields['heap_kb_end']), 100, result)
        for key in ('heap_kb_per_restart', 'heap_kb_per_restart_per_topic', 'rss_growth_pct'):
            self.assertRegex(fields[key], r'^-?[0-9]+\.[0-9]+$', result)

    def test_the_publisher_side_with_the_heap_trimmed(self):
        code, out = run('--restarts', '6', '--topics', '2', '--dead-s', '0.5', '--side',
                        'publisher', '--trim')
        self.assertEqual(code, 0, out)
        result = [line for line in out.splitlines() if line.startswith('RESULT ')]
        self.assertEqual(len(result), 1, out)
        fields = dict(kv.split('=', 1) for kv in result[0].split()[1:])
        self.assertEqual((fields['side'], fields['trim'], fields['restarts']),
                         ('publisher', 'True', '6'), result)
        self.assertGreater(int(fields['heap_kb_end']), 100, result)

    def test_bad_arguments_are_refused(self):
        for bad, words in ((['--restarts', '0'], '--restarts'),
                           (['--topics', 'x'], '--topics'),
                           (['--dead-s', '-1'], '--dead-s'),
                           (['--side', 'both'], '--side'),
                           (['--nonsense'], 'unknown argument')):
            code, out = run(*bad, timeout=60)
            self.assertEqual(code, 2, (bad, out))
            self.assertIn(words, out, bad)
            self.assertNotIn('RESULT', out, bad)


if __name__ == '__main__':
    unittest.main()
