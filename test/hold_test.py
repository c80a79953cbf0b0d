#!/usr/bin/env python3
"""The simulator's ~hold (issue 13): a lock-step run (paced at real time) holds before the
stated tick - the last /flock/world_poses is the tick before it, for as long as it holds, and the
markers' status line names the held tick - then goes on when released. A tick that is past is
refused with an ERROR and changes nothing."""

import sys
import threading
import time
import unittest

import rospy
import rostest
from swarm_transport.srv import Hold
from visualization_msgs.msg import MarkerArray

import swarm_testing as st


class HoldTest(unittest.TestCase):

    def test_a_run_holds_before_the_stated_tick_and_goes_on(self):
        g = lambda k: rospy.get_param('~' + k)  # noqa: E731
        timeout, at = g('timeout_s'), g('hold_tick')
        lock = threading.Lock()
        labels = []

        def on_markers(msg):
            with lock:
                labels.extend(m.text for m in msg.markers if m.ns == 'status')

        markers = rospy.Subscriber('/flock/markers', MarkerArray, on_markers, queue_size=10)
        positions = st.PositionLog()
        swarm = st.launch_swarm(robots=g('robots'), seed=1, lockstep=True, max_ticks=0,
                                real_time_factor=g('real_time_factor'))
        try:
            hold = rospy.ServiceProxy('/simulator/hold', Hold)
            hold.wait_for_service(timeout)
            answer = hold(at)
            self.assertEqual(answer.code, Hold._response_class.OK, answer.message)
            self.assertLess(answer.current_tick, at, 'the run was past the tick already')
            self.assertTrue(st.wait_for(lambda: hold(at).holding, timeout), 'it never held')
            self.assertEqual(positions.latest_tick(), at - 1)
            time.sleep(g('stand_s'))  # it must stand: nothing may go on meanwhile
            self.assertEqual(positions.latest_tick(), at - 1, 'the run went on while held')
            self.assertTrue(st.wait_for(
                lambda: any(t.startswith('tick %d ' % at) for t in list(labels)), timeout),
                'the markers never showed tick %d: %s' % (at, labels[-1:]))
            past = hold(at - 10)
            self.assertEqual(past.code, Hold._response_class.ERROR)
            self.assertIn('begun already', past.message)
            self.assertTrue(hold(at).holding, 'a refused request released the hold')

            released = time.time()
            self.assertEqual(hold(0).code, Hold._response_class.OK)
            self.assertTrue(positions.wait_tick(at + 20, timeout), 'it did not go on')
            # Paced from where it stood: the time held is not made up for by rushing.
            paced = 20 * 0.1 / g('real_time_factor')
            self.assertGreater(time.time() - released, 0.75 * paced,
                               '20 ticks after the hold took %.2f s' % (time.time() - released))
            ticks = positions.ticks()
            self.assertEqual(ticks, list(range(ticks[0], ticks[-1] + 1)), 'a tick is missing')
        finally:
            markers.unregister()
            positions.close()
            swarm.shutdown()


if __name__ == '__main__':
    rospy.init_node('hold_test')
    rostest.rosrun('swarm_transport', 'hold', HoldTest, sys.argv)
