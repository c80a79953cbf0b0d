"""Helpers of the tests that run one of scripts/ and read its RESULT line."""
import os
import subprocess

# The repository's own scripts (realpath: run from the workspace's links, a script would take
# .catkin_ws/src/swarm_transport for the repository and miss its workspace).
SCRIPTS = os.path.realpath(os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', '..',
                                        'scripts'))


def run(script, *args, timeout=180):
    """(exit code, stdout and stderr together) of scripts/<script> with args."""
    proc = subprocess.run([os.path.join(SCRIPTS, script)] + list(args), stdout=subprocess.PIPE,
                          stderr=subprocess.STDOUT, timeout=timeout, universal_newlines=True)
    return proc.returncode, proc.stdout


def result_fields(test, out):
    """The key=value fields of the one RESULT line in out (test fails unless there is one)."""
    result = [line for line in out.splitlines() if line.startswith('RESULT ')]
    test.assertEqual(len(result), 1, out)
    return dict(kv.split('=', 1) for kv in result[0].split()[1:])
