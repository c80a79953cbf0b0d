"""st_ros.stop_process_trees: what a stopped process had started does not outlive it, even in
a session of its own (as roslaunch starts its nodes) and when the parent must be killed."""

import subprocess
import time
import unittest

from swarm_transport import st_ros

# A parent that ignores SIGINT (so the stop must kill its group) and starts a child in a
# session of its own that ignores SIGINT too, then prints the child's pid.
PARENT = ('import os, signal, subprocess, sys, time\n'
          'signal.signal(signal.SIGINT, signal.SIG_IGN)\n'
          'c = subprocess.Popen([sys.executable, "-c", "import signal, time; '
          'signal.signal(signal.SIGINT, signal.SIG_IGN); time.sleep(300)"], '
          'start_new_session=True)\n'
          'print(c.pid, flush=True)\n'
          'time.sleep(300)\n')


def start(code):
    proc = subprocess.Popen(['/usr/bin/python3', '-c', code], stdout=subprocess.PIPE,
                            start_new_session=True, text=True, preexec_fn=st_ros.default_sigint)
    return proc, int(proc.stdout.readline())


class StopProcessTrees(unittest.TestCase):

    def test_child_in_own_session_is_stopped_with_its_killed_parent(self):
        proc, child = start(PARENT)
        self.addCleanup(proc.stdout.close)
        self.assertTrue(st_ros.process_alive(child))
        self.assertIn(child, st_ros.descendants(proc.pid))
        killed = st_ros.stop_process_trees([proc], timeout=1.0)
        self.assertIsNotNone(proc.poll())
        self.assertEqual(killed, [child])
        deadline = time.time() + 5
        while st_ros.process_alive(child) and time.time() < deadline:
            time.sleep(0.05)
        self.assertFalse(st_ros.process_alive(child), 'child %d outlived the stop' % child)

    def test_orderly_stop_kills_nothing_more(self):
        # A parent that stops on SIGINT and takes its child along leaves nothing behind.
        code = ('import subprocess, sys, time\n'
                'c = subprocess.Popen([sys.executable, "-c", "import time; time.sleep(300)"])\n'
                'print(c.pid, flush=True)\n'
                'try:\n    time.sleep(300)\n'
                'except KeyboardInterrupt:\n    c.kill(); c.wait()\n')
        proc, child = start(code)
        self.addCleanup(proc.stdout.close)
        self.assertEqual(st_ros.stop_process_trees([proc], timeout=10.0), [])
        self.assertFalse(st_ros.process_alive(child))

    def test_process_not_below_the_stopped_one_is_left_alone(self):
        other = subprocess.Popen(['/usr/bin/python3', '-c', 'import time; time.sleep(300)'],
                                 start_new_session=True)
        self.addCleanup(other.wait)
        self.addCleanup(other.kill)
        proc, child = start(PARENT)
        self.addCleanup(proc.stdout.close)
        self.assertNotIn(other.pid, st_ros.descendants(proc.pid))
        self.assertEqual(st_ros.stop_process_trees([proc], timeout=1.0), [child])
        self.assertIsNone(other.poll())
        self.assertTrue(st_ros.process_alive(other.pid))

if __name__ == '__main__':
    unittest.main()
