"""scripts/roscpp_probe (issue 29, docs/reliability.md): a short run prints its RESULT line with
the listener's heap before and after the peer's restarts, and bad arguments get one clear
message and exit 2 before anything starts."""
import os
import sys
import unittest

# nosetests runs with -P (no path adjustment): this folder's helper module by its path.
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import script_runs  # noqa: E402


def run(*args, timeout=180):
    return script_runs.run('roscpp_probe', *args, timeout=timeout)


class RoscppProbe(unittest.TestCase):

    def test_a_short_run_measures_the_listener(self):
        code, out = run('--restarts', '6', '--topics', '2', '--dead-s', '0.5')
        self.assertEqual(code, 0, out)
        fields = script_runs.result_fields(self, out)
        self.assertEqual((fields['side'], fields['trim'], fields['restarts'], fields['topics']),
                         ('subscriber', 'False', '6', '2'), fields)
        # A live listener's heap: hundreds of KB, read from its smaps (not a made-up zero).
        self.assertGreater(int(fields['heap_kb_after_warmup']), 100, fields)
        self.assertGreater(int(fields['heap_kb_end']), 100, fields)
        for key in ('heap_kb_per_restart', 'heap_kb_per_restart_per_topic', 'rss_growth_pct'):
            self.assertRegex(fields[key], r'^-?[0-9]+\.[0-9]+$', fields)

    def test_the_publisher_side_with_the_heap_trimmed(self):
        code, out = run('--restarts', '6', '--topics', '2', '--dead-s', '0.5', '--side',
                        'publisher', '--trim')
        self.assertEqual(code, 0, out)
        fields = script_runs.result_fields(self, out)
        self.assertEqual((fields['side'], fields['trim'], fields['restarts']),
                         ('publisher', 'True', '6'), fields)
        self.assertGreater(int(fields['heap_kb_end']), 100, fields)

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
