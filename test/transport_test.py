#!/usr/bin/env python3
"""The thesis's transport mission end to end in lock-step: gathering, freeze for loading,
transport, unloading, done - asserted on what the swarm actually did."""

import sys
import unittest

import rospy
import rostest
from swarm_transport.msg import New_Mission

import swarm_testing as st

class Transport(unittest.TestCase):

    def test_thesis_mission(self):
        g = lambda k: rospy.get_param('~' + k)  # noqa: E731
        robots, timeout = g('robots'), g('timeout_s')
        frm, to, leaders = g('from'), g('to'), g('leaders')
        obj = (g('object_x'), g('object_y'), g('object_size_x'), g('object_size_y'))
        target = (g('target_x'), g('target_y'))
        status = st.StatusLog()
        pub = rospy.Publisher('/flock/mission/new', New_Mission, queue_size=10)
        swarm = st.launch_swarm(robots=robots, seed=g('seed'), lockstep=True, max_ticks=0)
        log = None
        try:
            # Sent as a raw message, exactly as `rostopic pub` would, before the first tick
            # (the simulator waits for this test's position log): the run is the same every
            # time, whatever the machine's load.
            why = st.submit_before_first_tick(
                pub, st.mission(7, frm, to, leaders, obj, target), timeout)
            self.assertEqual(why, '')
            log = st.PositionLog()
            self.assertTrue(log.wait_tick(3, timeout), 'the swarm never ticked')
            self.assertTrue(st.wait_for(lambda: status.final(7), timeout),
                            'mission 7 did not finish; states so far %s' % status.states(7))
            done_tick = log.latest_tick()
            self.assertTrue(log.wait_tick(done_tick + 5, timeout))
            states = {rid: st.robot_state(rid, timeout) for rid in range(robots)}
        finally:
            swarm.shutdown()
            if log:
                log.close()

        self.assertEqual(status.states(7), ['QUEUED', 'GATHERING', 'LOADING', 'TRANSPORT',
                                            'UNLOADING', 'DONE'])
        assigned = list(range(frm, to))
        gathering = status.first(7, 1).tick
        loading = status.first(7, 2)
        transport = status.first(7, 3)
        unloading = status.first(7, 4)
        done = status.first(7, 5)

        # Every assigned robot was inside the object when the first leader froze them.
        at_freeze = log.at(loading.tick)
        for rid in assigned:
            self.assertTrue(st.inside(at_freeze[rid], obj, g('inside_tolerance_m')),
                            'robot %d not inside the object at the freeze: %s'
                            % (rid, at_freeze[rid]))
        # Frozen robots do not move during loading.
        a = log.at(loading.tick + g('settle_ticks'))
        b = log.at(transport.tick)
        self.assertGreater(transport.tick, loading.tick + g('settle_ticks'))
        for rid in assigned:
            self.assertLessEqual(st.moved(a[rid], b[rid]), g('still_tolerance_m'),
                                 'robot %d moved while frozen for loading' % rid)
        # Unassigned robots keep out of the object while it is a danger zone for them: the
        # object is static until TRANSPORT (after a grace to leave it), then moves onto them.
        worst = 0.0
        for t in range(gathering + g('grace_ticks'), transport.tick):
            pos = log.at(t)
            for rid, p in pos.items():
                if rid not in assigned:
                    worst = max(worst, st.depth_inside(p, obj[:2], obj[2:]))
        self.assertLessEqual(worst, g('danger_tolerance_m'),
                             'an unassigned robot was %.3f m inside the object' % worst)
        # The object centre ends within the tolerance of the target.
        final = (done.object_position_x, done.object_position_y)
        self.assertLessEqual(st.moved(final, target), g('goal_tolerance_m') + 1e-6,
                             'object ended at %s' % (final,))
        self.assertLessEqual(unloading.distance_to_target, g('goal_tolerance_m') + 1e-6)
        # After Delete_Object no robot keeps the zone or the mission.
        for rid, state in states.items():
            self.assertEqual(list(state.mission_ids), [],
                             'robot %d still holds a mission: %s' % (rid, state))
            self.assertEqual(list(state.zone_ids), [], 'robot %d still keeps a zone: %s' % (rid, state))
            self.assertFalse(state.frozen, 'robot %d is still frozen' % rid)
        rospy.loginfo('transport: gathering %d, loading %d, transport %d, unloading %d, done %d',
                      gathering, loading.tick, transport.tick, unloading.tick, done.tick)


if __name__ == '__main__':
    rospy.init_node('transport_test')
    rostest.rosrun('swarm_transport', 'transport_thesis', Transport, sys.argv)
