"""scripts/check_doc_commands can fail (issue 26): made-up dead commands - a renamed option, launch
argument, message field, topic, service, script, preset, file, node, subcommand or live-tuning
key - are each reported with their line and make it exit 1, while the same commands spelled
right pass; its junit file names the failure. (scripts/test runs it over README.md and docs/.)"""
import importlib.machinery
import importlib.util
import os
import tempfile
import unittest

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', '..')


def load_checker():
    path = os.path.join(ROOT, 'scripts', 'check_doc_commands')
    loader = importlib.machinery.SourceFileLoader('check_doc_commands', path)
    spec = importlib.util.spec_from_loader('check_doc_commands', loader)
    module = importlib.util.module_from_spec(spec)
    loader.exec_module(module)
    return module


CDC = load_checker()

# (dead command, the same command alive, words of the expected problem)
PAIRS = [
    ('scripts/demo --robotz 5', 'scripts/demo --robots 5', 'no option --robotz'),
    ('scripts/experiment run smoke --jobz 2', 'scripts/experiment run smoke --jobs 2', '--jobz'),
    ('scripts/experiment run no_such_preset', 'scripts/experiment run smoke', 'no_such_preset'),
    ('scripts/scenario run test/scenarios/nope.yaml',
     'scripts/scenario run test/scenarios/thesis_transport.yaml', 'no file'),
    ('scripts/fuzz --secs 3', 'scripts/fuzz --seconds 3', '--secs'),
    ('scripts/nosuch', 'scripts/build', 'no script'),
    ('roslaunch swarm_transport swarm.launch robotz:=3',
     'roslaunch swarm_transport swarm.launch robots:=3', "'robotz'"),
    ('roslaunch swarm_transport swarm.launch clock:=lockstep',
     'roslaunch swarm_transport swarm.launch lockstep:=true', "'clock'"),
    ("rostopic pub -1 /flock/freeze swarm_transport/Robot_Freeze '{robot_index_form: 0}'",
     "rostopic pub -1 /flock/freeze swarm_transport/Robot_Freeze '{robot_index_from: 0}'",
     'robot_index_form'),
    ("rostopic pub -1 /flock/freez swarm_transport/Robot_Freeze '{robot_index_from: 0}'",
     "rostopic pub -1 /flock/freeze swarm_transport/Robot_Freeze '{robot_index_from: 0}'",
     'no topic'),
    ('rosservice call /spawn "{robot_id: 25, why: 9.0}"',
     'rosservice call /spawn "{robot_id: 25, y: 9.0}"', "'why'"),
    ('rosrun swarm_transport mission transport --robotz 0:12',
     'rosrun swarm_transport mission transport --robots 0:12', '--robotz'),
    ('rosrun swarm_transport mission carry --id 7',
     'rosrun swarm_transport mission watch --id 7', 'subcommand'),
    ('rosrun swarm_transport robbot', 'rosrun swarm_transport robot', 'no executable'),
    ('rosrun dynamic_reconfigure dynparam set /simulator free_will 45',
     'rosrun dynamic_reconfigure dynparam set /simulator free_will_deg 45', "'free_will'"),
    ('rostest swarm_transport scenario.test fiel:=x',
     'rostest swarm_transport scenario.test file:=x', "'fiel'"),
]


def write(text):
    handle = tempfile.NamedTemporaryFile('w', suffix='.md', delete=False)
    handle.write(text)
    handle.close()
    return handle.name


class CheckDocCommands(unittest.TestCase):

    @classmethod
    def setUpClass(cls):
        cls.checker = CDC.Checker(os.path.realpath(ROOT))

    def test_each_dead_command_is_reported_and_its_live_twin_passes(self):
        for dead, alive, words in PAIRS:
            for words_of_command in CDC.split_commands(dead):
                problems = self.checker.check(words_of_command)
                self.assertTrue(problems, dead)
                self.assertIn(words, ' '.join(problems), dead)
            for words_of_command in CDC.split_commands(alive):
                self.assertEqual(self.checker.check(words_of_command), [], alive)

    def test_a_page_with_a_dead_command_fails_with_its_line_and_junit(self):
        page = write('# made up\n\n```bash\nscripts/demo --seed 3\nscripts/demo --robotz 5\n```\n\n'
                     'Inline: `scripts/bench --arena room|density --sekonds 3`.\n')
        junit = page + '.xml'
        try:
            self.assertEqual(CDC.main(['--junit', junit, page]), 1)
            results = CDC.check_files([page], self.checker)[page]
            self.assertEqual([(n, p) for n, _, p in results],
                             [(5, 'scripts/demo has no option --robotz'),
                              (8, 'scripts/bench has no option --sekonds')])
            xml = open(junit).read()
            self.assertIn('failures="1"', xml)
            self.assertIn('--robotz', xml)
        finally:
            os.unlink(page)
            if os.path.exists(junit):
                os.unlink(junit)

    def test_commands_are_split_and_comments_dropped(self):
        words = CDC.split_commands('roscore -p 1 & sleep 3; scripts/demo --rviz  # --nope')
        self.assertEqual(words, [['roscore', '-p', '1'], ['sleep', '3'], ['scripts/demo', '--rviz']])
        found = CDC.commands_of('```yaml\nscripts/demo --nope\n```\n```bash\nscripts/bench \\\n'
                                '  --robots 3\n```\n')
        self.assertEqual(found, [(5, ['scripts/bench', '--robots', '3'])])


if __name__ == '__main__':
    unittest.main()
