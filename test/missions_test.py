#!/usr/bin/env python3
"""Bad missions rejected without any robot changing behaviour: by the dispatcher's service and
as raw messages, and a duplicate live id. (Scenarios as data: two queued missions in
test/scenarios/two_queued_missions.yaml, a leader-only mission with a passive swarm in
test/scenarios/leader_brings_its_swarm.yaml.)"""

import sys
import unittest

import rospy
import rostest
from swarm_transport.msg import New_Mission
from swarm_transport.srv import Hold, Submit_Mission

import swarm_testing as st


class Missions(unittest.TestCase):

    def start(self, **launch):
        self.log, self.status = st.PositionLog(), st.StatusLog()
        self.raw = rospy.Publisher('/flock/mission/new', New_Mission, queue_size=10)
        self.swarm = st.launch_swarm(lockstep=True, max_ticks=0, **launch)
        self.timeout = rospy.get_param('~timeout_s')
        self.assertTrue(self.log.wait_tick(3, self.timeout), 'the swarm never ticked')
        self.submit = rospy.ServiceProxy('/mission_dispatcher/submit', Submit_Mission)
        self.submit.wait_for_service(self.timeout)

    def tearDown(self):
        self.swarm.shutdown()
        self.log.close()

    def states(self, robots):
        return {rid: st.robot_state(rid, self.timeout) for rid in range(robots)}

    def test_bad_missions_are_rejected_and_change_nothing(self):
        robots = rospy.get_param('~bad/robots')
        self.start(robots=robots, seed=rospy.get_param('~bad/seed'))
        nan = float('nan')
        bad = {
            41: st.mission(41, 0, 5, 1, (nan, 7.0, 2.0, 2.0), (3.0, 3.0)),
            42: st.mission(42, 5, 5, 1, (7.0, 7.0, 2.0, 2.0), (3.0, 3.0)),
            43: st.mission(43, 0, 5, 6, (7.0, 7.0, 2.0, 2.0), (3.0, 3.0)),
            44: st.mission(44, 0, 5, 0, (7.0, 7.0, 2.0, 2.0), (3.0, 3.0)),
            45: st.mission(45, 0, 5, 1, (7.0, 7.0, -1.0, 2.0), (3.0, 3.0)),
            46: st.mission(46, 0, 5, 1, (7.0, 7.0, 2.0, 2.0), (30.0, 3.0)),
            47: st.mission(47, 0, 5, 1, (7.0, 7.0, 2.0, 2.0), (3.0, 3.0)),
        }
        bad[47].robot_ids = [1, 2, 900]  # robot 900 does not exist
        for mid, m in sorted(bad.items()):
            answer = self.submit(m)
            self.assertNotEqual(answer.code, 0, 'mission %d was accepted' % mid)
            self.assertTrue(answer.message, 'mission %d rejected without a reason' % mid)
        # The same bad orders as raw messages: REJECTED statuses with reasons.
        self.assertTrue(st.wait_connected(self.raw, self.timeout))
        for mid, m in sorted(bad.items()):
            self.raw.publish(m)
            # Delivered: the dispatcher answers it before the next one goes.
            self.assertTrue(st.wait_for(lambda: self.status.first(mid, 7) is not None, 30),
                            'no REJECTED status for mission %d' % mid)
            self.assertTrue(self.status.first(mid, 7).reason)
        # A duplicate live id: the first is accepted, the second rejected.
        ok = st.mission(48, 0, 5, 1, (7.0, 7.0, 2.0, 2.0), (3.0, 3.0))
        self.assertEqual(self.submit(ok).code, 0)
        dup = st.mission(48, 5, 10, 1, (3.0, 8.0, 2.0, 2.0), (8.0, 3.0))
        self.assertNotEqual(self.submit(dup).code, 0, 'duplicate live mission id accepted')
        # The good order, sent after the bad ones, reached the robots (its first leader's
        # QUEUED): what follows is not "nothing arrived yet".
        self.assertTrue(st.wait_for(lambda: self.status.first(48, 0) is not None, self.timeout),
                        'mission 48 never reached its robots: %s' % self.status.states(48))
        t = self.log.latest_tick()
        self.assertTrue(self.log.wait_tick(t + 20, self.timeout), 'the swarm stopped ticking')
        for rid, state in self.states(robots).items():
            held = set(state.mission_ids)
            # None of the bad orders reached any robot. (The accepted 48 may already be done:
            # lock-step runs hundreds of ticks while the robots are asked one by one.)
            self.assertTrue(held <= {48}, 'robot %d holds missions %s: %s' % (rid, held, state))
            if rid >= 5:
                self.assertFalse(state.has_active,
                                 'robot %d works on mission %d' % (rid, state.active_mission))

    def test_a_count_only_mission_gets_its_robots_picked_and_completes(self):
        """New_Mission.robot_count (ext, SPEC 9.10): no range, no ids; the dispatcher picks the
        robots by the selection matrix and sends the order with their ids, and the leaders among
        them (issue 12): those whose slots lie furthest toward the target, in leader_ids."""
        g = lambda k: rospy.get_param('~count/' + k)  # noqa: E731
        robots, count, leaders = g('robots'), g('count'), g('leaders')
        # The run stands at tick `at` while the robots are picked: the dispatcher picks from the
        # poses of tick at - 1, which the seed decides, so that the pick is always the same. It
        # holds from the start (swarm.launch hold_at): asked for once it runs, a fast run could
        # be past that tick already.
        at = g('pick_at_tick')
        self.start(robots=robots, seed=g('seed'), hold_at=at)
        hold = rospy.ServiceProxy('/simulator/hold', Hold)
        hold.wait_for_service(self.timeout)
        self.assertTrue(st.wait_for(lambda: hold(at).holding, self.timeout), 'it never held')
        self.assertTrue(st.wait_for(lambda: self.log.latest_tick() == at - 1, self.timeout),
                        'held, the newest poses are of tick %d' % self.log.latest_tick())
        # The dispatcher has the poses of tick at - 1 too (the newest: the run holds).
        self.assertTrue(st.wait_for(lambda: st.dispatcher_positions_tick() == at - 1,
                                    self.timeout),
                        'the dispatcher has the poses of tick %s' % st.dispatcher_positions_tick())
        orders = []
        sub = rospy.Subscriber('/flock/mission/new', New_Mission,
                               lambda o: orders.append(o) if o.mission_id == 51 else None)
        named = st.mission(54, 0, 0, 1, (7.0, 7.0, 2.0, 2.0), (3.0, 3.0))
        named.robot_count, named.leader_ids = 2, [0]
        answer = self.submit(named)
        self.assertNotEqual(answer.code, 0, 'leader_ids besides robot_count was accepted')
        self.assertIn('leader_ids', answer.message)
        too_many = st.mission(52, 0, 0, 1, (7.0, 7.0, 2.0, 2.0), (3.0, 3.0))
        too_many.robot_count = robots + 1
        answer = self.submit(too_many)
        self.assertNotEqual(answer.code, 0, 'a count above the swarm was accepted')
        self.assertIn('idle', answer.message)
        both = st.mission(53, 0, 2, 1, (7.0, 7.0, 2.0, 2.0), (3.0, 3.0))
        both.robot_count = 2
        self.assertNotEqual(self.submit(both).code, 0, 'a count besides a range was accepted')
        m = st.mission(51, 0, 0, leaders, (7.0, 7.0, 2.0, 2.0), tuple(g('target')))
        m.robot_count = count
        answer = self.submit(m)
        self.assertEqual(answer.code, 0, answer.message)
        self.assertTrue(st.wait_for(lambda: orders, self.timeout), 'no order of mission 51')
        order = orders[-1]
        sub.unregister()
        self.assertEqual(len(order.robot_ids), count)
        self.assertEqual(order.robot_count, 0)
        # The leaders: leader_number of the picked robots, the plan's front ones - not the
        # lowest ids, as in an order that names none.
        picked = sorted(order.robot_ids)
        self.assertEqual(len(order.leader_ids), leaders)
        self.assertTrue(set(order.leader_ids) <= set(picked), (order.leader_ids, picked))
        self.assertEqual(sorted(order.leader_ids), g('front_leaders'),
                         'picked %s, leaders %s' % (picked, list(order.leader_ids)))
        self.assertNotEqual(sorted(order.leader_ids), picked[:leaders])
        # The robots lead as the order says: the hold moves on 5 ticks at a time until the
        # mission gathers (its first leader, one of the leaders, says so in its ~state: no
        # status in flight to wait for), then they are asked.
        def gathering():
            for rid in order.leader_ids:
                state = st.robot_state(rid, self.timeout)
                phases = dict(zip(state.mission_ids, bytearray(state.mission_phases)))
                if phases.get(51, 0) >= 1:
                    return True
            return False

        for _ in range(40):
            if gathering():
                break
            at += 5
            self.assertEqual(hold(at).code, Hold._response_class.OK)
            self.assertTrue(st.wait_for(lambda: hold(at).holding, self.timeout), 'never held')
        self.assertTrue(st.wait_for(lambda: self.status.first(51, 1) is not None, self.timeout),
                        self.status.states(51))
        self.assertFalse(self.status.final(51), self.status.states(51))
        states = self.states(robots)
        self.assertEqual(hold(0).code, Hold._response_class.OK)
        leading = sorted(rid for rid, state in states.items()
                         if state.leader and state.has_active and state.active_mission == 51)
        self.assertEqual(leading, sorted(order.leader_ids), states)
        self.assertTrue(st.wait_for(lambda: self.status.final(51), self.timeout),
                        'count-only mission did not finish: %s' % self.status.states(51))
        done = self.status.first(51, 5)
        self.assertIsNotNone(done, 'mission ended %s' % self.status.states(51))
        self.assertEqual(done.robots_assigned, count)

    def test_a_recruiting_mission_takes_the_first_robots_into_its_object_and_completes(self):
        """New_Mission.recruit (ext, SPEC 9.4): no robots named; a statist at the object pulls the
        swarm, the first robot_count idle robots inside the object take the mission."""
        g = lambda k: rospy.get_param('~recruit/' + k)  # noqa: E731
        robots, count = g('robots'), g('count')
        self.start(robots=robots, seed=g('seed'), extra_config=g('extra_config'))
        obj = (5.5, 5.5, 2.0, 2.0)
        too_many = st.mission(62, 0, 0, 1, obj, (3.0, 3.0))
        too_many.robot_count, too_many.recruit = robots + 1, True
        answer = self.submit(too_many)
        self.assertNotEqual(answer.code, 0, 'a recruit above the swarm was accepted')
        self.assertIn('idle', answer.message)
        outside = st.mission(63, 0, 0, 1, (20.0, 5.5, 2.0, 2.0), (3.0, 3.0))
        outside.robot_count, outside.recruit = count, True
        answer = self.submit(outside)
        self.assertNotEqual(answer.code, 0, 'a recruit outside the arena was accepted')
        self.assertIn('outside the arena', answer.message)
        orders = []
        sub = rospy.Subscriber('/flock/mission/new', New_Mission,
                               lambda o: orders.append(o) if o.mission_id == 61 else None)
        m = st.mission(61, 0, 0, g('leaders'), obj, (3.0, 3.0))
        m.robot_count, m.recruit = count, True
        answer = self.submit(m)
        self.assertEqual(answer.code, 0, answer.message)
        self.assertIn('recruiting', answer.message)
        self.assertTrue(st.wait_for(lambda: self.status.final(61), self.timeout),
                        'recruiting mission did not finish: %s' % self.status.states(61))
        done = self.status.first(61, 5)
        self.assertIsNotNone(done, 'mission ended %s' % self.status.states(61))
        self.assertEqual(done.robots_assigned, count)
        # The dispatcher named the robots only once enough were inside: the order it sent.
        sub.unregister()
        self.assertTrue(orders, 'no order of mission 61 was heard')
        self.assertEqual(len(orders[-1].robot_ids), count)
        self.assertFalse(orders[-1].recruit)


if __name__ == '__main__':
    rospy.init_node('missions_test')
    rostest.rosrun('swarm_transport', 'missions', Missions, sys.argv)
