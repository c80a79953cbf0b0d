"""The soak's missions (scripts/soak, issue 29): transport missions between six places of the
arena, submitted through the dispatcher's service, every state they report, and the recorder's
rows of them."""

import csv
import os
import re
import threading
import time

from swarm_transport import soak_faults as sf

LIVE = (0, 1, 2, 3, 4)  # QUEUED .. UNLOADING
GATHERING = 1
DONE, ABORTED, REJECTED = 5, 6, 7
STATE = ['QUEUED', 'GATHERING', 'LOADING', 'TRANSPORT', 'UNLOADING', 'DONE', 'ABORTED',
         'REJECTED']
# Where objects start and go: six places in the thesis's 11.09 m arena, at least 3 m apart, so
# that a 1 x 1 object and its robots at one do not touch another's; a live mission holds two
# (its start and its target), so three missions can be live at once.
SLOTS = ((2.5, 2.5), (5.5, 2.0), (8.5, 2.5), (8.5, 8.5), (5.5, 9.0), (2.5, 8.5))


class Missions(object):
    """The soak's own missions (ids from 1 up, never reused) and every state they reported."""

    def __init__(self):
        self.lock = threading.Lock()
        self.states = {}     # id -> list of (wall, state, reason)
        self.slots = {}      # id -> (from slot, to slot)
        self.submitted = {}  # id -> wall time of its submission
        self.robots = {}     # id -> its robots, as the dispatcher picked them
        self.first_leader = {}  # id -> its first leader, as the dispatcher named it
        self.progress = {}   # id -> (wall of its last progress, least distance, most inside)
        self.last = {}       # id -> the last Mission_Status heard of it
        self.next_id = 1

    def on_status(self, msg):
        """A Mission_Status (/flock/mission/status or /flock/mission/progress): a new state, or
        the object 5 cm nearer its target, or more robots inside, is progress."""
        with self.lock:
            if msg.mission_id not in self.states:
                return
            seen = self.states[msg.mission_id]
            # Phases only go forward. Statuses and progress reports come over separate
            # connections (a thread each in rospy), so an older phase's report can be taken
            # after a newer one: it is no step back (a slice took a late UNLOADING after the
            # DONE and counted its mission hung, 2026-11-28).
            if seen and (seen[-1][1] not in LIVE or
                         (msg.state in LIVE and msg.state < seen[-1][1])):
                return
            now = time.time()
            self.last[msg.mission_id] = msg
            moved = False
            if not seen or seen[-1][1] != msg.state:
                seen.append((now, msg.state, msg.reason))
                moved = True
            last = self.progress.get(msg.mission_id, (now, float('inf'), -1))
            if msg.distance_to_target < last[1] - 0.05 or msg.robots_inside > last[2]:
                moved = True
            if moved:
                self.progress[msg.mission_id] = (now, min(last[1], msg.distance_to_target),
                                                 max(last[2], msg.robots_inside))

    def final(self, mid):
        seen = self.states[mid]
        return seen[-1][1] if seen else None

    def live(self):
        with self.lock:
            return [m for m in self.states if self.final(m) not in (DONE, ABORTED, REJECTED)]

    def count(self, state):
        with self.lock:
            return sum(1 for m in self.states if self.final(m) == state)

    def free_slots(self):
        used = set()
        for m in self.live():
            used.update(self.slots[m])
        return [i for i in range(len(SLOTS)) if i not in used]

    def leader_target(self, exclude=()):
        """(mission, its first leader, its state) of the newest mission in GATHERING whose
        first leader is known, not one of `exclude`, or None."""
        with self.lock:
            gathering = [m for m in self.states if self.final(m) == GATHERING
                         and m in self.first_leader and m not in exclude]
            if not gathering:
                return None
            m = max(gathering)
            return m, self.first_leader[m], STATE[GATHERING]

    def hung(self, now, hung_s):
        """Live missions without progress (a new state, the object nearer its target, more
        robots inside) for longer than `hung_s`."""
        with self.lock:
            return [m for m in self.states
                    if self.final(m) not in (DONE, ABORTED, REJECTED)
                    and now - self.progress.get(m, (self.submitted[m],))[0] > hung_s]


def submit(missions, a, rng, log):
    """One more transport mission between two free slots, through the dispatcher's service;
    False when the dispatcher is not there (it is being restarted)."""
    import rospy
    from swarm_transport.msg import New_Mission
    from swarm_transport.srv import Submit_Mission
    free = missions.free_slots()
    if len(free) < 2:
        return False
    src, dst = rng.sample(free, 2)
    m = New_Mission()
    m.mission_id = missions.next_id
    m.robot_count = a.mission_robots
    m.leader_number = 1
    m.object_position_x, m.object_position_y = SLOTS[src]
    m.object_size_x = m.object_size_y = 1.0
    m.target_x, m.target_y = SLOTS[dst]
    try:
        rospy.wait_for_service(sf.DISPATCHER + '/submit', 0.5)
        answer = rospy.ServiceProxy(sf.DISPATCHER + '/submit', Submit_Mission)(m)
    except Exception:  # noqa: BLE001 - down, or went down during the call
        return False
    with missions.lock:
        missions.next_id += 1
        missions.states[m.mission_id] = []
        missions.submitted[m.mission_id] = time.time()
        missions.slots[m.mission_id] = (src, dst)
        picked = re.search(r'robots \{([0-9, ]+)\}', answer.message)
        if picked:
            missions.robots[m.mission_id] = [int(r) for r in picked.group(1).split(',')]
        first = re.search(r'first leader (\d+)', answer.message)
        if first:
            missions.first_leader[m.mission_id] = int(first.group(1))
        if answer.code != 0:
            missions.states[m.mission_id].append((time.time(), REJECTED, answer.message))
    log('mission %d: %d robots, slot %d -> %d: %s' % (m.mission_id, a.mission_robots, src, dst,
                                                     answer.message))
    return True


def recorded_rows(run_dir):
    """{mission_id: rows} of the recorder's missions.csv (every file of the run)."""
    rows = {}
    path = os.path.join(run_dir, 'missions.csv')
    if not os.path.exists(path):
        return rows
    with open(path) as f:
        for row in csv.reader(line for line in f if not line.startswith('#')):
            if row and row[0].isdigit():
                rows[int(row[0])] = rows.get(int(row[0]), 0) + 1
    return rows
