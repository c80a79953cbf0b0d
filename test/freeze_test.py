#!/usr/bin/env python3
"""Bad freeze and position input in lock-step: an inverted Robot_Freeze range is rejected and
changes nothing; a NaN Robot_Position is rejected and every node goes on ticking; a burst of bad
messages costs each robot one log line, not one per message. Each bad message is followed by a
good one on the same topic whose effect is seen, so the bad one was delivered before it (one
publisher, one connection, in order): "nothing happened" is not a lost message. (Freeze then
continue is a scenario: test/scenarios/freeze_continue.yaml.)"""

import sys
import unittest

import rospy
import rostest
from rosgraph_msgs.msg import Log
from swarm_transport.msg import Delete_Robot, Neighbors, Robot_Continue, Robot_Freeze, Robot_Position

import swarm_testing as st


class FreezeContinue(unittest.TestCase):

    @classmethod
    def setUpClass(cls):
        cls.robots = rospy.get_param('~robots')
        cls.timeout = rospy.get_param('~timeout_s')
        cls.log = st.PositionLog()
        cls.freeze = rospy.Publisher('/flock/freeze', Robot_Freeze, queue_size=10)
        cls.cont = rospy.Publisher('/flock/continue', Robot_Continue, queue_size=10)
        cls.position = rospy.Publisher('/flock/position', Robot_Position, queue_size=10)
        cls.delete = rospy.Publisher('/flock/robot/delete', Delete_Robot, queue_size=10)
        cls.swarm = st.launch_swarm(robots=cls.robots, seed=rospy.get_param('~seed'),
                                    lockstep=True, max_ticks=0)
        assert cls.log.wait_tick(5, cls.timeout), 'the swarm never ticked'
        # Every robot must be connected before a command means anything.
        assert st.wait_connected(cls.freeze, cls.timeout)
        assert st.wait_connected(cls.cont, cls.timeout)
        assert st.wait_connected(cls.position, cls.timeout)
        assert st.wait_connected(cls.delete, cls.timeout)

    @classmethod
    def tearDownClass(cls):
        cls.swarm.shutdown()
        cls.log.close()

    def frozen(self):
        """Which robots say they are frozen (their ~state service)."""
        return {rid for rid in range(self.robots) if st.robot_state(rid, self.timeout).frozen}

    def window(self, ticks):
        """Positions at the start and the end of the next `ticks` ticks."""
        t0 = self.log.latest_tick()
        self.assertTrue(self.log.wait_tick(t0 + ticks, self.timeout))
        return self.log.at(t0), self.log.at(t0 + ticks)

    def driven(self, ticks):
        """Per robot, the path driven in the next `ticks` ticks (sum of the per-tick moves):
        a robot free to move may still end up near where it started."""
        t0 = self.log.latest_tick()
        self.assertTrue(self.log.wait_tick(t0 + ticks, self.timeout))
        # A frame this process missed only shortens the sum (a chord for two moves).
        frames = [f for f in (self.log.at(t) for t in range(t0, t0 + ticks + 1)) if f]
        self.assertGreaterEqual(len(frames), 2, 'no frames of /flock/world_poses')
        return {rid: sum(st.moved(a[rid], b[rid]) for a, b in zip(frames, frames[1:]))
                for rid in frames[0]}

    def test_2_inverted_freeze_is_rejected(self):
        min_move = rospy.get_param('~min_move_m')
        span = rospy.get_param('~window_ticks')
        self.assertEqual(self.frozen(), set())
        lines = {}      # robot -> its lines about the inverted Robot_Freeze
        sentinels = {}  # robot -> its lines about the inverted Robot_Continue sent after it

        def on_log(msg):
            if not msg.msg.startswith('robot '):
                return
            rid = int(msg.msg.split()[1].rstrip(':'))
            for what, seen in (('rejected freeze [', lines),
                               ('rejected continue [', sentinels)):
                if what in msg.msg:
                    seen[rid] = seen.get(rid, 0) + 1

        log_sub = rospy.Subscriber('/rosout', Log, on_log, queue_size=1000)
        # Connected to every robot's /rosout publication, we hear every line from now on.
        self.assertTrue(st.wait_hears(log_sub, ['/robot_%d/robot' % r for r in range(self.robots)],
                                      self.timeout), 'not connected to every robot\'s /rosout')
        burst = rospy.get_param('~bad_burst')
        for _ in range(burst):
            self.freeze.publish(Robot_Freeze(8, 3))  # from > to: rejected, nobody freezes
        self.window(rospy.get_param('~settle_ticks'))
        self.assertEqual(self.frozen(), set(), 'an inverted Robot_Freeze froze robots')
        # Delivered and said (each robot logs it) - but once, not once per message.
        self.assertTrue(st.wait_for(lambda: sorted(lines) == list(range(self.robots)),
                                    self.timeout),
                        'robots that logged the rejection: %s' % sorted(lines))
        # Every robot logs the rejection of a later message of another kind (its own throttle)
        # after whatever it logged about the burst: with that line here, all of them are.
        self.cont.publish(Robot_Continue(8, 3))
        self.assertTrue(st.wait_for(lambda: sorted(sentinels) == list(range(self.robots)),
                                    self.timeout),
                        'robots that logged the inverted Robot_Continue: %s' % sorted(sentinels))
        log_sub.unregister()
        self.assertLessEqual(max(lines.values()), rospy.get_param('~max_log_lines_per_robot'),
                             'log lines per robot for %d bad messages: %s' % (burst, lines))
        driven = self.driven(span)
        for rid in range(self.robots):
            self.assertGreater(driven[rid], min_move,
                               'robot %d stopped after an inverted Robot_Freeze' % rid)

    def test_3_nan_position_is_rejected(self):
        # What robot 0 perceives: statists reach every robot, wherever they are.
        extras = []  # per round: the non-physical robots robot 0 heard

        def on_round(msg):
            extras.append([(r.robot_id, r.sub_id, r.type, r.pos_x, r.pos_y)
                           for r in msg.robots if r.type != Robot_Position.TYPE_PHYSICAL])

        rounds = rospy.Subscriber('/robot_0/neighbors', Neighbors, on_round, queue_size=1000)
        self.assertTrue(st.wait_hears(rounds, ['/simulator'], self.timeout))
        self.assertTrue(st.wait_for(lambda: extras, self.timeout), 'robot 0 got no round')
        self.assertEqual(extras[-1], [], 'a statist before the test')
        self.position.publish(Robot_Position(robot_id=3, sub_id=0, type=2, pos_x=float('nan'),
                                             pos_y=1.0, angle=0.0))
        self.position.publish(Robot_Position(robot_id=3, sub_id=0, type=0, pos_x=1.0,
                                             pos_y=float('nan'), angle=0.0))
        # Then a good statist (another sub id): once robot 0 hears it, the simulator had the bad
        # ones before it.
        good = (3, 1, 2, 4.0, 5.0)
        self.position.publish(Robot_Position(robot_id=3, sub_id=1, type=2, pos_x=4.0, pos_y=5.0,
                                             angle=0.0))
        try:
            self.assertTrue(st.wait_for(lambda: good in extras[-1], self.timeout),
                            'the good statist never reached robot 0: %s' % extras[-1:])
            a, b = self.window(rospy.get_param('~window_ticks'))
            # The NaN statist was not taken: from its first round with the good one on, that is
            # all robot 0 hears.
            heard = list(extras)
            first = next(k for k, e in enumerate(heard) if good in e)
            self.assertEqual([e for e in heard[first:] if e != [good]], [],
                             'robot 0 heard more than the good statist')
        finally:
            rounds.unregister()
            self.delete.publish(Delete_Robot(robot_id=3, sub_id=1))
        self.assertEqual(len(b), self.robots, 'a robot disappeared after a NaN position')
        for rid in range(self.robots):
            self.assertTrue(all(v == v for v in b[rid]), 'NaN reached robot %d' % rid)
        self.assertTrue(any(st.moved(a[r], b[r]) > 0 for r in range(self.robots)))


if __name__ == '__main__':
    rospy.init_node('freeze_test')
    rostest.rosrun('swarm_transport', 'freeze_continue', FreezeContinue, sys.argv)
