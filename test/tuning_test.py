#!/usr/bin/env python3
"""Live tuning (issue 13): dynamic_reconfigure of the simulator's flocking parameters on a
running lock-step swarm. Every robot takes a change at the same tick - the tick the simulator
announces on /flock/tuning - and reports it in its ~state; a bad value (free will out of
[0, 360], a speed beyond the local range) is refused with an ERROR naming the key, and nothing
changes: not the server's values, not /flock/tuning, not any robot. The same server sets the
simulator's radio loss live (not relayed): at 1 no robot hears another."""

import sys
import threading
import unittest

import dynamic_reconfigure.client
import rospy
import rostest
from rosgraph_msgs.msg import Log
from swarm_transport.msg import Flocking_Tuning

import swarm_testing as st


class Tuning(unittest.TestCase):

    @classmethod
    def setUpClass(cls):
        g = lambda k: rospy.get_param('~' + k)  # noqa: E731
        cls.g = staticmethod(g)
        cls.timeout = g('timeout_s')
        cls.lock = threading.Lock()
        cls.tunings = []
        cls.errors = []
        cls.tuning_sub = rospy.Subscriber('/flock/tuning', Flocking_Tuning, cls._on_tuning,
                                          queue_size=10)
        cls.log_sub = rospy.Subscriber('/rosout', Log, cls._on_log, queue_size=1000)
        cls.positions = st.PositionLog()
        cls.swarm = st.launch_swarm(robots=g('robots'), seed=2, lockstep=True, max_ticks=0,
                                    real_time_factor=g('real_time_factor'))

    @classmethod
    def tearDownClass(cls):
        cls.tuning_sub.unregister()
        cls.log_sub.unregister()
        cls.positions.close()
        cls.swarm.shutdown()

    @classmethod
    def _on_tuning(cls, msg):
        with cls.lock:
            cls.tunings.append(msg)

    @classmethod
    def _on_log(cls, msg):
        if msg.level >= Log.ERROR and msg.name == '/simulator':
            with cls.lock:
                cls.errors.append(msg.msg)

    def states(self):
        return [st.robot_state(rid, self.timeout) for rid in range(self.g('robots'))]

    def settle(self):
        """Waits until the run is settle_ticks past now (every robot answered those ticks)."""
        now = self.positions.latest_tick()
        self.assertTrue(self.positions.wait_tick(now + self.g('settle_ticks'), self.timeout),
                        'the run stopped near tick %s' % now)

    def refused(self, client, change, key, before):
        with self.lock:
            errors_before = len(self.errors)
        answer = client.update_configuration(change)
        for k, v in before.items():
            self.assertAlmostEqual(answer[k], v, msg='%s changed to %s by %s' % (k, answer[k],
                                                                                   change))
        ok = st.wait_for(lambda: len(self.errors) > errors_before, self.timeout)
        self.assertTrue(ok, 'no ERROR from the simulator for %s' % change)
        with self.lock:
            line = self.errors[-1]
        self.assertIn(key, line)
        self.assertIn('nothing changed', line)

    def test_every_robot_takes_a_change_at_the_same_tick_and_a_bad_one_changes_nothing(self):
        g = self.g
        self.assertTrue(self.positions.wait_tick(g('change_after_tick'), self.timeout),
                        'the swarm never reached tick %d' % g('change_after_tick'))
        client = dynamic_reconfigure.client.Client('/simulator', timeout=self.timeout)
        start = client.get_configuration(timeout=self.timeout)
        # The server starts with /swarm's values (config/swarm.yaml), not the .cfg's defaults.
        self.assertAlmostEqual(start['free_will_deg'], rospy.get_param('/swarm/free_will_deg'))
        self.assertAlmostEqual(start['cohesion'], rospy.get_param('/swarm/cohesion'))
        for s in self.states():
            self.assertEqual(s.tuning_generation, 0)
            self.assertAlmostEqual(s.free_will_deg, rospy.get_param('/swarm/free_will_deg'))

        requested_at = self.positions.latest_tick()
        answer = client.update_configuration({'free_will_deg': g('free_will_deg')})
        self.assertAlmostEqual(answer['free_will_deg'], g('free_will_deg'))
        self.assertTrue(st.wait_for(lambda: len(self.tunings) >= 1, self.timeout),
                        'nothing on /flock/tuning')
        with self.lock:
            tuning = self.tunings[0]
        self.assertEqual(tuning.generation, 1)
        self.assertGreaterEqual(tuning.tick, requested_at)
        self.assertAlmostEqual(tuning.free_will_deg, g('free_will_deg'))
        self.assertAlmostEqual(tuning.cohesion, start['cohesion'])
        self.settle()
        states = self.states()
        self.assertEqual(sorted(s.robot_id for s in states), list(range(g('robots'))))
        for s in states:
            # The same tick for every robot: the one the simulator announced.
            self.assertEqual((s.robot_id, s.tuning_generation, s.tuning_tick),
                             (s.robot_id, 1, tuning.tick))
            self.assertAlmostEqual(s.free_will_deg, g('free_will_deg'))
            self.assertAlmostEqual(s.cohesion, start['cohesion'])
            self.assertAlmostEqual(s.local_range_m, start['local_range_m'])
            self.assertAlmostEqual(s.speed_m_per_tick, start['speed_m_per_tick'])
            self.assertGreater(s.ticks, tuning.tick)

        # Bad values: refused with the key named, the values in use stay everywhere.
        now = {'free_will_deg': g('free_will_deg'), 'speed_m_per_tick': start['speed_m_per_tick']}
        self.refused(client, {'free_will_deg': g('bad_free_will_deg')}, 'free_will_deg', now)
        self.refused(client, {'speed_m_per_tick': g('bad_speed_m_per_tick')}, 'speed_m_per_tick',
                     now)
        self.settle()
        with self.lock:
            self.assertEqual(len(self.tunings), 1, 'a refused value went out on /flock/tuning')
        after = client.get_configuration(timeout=self.timeout)
        self.assertAlmostEqual(after['free_will_deg'], g('free_will_deg'))
        self.assertAlmostEqual(after['speed_m_per_tick'], start['speed_m_per_tick'])
        for s in self.states():
            self.assertEqual((s.robot_id, s.tuning_generation), (s.robot_id, 1))
            self.assertAlmostEqual(s.free_will_deg, g('free_will_deg'))
            self.assertAlmostEqual(s.speed_m_per_tick, start['speed_m_per_tick'])

        # Range and speed together (a speed beyond the old range, within the new one): one
        # change, the next generation, again the same tick everywhere.
        wide = {'local_range_m': g('wide_local_range_m'),
                'speed_m_per_tick': g('wide_speed_m_per_tick')}
        answer = client.update_configuration(wide)
        self.assertAlmostEqual(answer['local_range_m'], wide['local_range_m'])
        self.assertTrue(st.wait_for(lambda: len(self.tunings) >= 2, self.timeout),
                        'the second change never went out')
        with self.lock:
            second = self.tunings[1]
        self.assertEqual(second.generation, 2)
        self.assertGreater(second.tick, tuning.tick)
        self.settle()
        for s in self.states():
            self.assertEqual((s.robot_id, s.tuning_generation, s.tuning_tick),
                             (s.robot_id, 2, second.tick))
            self.assertAlmostEqual(s.local_range_m, wide['local_range_m'])
            self.assertAlmostEqual(s.speed_m_per_tick, wide['speed_m_per_tick'])
            self.assertAlmostEqual(s.free_will_deg, g('free_will_deg'))

        # The simulator's radio loss (not relayed): 1 silences every robot's neighbours, a
        # probability outside [0, 1] is refused and changes nothing, 0 brings them back.
        self.assertAlmostEqual(after['radio_loss'], rospy.get_param('/swarm/radio_loss', 0.0))
        answer = client.update_configuration({'radio_loss': 1.0})
        self.assertAlmostEqual(answer['radio_loss'], 1.0)
        self.settle()
        heard = [s.heard for s in self.states()]
        self.assertEqual(heard, [0] * g('robots'), 'robots heard others at radio_loss 1')
        self.refused(client, {'radio_loss': g('bad_radio_loss')}, 'radio_loss',
                     {'radio_loss': 1.0})
        self.refused(client, {'radio_loss': 0.0, 'free_will_deg': g('bad_free_will_deg')},
                     'free_will_deg', {'radio_loss': 1.0, 'free_will_deg': g('free_will_deg')})
        self.settle()
        self.assertEqual([s.heard for s in self.states()], [0] * g('robots'),
                         'a refused change reached the radio')
        client.update_configuration({'radio_loss': 0.0})
        self.assertTrue(st.wait_for(lambda: sum(s.heard for s in self.states()) > 0,
                                    self.timeout),
                        'no robot hears another after radio_loss went back to 0')
        with self.lock:
            self.assertEqual(len(self.tunings), 2, 'the radio loss went out on /flock/tuning')


if __name__ == '__main__':
    rospy.init_node('tuning_test')
    rostest.rosrun('swarm_transport', 'tuning', Tuning, sys.argv)
