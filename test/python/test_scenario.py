"""The scenario format and its expectation checks without ROS (issue 14): the shipped example
parses; a malformed scenario gets one error naming the line and the key; every expectation
passes on a hand-made log that meets it and fails on one that does not."""
import os
import unittest

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.realpath(__file__))))

from swarm_transport import scenario_checks as checks
from swarm_transport import scenario_format as fmt

MINIMAL = '''world:
  robots: 6
max_ticks: 100
missions:
  - id: 7
    robots_from: 0
    robots_to: 4
    leaders: 1
    object: [5.0, 5.0, 1.0, 1.0]
    target: [3.0, 3.0]
expect:
  - mission_state: {mission: 7, state: DONE, by_tick: 90}
'''


class Format(unittest.TestCase):

    def test_the_shipped_scenarios_parse(self):
        d = os.path.join(ROOT, 'test', 'scenarios')
        files = sorted(f for f in os.listdir(d) if f.endswith('.yaml'))
        self.assertIn('example.yaml', files)
        for f in files:
            s = fmt.load(os.path.join(d, f))
            self.assertTrue(s['expect'], f)
        s = fmt.load(os.path.join(d, 'example.yaml'))
        self.assertEqual(s['world']['robots'], 25)
        self.assertEqual(s['missions'][0]['robot_ids'], list(range(12)))
        self.assertEqual([e['kind'] for e in s['events']], ['freeze', 'continue'])
        self.assertEqual(s['events'][0]['range'], [20, 25])

    def test_defaults(self):
        s = fmt.parse(MINIMAL, 'm.yaml')
        self.assertEqual((s['world']['deploy'], s['world']['clock'], s['world']['seed']),
                         ('host_sim', 'lockstep', 1))
        self.assertEqual(s['missions'][0]['at_tick'], 0)

    def expect_error(self, text, line, *words):
        """`text` refused with an error that names line `line` and holds each of `words`."""
        with self.assertRaises(fmt.ScenarioError) as cm:
            fmt.parse(text, 'bad.yaml')
        msg = str(cm.exception)
        self.assertTrue(msg.startswith('bad.yaml:%d: ' % line), msg)
        for w in words:
            self.assertIn(w, msg)

    def test_a_recruiting_mission_names_no_robots(self):
        recruit = MINIMAL.replace('    robots_from: 0\n    robots_to: 4\n', '    recruit: 3\n')
        m = fmt.parse(recruit, 'r.yaml')['missions'][0]
        self.assertEqual((m['recruit'], m['robot_ids']), (3, []))
        self.expect_error(MINIMAL.replace('    robots_from: 0\n', '    recruit: 3\n'
                                          '    robots_from: 0\n'), 6,
                          'missions[0].recruit: names no robots')
        self.expect_error(recruit.replace('leaders: 1', 'leaders: 4'), 7,
                          'missions[0].leaders: more leaders than recruit')

    def test_a_malformed_scenario_names_the_line_and_the_key(self):
        self.expect_error(MINIMAL.replace('max_ticks: 100', 'max_tick: 100'), 3,
                          'max_tick: unknown key')
        self.expect_error(MINIMAL.replace('leaders: 1', 'leaders: 5'), 8,
                          'missions[0].leaders: more leaders than robots')
        self.expect_error(MINIMAL.replace('robots_to: 4', 'robots_to: 0'), 7,
                          'missions[0].robots_to: must be > robots_from')
        self.expect_error(MINIMAL.replace('[3.0, 3.0]', '[3.0, .nan]'), 10,
                          'missions[0].target[1]: must be a finite number')
        self.expect_error(MINIMAL + 'events:\n  - at_tick: 5\n    freeze: [4, 2]\n', 15,
                          'events[0].freeze: must be [from, to)')
        self.expect_error(MINIMAL + 'events:\n  - at_tick: 5\n    signal: {mission: 8, '
                          'event: LOADED}\n', 15, 'events[0].signal.mission: no mission 8')
        self.expect_error(MINIMAL.replace('state: DONE', 'state: FINISHED'), 12,
                          'expect[0].mission_state.state: must be one of')
        self.expect_error(MINIMAL.replace('  robots: 6', '  robots: 6\n  deploy: cloud'), 3,
                          'world.deploy: must be one of process, host, host_sim, hardware')
        self.expect_error(MINIMAL.replace('max_ticks: 100\n', ''), 1, "missing 'max_ticks'")
        self.expect_error('world: [1\n', 2, 'not YAML')
        self.expect_error(MINIMAL + '  - swarm_count: {at_tick: 50, min: 3, max: 2}\n', 13,
                          'min 3 > max 2')

    def test_spawns_and_kills_name_robots_that_are_or_are_not_there(self):
        ev = lambda text: MINIMAL + 'events:\n' + text  # noqa: E731
        self.expect_error(ev('  - at_tick: 5\n    kill: 6\n'), 15,
                          'events[0].kill: no robot 6 in the world at tick 5 (world.robots: 0..5')
        self.expect_error(ev('  - at_tick: 5\n    spawn: {id: 2, x: 1, y: 1}\n'), 15,
                          'events[0].spawn: robot 2 is in the world already at tick 5')
        # in tick order, whatever the file order: killed at 9, robot 3 cannot be killed at 20
        self.expect_error(ev('  - at_tick: 20\n    kill: 3\n  - at_tick: 9\n    kill: 3\n'),
                          15, 'events[0].kill: no robot 3 in the world at tick 20')
        s = fmt.parse(ev('  - at_tick: 30\n    kill: 6\n  - at_tick: 10\n'
                         '    spawn: {id: 6, x: 1, y: 1}\n  - at_tick: 40\n'
                         '    spawn: {id: 6, x: 2, y: 2}\n  - at_tick: 40\n    kill: 0\n'),
                      'ok.yaml')
        self.assertEqual([(e['kind'], e['at_tick']) for e in s['events']],
                         [('kill', 30), ('spawn', 10), ('spawn', 40), ('kill', 40)])

    def test_a_malformed_world_names_the_line_and_the_key(self):
        world = lambda text: MINIMAL.replace('  robots: 6', '  robots: 6\n' + text)  # noqa
        # /swarm keys: a misspelt one is named with the near key, a value of the wrong kind too
        self.expect_error(world('  config:\n    free_will_dg: 45'), 4,
                          'world.config.free_will_dg: unknown key (did you mean free_will_deg?')
        self.expect_error(world('  config:\n    cohesion: 0.3\n    free_will_deg: fast'), 5,
                          "world.config.free_will_deg: must be a finite number (as in "
                          "config/swarm.yaml) but is 'fast'")
        self.expect_error(world('  config:\n    free_will_deg: .inf'), 4,
                          'world.config.free_will_deg: must be a finite number')
        self.expect_error(world('  base_config: thesis.yaml'), 3,
                          "world.base_config: no file 'thesis.yaml'")
        self.expect_error(world('  placement: file\n  placement_file: /no/such/file.txt'), 4,
                          'world.placement_file: no file /no/such/file.txt')
        # danger zones, in world or in world.config, as config/obstacles.yaml writes them
        self.expect_error(world('  danger_zones:\n    - {shape: square, x: 5, y: 5}'), 4,
                          "world.danger_zones[0].shape: must be one of rect, circle but is "
                          "'square'")
        self.expect_error(world('  danger_zones:\n    - {shape: circle, x: 5, y: 5, radius: 1}'
                                '\n    - {shape: rect, x: 5, y: 5, size_x: 0, size_y: 1}'),
                          5, 'world.danger_zones[1].size_x: must be a finite number in [1e-09')
        self.expect_error(world('  danger_zones:\n    - {shape: circle, x: 5, y: 5}'), 4,
                          "world.danger_zones[0]: missing 'radius'")
        self.expect_error(world('  config:\n    danger_zones:\n'
                                '      - {shape: rect, x: 1, y: 1}'), 5,
                          "world.config.danger_zones[0]: missing 'size_x'")
        # and the good ones pass through
        s = fmt.parse(world('  base_config: thesis_transport.yaml\n  config:\n'
                            '    free_will_deg: 45\n    radio_loss: 0.1\n  danger_zones:\n'
                            '    - {shape: circle, x: 5, y: 5, radius: 1}'), 'ok.yaml')
        self.assertEqual(s['world']['config'], {'free_will_deg': 45, 'radio_loss': 0.1})
        self.assertEqual(s['world']['danger_zones'],
                         [{'shape': 'circle', 'x': 5, 'y': 5, 'radius': 1}])

    def test_the_hardware_stand_in_runs_on_the_wall_clock_with_its_bases_and_events(self):
        hw = lambda text: MINIMAL.replace('  robots: 6', '  robots: 6\n' + text)  # noqa
        self.expect_error(hw('  deploy: hardware'), 3,
                          'world.deploy: hardware runs on the wall clock: needs clock: realtime')
        self.expect_error(hw('  bases: {position_noise_m: 0.01}'), 3,
                          'world.bases: only with deploy: hardware')
        real = hw('  deploy: hardware\n  clock: realtime\n  bases: {heading_drift_deg: 0.5}')
        self.expect_error(real.replace('drift_deg', 'drift'), 5,
                          'world.bases.heading_drift: unknown key')
        self.expect_error(real + 'events:\n  - at_tick: 5\n    kill: 2\n', 17,
                          'events[0].kill: world.deploy: hardware plays only odom_stop')
        self.expect_error(MINIMAL + 'events:\n  - at_tick: 5\n    odom_stop: {robot: 2, ticks: 3}'
                          '\n', 14, 'events[0].odom_stop: world.deploy: hardware plays only')
        self.expect_error(real + 'events:\n  - at_tick: 5\n    odom_stop: {robot: 2, ticks: 0}'
                          '\n', 18, 'events[0].odom_stop.ticks: must be an integer in [1')
        s = fmt.parse(real + 'events:\n  - at_tick: 5\n    odom_stop: {robot: 2, ticks: 20}\n',
                      'ok.yaml')
        self.assertEqual(s['world']['bases'], {'heading_drift_deg': 0.5})
        self.assertEqual(s['events'][0], {'at_tick': 5, 'kind': 'odom_stop', 'robot': 2,
                                          'ticks': 20})


def log_of(positions, statuses=(), objects=None, metrics=None):
    return checks.RunLog(positions, statuses, objects, metrics)


class Checks(unittest.TestCase):

    expect_error = Format.expect_error

    def setUp(self):
        self.s = fmt.parse(MINIMAL, 'm.yaml')

    def run_check(self, text, log, second=None):
        e = fmt.parse(MINIMAL + text, 'm.yaml')['expect'][-1]
        return checks.check(e, log, self.s, second)

    def test_a_mission_state_by_a_tick(self):
        log = log_of({}, [(7, 'QUEUED', 0), (7, 'GATHERING', 1), (7, 'DONE', 80)])
        self.assertTrue(checks.check(self.s['expect'][0], log, self.s)[0])
        late = log_of({}, [(7, 'QUEUED', 0), (7, 'DONE', 95)])
        ok, measured = checks.check(self.s['expect'][0], late, self.s)
        self.assertFalse(ok)  # an impossible deadline fails
        self.assertIn('DONE at tick 95', measured)
        self.assertFalse(checks.check(self.s['expect'][0], log_of({}, []), self.s)[0])

    def test_in_arena_and_overlap(self):
        inside = log_of({0: {0: (1.0, 1.0, 0), 1: (1.2, 1.0, 0)}})
        self.assertTrue(self.run_check('  - in_arena: {}\n', inside)[0])
        self.assertTrue(self.run_check('  - no_overlap: {}\n', inside)[0])
        out = log_of({0: {0: (-0.02, 1.0, 0)}, 1: {0: (11.2, 1.0, 0)}})
        ok, measured = self.run_check('  - in_arena: {tolerance_m: 0.05}\n', out)
        self.assertFalse(ok)
        self.assertIn('robot 0, tick 1', measured)
        touching = log_of({3: {0: (1.0, 1.0, 0), 1: (1.08, 1.0, 0)}})
        ok, measured = self.run_check('  - no_overlap: {tolerance_m: 0.01}\n', touching)
        self.assertFalse(ok)
        self.assertIn('0.0200', measured)
        self.assertTrue(self.run_check('  - no_overlap: {tolerance_m: 0.03}\n', touching)[0])

    def test_no_intrusion_follows_the_object_while_it_is_live(self):
        # Robot 5 is not assigned; the 1 x 1 object is at (5, 5) at tick 0, at (6, 5) at tick
        # 20 and gone at tick 40.
        objects = {0: {7: (5.0, 5.0, 1.0, 1.0)}, 20: {7: (6.0, 5.0, 1.0, 1.0)}, 40: {}}
        clear = log_of({0: {5: (5.6, 5.0, 0)}, 20: {5: (5.0, 5.0, 0)},
                        40: {5: (6.0, 5.0, 0)}}, objects=objects)
        self.assertTrue(self.run_check('  - no_intrusion: {}\n', clear)[0])
        inside = log_of({20: {5: (6.1, 5.0, 0)}}, objects=objects)
        ok, measured = self.run_check('  - no_intrusion: {tolerance_m: 0.1}\n', inside)
        self.assertFalse(ok)
        self.assertIn('robot 5', measured)
        self.assertIn('tick 20', measured)
        self.assertTrue(self.run_check('  - no_intrusion: {tolerance_m: 0.5}\n', inside)[0])
        # Up to a phase only: from TRANSPORT on the object moves onto robots that flee it.
        moving = log_of({20: {5: (6.1, 5.0, 0)}}, [(7, 'TRANSPORT', 15)], objects)
        self.assertTrue(self.run_check('  - no_intrusion: {until_phase: TRANSPORT}\n',
                                       moving)[0])
        self.assertFalse(self.run_check('  - no_intrusion: {until_phase: DONE}\n', moving)[0])
        # Its own robots may be inside.
        self.assertTrue(self.run_check('  - no_intrusion: {}\n',
                                       log_of({20: {1: (6.0, 5.0, 0)}}, objects=objects))[0])

    def test_swarm_count_and_metrics(self):
        pts = {50: {0: (1.0, 1.0, 0), 1: (1.9, 1.0, 0), 2: (5.0, 5.0, 0)}}
        self.assertTrue(self.run_check('  - swarm_count: {at_tick: 50, min: 2, max: 2}\n',
                                       log_of(pts))[0])
        ok, measured = self.run_check('  - swarm_count: {at_tick: 50, max: 1}\n', log_of(pts))
        self.assertFalse(ok)
        self.assertIn('2 swarm(s)', measured)
        self.assertFalse(self.run_check('  - swarm_count: {at_tick: 40}\n', log_of(pts))[0])
        metrics = {7: {'transport_ticks': '68', 'slip_per_robot_m': '2.5'}}
        self.assertTrue(self.run_check('  - transport_ticks: {mission: 7, max: 70}\n',
                                       log_of({}, metrics=metrics))[0])
        self.assertFalse(self.run_check('  - slip_per_robot_m: {mission: 7, max: 2.0}\n',
                                        log_of({}, metrics=metrics))[0])
        self.assertFalse(self.run_check('  - transport_ticks: {mission: 7}\n',
                                        log_of({}, metrics={7: {'transport_ticks': ''}}))[0])

    def test_phases_gathered_and_still_while_frozen(self):
        statuses = [(7, 'QUEUED', 0), (7, 'GATHERING', 0), (7, 'LOADING', 10),
                    (7, 'TRANSPORT', 20), (7, 'DONE', 30)]
        objects = {10: {7: (5.0, 5.0, 1.0, 1.0)}}
        inside = {0: (4.8, 5.0, 0), 1: (5.2, 5.1, 0), 2: (5.0, 4.6, 0), 3: (5.0, 5.4, 0)}
        moved = {**inside, 2: (5.0, 4.7, 0)}
        log = log_of({10: inside, 13: inside, 20: inside}, statuses, objects)
        self.assertTrue(self.run_check(
            '  - phases: {mission: 7, states: [QUEUED, GATHERING, LOADING, TRANSPORT, DONE]}\n',
            log)[0])
        ok, measured = self.run_check('  - phases: {mission: 7, states: [QUEUED, DONE]}\n', log)
        self.assertFalse(ok)
        self.assertIn('GATHERING', measured)
        self.assertTrue(self.run_check('  - gathered: {mission: 7}\n', log)[0])
        out = log_of({10: {**inside, 3: (5.0, 5.7, 0)}}, statuses, objects)
        ok, measured = self.run_check('  - gathered: {mission: 7, tolerance_m: 0.1}\n', out)
        self.assertFalse(ok)
        self.assertIn('robot 3', measured)
        self.assertTrue(self.run_check('  - still_while_frozen: {mission: 7}\n', log)[0])
        ok, measured = self.run_check('  - still_while_frozen: {mission: 7}\n',
                                      log_of({13: inside, 20: moved}, statuses, objects))
        self.assertFalse(ok)
        self.assertIn('robot 2', measured)

    def test_phase_order_and_released(self):
        text = '  - phase_order: {mission: 7, state: DONE, after_mission: 7, after_state: QUEUED}\n'
        log = log_of({}, [(7, 'QUEUED', 3), (7, 'DONE', 9)])
        self.assertTrue(self.run_check(text, log)[0])
        swapped = text.replace('DONE', 'X').replace('QUEUED', 'DONE').replace('X', 'QUEUED')
        ok, measured = self.run_check(swapped, log)
        self.assertFalse(ok)
        self.assertIn('QUEUED at tick 3', measured)
        free = checks.RunLog({}, [], robot_states={0: ([], [], False), 1: ([], [], False)})
        self.assertTrue(self.run_check('  - released: {}\n', free)[0])
        held = checks.RunLog({}, [], robot_states={0: ([], [], False), 1: ([7], [7], True)})
        ok, measured = self.run_check('  - released: {}\n', held)
        self.assertFalse(ok)
        self.assertIn('(1, ([7], [7], True))', measured)
        self.assertFalse(self.run_check('  - released: {}\n', log)[0])

    def test_object_clear_of_zones(self):
        s = fmt.parse(MINIMAL.replace('  robots: 6', '  robots: 6\n  danger_zones:\n'
                                      '    - {shape: rect, x: 5.0, y: 3.0, size_x: 1.0, '
                                      'size_y: 1.0}\n    - {shape: circle, x: 8.0, y: 8.0, '
                                      'radius: 0.5}') + '  - object_clear_of_zones: '
                      '{mission: 7}\n', 'z.yaml')
        e = s['expect'][-1]
        clear = log_of({}, objects={1: {7: (5.0, 4.6, 1.0, 1.0)}, 2: {7: (7.0, 8.0, 1.0, 1.0)}})
        self.assertTrue(checks.check(e, clear, s)[0])
        rect = log_of({}, objects={1: {7: (5.0, 3.9, 1.0, 1.0)}})
        ok, measured = checks.check(e, rect, s)
        self.assertFalse(ok)
        self.assertIn('0.1000 m (danger_zones[0], tick 1)', measured)
        circle = log_of({}, objects={3: {7: (7.2, 8.0, 1.0, 1.0)}})
        ok, measured = checks.check(e, circle, s)
        self.assertFalse(ok)
        self.assertIn('danger_zones[1], tick 3', measured)
        self.assertFalse(checks.check(e, log_of({}, objects={}), s)[0])  # never listed

    def test_robots_clear_of_zones(self):
        s = fmt.parse(MINIMAL.replace('  robots: 6', '  robots: 6\n  danger_zones:\n'
                                      '    - {shape: rect, x: 3.0, y: 5.0, size_x: 0.4, '
                                      'size_y: 2.0}') + '  - robots_clear_of_zones: '
                      '{mission: 7}\n', 'r.yaml')
        e = s['expect'][-1]
        self.assertEqual(e['until_state'], 'LOADING')
        # Robot 1 passes north of the zone; robot 5 (not the mission's) crosses it.
        around = {1: {1: (2.7, 6.1, 0), 5: (2.7, 5.0, 0)}, 2: {1: (3.3, 6.1, 0), 5: (3.3, 5.0, 0)}}
        self.assertTrue(checks.check(e, log_of(around), s)[0])
        # A move whose ends are outside but which cuts the zone's corner fails.
        cut = {1: {1: (2.7, 5.8, 0)}, 2: {1: (2.9, 6.1, 0)}}
        ok, measured = checks.check(e, log_of(cut), s)
        self.assertFalse(ok)
        self.assertIn('(robot 1, danger_zones[0], tick 2)', measured)
        # After LOADING it is not checked.
        late = {1: {1: (2.7, 6.1, 0)}, 2: {1: (2.8, 6.1, 0)}, 3: {1: (3.0, 5.0, 0)}}
        self.assertTrue(checks.check(e, log_of(late, [(7, 'LOADING', 2)]), s)[0])
        self.assertFalse(checks.check(e, log_of(late), s)[0])
        self.assertFalse(checks.check(e, log_of({}), s)[0])  # no move

    def test_centroid_near_and_statist_events(self):
        s = fmt.parse(MINIMAL + 'events:\n  - at_tick: 2\n    statist: {id: 900, x: 8, y: 8}\n'
                      '  - at_tick: 9\n    remove_statist: {id: 900}\n', 'm.yaml')
        self.assertEqual([(e['kind'], e['robot'], e['sub_id']) for e in s['events']],
                         [('statist', 900, 0), ('remove_statist', 900, 0)])
        log = log_of({5: {0: (1.0, 1.0, 0), 1: (3.0, 1.0, 0)}})
        self.assertTrue(self.run_check('  - centroid_near: {at_tick: 5, x: 2, y: 1, max_m: 0.1}\n',
                                       log)[0])
        ok, measured = self.run_check('  - centroid_near: {at_tick: 5, x: 8, y: 8, max_m: 2}\n',
                                      log)
        self.assertFalse(ok)
        self.assertIn('centroid (2.00, 1.00)', measured)
        self.assertTrue(self.run_check('  - centroid_near: {at_tick: 5, x: 8, y: 8, min_m: 5}\n',
                                       log)[0])

    def test_centroid_approach_measures_how_much_nearer_the_centroid_came(self):
        # From tick 5 to 9 the centroid moves from (2, 1) to (4, 1): 2 m nearer (8, 1), 2 m
        # farther from (0, 1).
        log = log_of({5: {0: (1.0, 1.0, 0), 1: (3.0, 1.0, 0)},
                      9: {0: (3.0, 1.0, 0), 1: (5.0, 1.0, 0)}})
        approach = '  - centroid_approach: {from_tick: 5, to_tick: 9, x: %s, y: 1, %s}\n'
        ok, measured = self.run_check(approach % (8, 'max_m: 0.5'), log)
        self.assertFalse(ok)
        self.assertIn('centroid 2.00 m nearer from tick 5 to 9 (6.00 -> 4.00 m away)', measured)
        self.assertTrue(self.run_check(approach % (8, 'min_m: 1.9, max_m: 2.1'), log)[0])
        self.assertTrue(self.run_check(approach % (0, 'max_m: -1.9'), log)[0])
        self.assertFalse(self.run_check(approach % (0, 'min_m: -1.9'), log)[0])
        ok, measured = self.run_check(approach.replace('9', '7') % (8, 'max_m: 5'), log)
        self.assertFalse(ok)
        self.assertIn('no positions at tick 7', measured)
        for bad, words in ((approach % (8, 'min_m: 1, max_m: -1'), 'min_m 1 > max_m -1'),
                           (approach.replace('9', '5') % (8, 'max_m: 1'),
                            'from_tick 5 must be < to_tick 5')):
            self.expect_error(MINIMAL + bad, 13, words)

    def test_spacing_bounds_the_nearest_neighbour_distances_and_their_spread(self):
        # Nearest neighbours 1, 1 and 2 m: mean 4/3, cv sqrt(2/9) / (4/3) = 0.354.
        log = log_of({5: {0: (1.0, 1.0, 0), 1: (2.0, 1.0, 0), 2: (4.0, 1.0, 0)}})
        ok, measured = self.run_check('  - spacing: {at_tick: 5, min_nn_m: 0.9, max_nn_m: 2.1}\n',
                                      log)
        self.assertTrue(ok, measured)
        self.assertIn('1.000-2.000 m', measured)
        self.assertIn('cv 0.3536', measured)
        for bad in ('{at_tick: 5, min_nn_m: 1.1}', '{at_tick: 5, max_nn_m: 1.9}',
                    '{at_tick: 5, max_cv: 0.3}', '{at_tick: 6}'):
            self.assertFalse(self.run_check('  - spacing: %s\n' % bad, log)[0], bad)

    def test_robot_near_and_swarm_of_at_a_tick_or_a_state(self):
        # robot 4 leads to (5, 5): at DONE (tick 6) it is 0.1 m from it with robots 0 and 1 in
        # its swarm (hop by hop within 1 m), robot 2 far away; robot 3 has not arrived at tick 2.
        log = log_of({2: {0: (1.0, 1.0, 0), 1: (1.5, 1.0, 0), 2: (9.0, 9.0, 0), 4: (2.0, 2.0, 0)},
                      6: {0: (4.0, 5.0, 0), 1: (3.2, 5.0, 0), 2: (9.0, 9.0, 0),
                          4: (4.9, 5.0, 0)}},
                     [(7, 'QUEUED', 0), (7, 'TRANSPORT', 1), (7, 'DONE', 6)])
        near = '  - robot_near: {robot: 4, x: 5, y: 5, max_m: %s, mission: 7, state: DONE}\n'
        ok, measured = self.run_check(near % 0.11, log)
        self.assertTrue(ok, measured)
        self.assertIn('robot 4 at (4.90, 5.00) at tick 6 (mission 7 DONE), 0.100 m away',
                      measured)
        self.assertFalse(self.run_check(near % 0.09, log)[0])
        self.assertFalse(self.run_check(
            '  - robot_near: {robot: 4, x: 5, y: 5, max_m: 1, at_tick: 2}\n', log)[0])
        ok, measured = self.run_check(
            '  - robot_near: {robot: 4, x: 5, y: 5, mission: 7, state: UNLOADING}\n', log)
        self.assertFalse(ok)
        self.assertIn('never reported UNLOADING', measured)
        self.assertFalse(self.run_check(
            '  - robot_near: {robot: 9, x: 5, y: 5, at_tick: 6}\n', log)[0])  # no robot 9
        of = '  - swarm_of: {robot: 4, min_fraction: %s, mission: 7, state: DONE}\n'
        ok, measured = self.run_check(of % 0.66, log)
        self.assertTrue(ok, measured)
        self.assertIn("2 of the 3 other robots in robot 4's swarm at tick 6", measured)
        self.assertFalse(self.run_check(of % 0.8, log)[0])
        ok, measured = self.run_check(
            '  - swarm_of: {robot: 4, min_fraction: 0.3, at_tick: 2}\n', log)
        self.assertFalse(ok)
        self.assertIn('0 of the 3 other robots', measured)  # 1.1 m from robot 1
        self.assertTrue(self.run_check(
            '  - swarm_of: {robot: 2, max_fraction: 0.0, at_tick: 6}\n', log)[0])

    def test_robot_count_at_a_tick(self):
        log = log_of({3: {0: (1, 1, 0), 1: (2, 2, 0), 2: (3, 3, 0), 5: (4, 4, 0)},
                      4: {0: (1, 1, 0), 1: (2, 2, 0), 2: (3, 3, 0)}})
        ok, measured = self.run_check('  - robot_count: {at_tick: 3, min: 4, max: 4}\n', log)
        self.assertTrue(ok, measured)
        self.assertEqual(measured, '4 robot(s) at tick 3: 0-2, 5')
        ok, measured = self.run_check('  - robot_count: {at_tick: 4, min: 4}\n', log)
        self.assertFalse(ok)
        self.assertEqual(measured, '3 robot(s) at tick 4: 0-2')
        self.assertFalse(self.run_check('  - robot_count: {at_tick: 3, max: 3}\n', log)[0])
        self.assertFalse(self.run_check('  - robot_count: {at_tick: 7}\n', log)[0])

    def test_a_tick_is_named_once_for_robot_near_and_swarm_of(self):
        for bad, words in (('{robot: 4, x: 5, y: 5}', 'needs either at_tick or mission and'),
                           ('{robot: 4, x: 5, y: 5, at_tick: 3, mission: 7, state: DONE}',
                            'needs either at_tick or mission and'),
                           ('{robot: 4, x: 5, y: 5, mission: 7}', 'needs either at_tick'),
                           ('{robot: 4, x: 5, y: 5, at_tick: 3, min_m: 2, max_m: 1}',
                            'min_m 2 > max_m 1')):
            self.expect_error(MINIMAL + '  - robot_near: %s\n' % bad, 13,
                              'expect[1].robot_near', words)
        self.expect_error(MINIMAL + '  - swarm_of: {robot: 4, min_fraction: 1.5, at_tick: 3}\n',
                          13, 'expect[1].swarm_of.min_fraction: must be a finite number in '
                          '[0.0, 1.0]')

    def test_moved_and_in_arena_with_an_inset(self):
        log = log_of({0: {0: (1.0, 1.0, 0), 1: (2.0, 2.0, 0)},
                      9: {0: (1.5, 1.0, 0), 1: (2.0, 2.02, 0)}})
        self.assertTrue(self.run_check('  - moved: {min_m: 0.01}\n', log)[0])
        ok, measured = self.run_check('  - moved: {min_m: 0.05}\n', log)
        self.assertFalse(ok)
        self.assertIn('0.0200 m (robot 1)', measured)
        edge = log_of({0: {0: (0.03, 5.0, 0)}})
        self.assertTrue(self.run_check('  - in_arena: {}\n', edge)[0])
        ok, measured = self.run_check('  - in_arena: {inset_m: 0.05, tolerance_m: 0.001}\n',
                                      edge)
        self.assertFalse(ok)
        self.assertIn('0.0200 m', measured)


if __name__ == '__main__':
    unittest.main()
