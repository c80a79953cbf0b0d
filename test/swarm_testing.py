"""Shared helpers of the scenario rostests: launch a swarm inside the test's master, follow
the aggregated /flock/world_poses stream, wait on conditions with timeouts (never fixed sleeps)."""

import math
import threading
import time

import rospkg
import rospy
import roslaunch
from swarm_transport.msg import Mission_Status, New_Mission, Robot_Positions
from swarm_transport import st_ros
from swarm_transport.st_ros import process_alive  # noqa: F401 (the tests' helper)


def launch_swarm(**args):
    """Starts launch/swarm.launch with the given args in the running master; returns the
    parent (call .shutdown())."""
    path = rospkg.RosPack().get_path('swarm_transport') + '/launch/swarm.launch'
    args.setdefault('observers', 1)  # the test's PositionLog must see the first tick
    cli = ['%s:=%s' % (k, str(v).lower() if isinstance(v, bool) else v) for k, v in args.items()]
    uuid = roslaunch.rlutil.get_or_generate_uuid(None, False)
    parent = roslaunch.parent.ROSLaunchParent(uuid, [(path, cli)], is_core=False)
    parent.start()
    return parent


def launch_file(name, **args):
    """Starts launch/<name> of this package with the given args in the running master (e.g. one
    more robot: launch_file('robot.launch', id=8, clock='lockstep')); returns the parent."""
    path = rospkg.RosPack().get_path('swarm_transport') + '/launch/' + name
    cli = ['%s:=%s' % (k, str(v).lower() if isinstance(v, bool) else v) for k, v in args.items()]
    uuid = roslaunch.rlutil.get_or_generate_uuid(None, False)
    parent = roslaunch.parent.ROSLaunchParent(uuid, [(path, cli)], is_core=False)
    parent.start()
    return parent


def service_names():
    """Every service the master knows now."""
    import rosgraph
    _, _, services = rosgraph.Master(rospy.get_name()).getSystemState()
    return {name for name, _ in services}


def subscribes(node, topic):
    """True when the master lists `node` (e.g. '/robot_4/robot') as a subscriber of `topic`."""
    import rosgraph
    _, subs, _ = rosgraph.Master(rospy.get_name()).getSystemState()
    return any(name == topic and node in nodes for name, nodes in subs)


def stop_process_groups(procs, timeout=st_ros.STOP_TIMEOUT_S):
    """Stops processes started with start_new_session=True (subprocess.Popen), last first, by
    their process group: SIGINT, then SIGKILL after `timeout` s (default: longer than
    roslaunch's own escalation); then whatever they had started that still runs (a roslaunch's
    nodes, each in a session of its own): st_ros.stop_process_trees."""
    return st_ros.stop_process_trees(procs, timeout=timeout)


class PositionLog(object):
    """Every /flock/world_poses message by tick (the simulator's ground truth)."""

    def __init__(self):
        self.lock = threading.Lock()
        self.by_tick = {}
        self.last = None
        self.sub = rospy.Subscriber('/flock/world_poses', Robot_Positions, self._cb,
                                    queue_size=10000, tcp_nodelay=True)

    def _cb(self, msg):
        with self.lock:
            self.by_tick[msg.tick] = {r.robot_id: (r.pos_x, r.pos_y, r.angle)
                                      for r in msg.robots if r.type == 0}
            self.last = msg

    def latest_tick(self):
        with self.lock:
            return -1 if self.last is None else self.last.tick

    def wait_tick(self, tick, timeout):
        deadline = time.time() + timeout
        while time.time() < deadline and not rospy.is_shutdown():
            if self.latest_tick() >= tick:
                return True
            time.sleep(0.01)
        return False

    def at(self, tick):
        with self.lock:
            return dict(self.by_tick.get(tick, {}))

    def ticks(self):
        with self.lock:
            return sorted(self.by_tick)

    def close(self):
        self.sub.unregister()


def realtime_swarm_for(case, robots, seed, timeout):
    """A real-time swarm for one test case (`case`, a unittest.TestCase: stopped at its cleanup)
    that ticks, with a publisher of orders connected to every node that takes them; returns
    (that publisher, the swarm's PositionLog)."""
    pub = rospy.Publisher('/flock/mission/new', New_Mission, queue_size=10)
    swarm = launch_swarm(robots=robots, seed=seed, lockstep=False, max_ticks=0)
    case.addCleanup(swarm.shutdown)
    log = PositionLog()
    case.addCleanup(log.close)
    case.assertTrue(log.wait_tick(3, timeout), 'the swarm never ticked')
    # Every robot, the simulator and the dispatcher.
    case.assertTrue(wait_connected(pub, timeout, at_least=robots + 2))
    case.assertTrue(wait_on_radio(range(robots), timeout), 'not every robot hears its rounds')
    return pub, log


def wait_on_radio(robot_ids, timeout):
    """Waits until the simulator sends each robot its rounds (its own bus information): a
    real-time robot joins the radio only once it heard the dispatcher, up to 10 s after it is
    connected to the orders, and a robot not on the radio when a mission starts is quiet for its
    peers, which count it lost (robot_loss: a takeover named robots 0, 2, 3 lost, not 0)."""
    wanted = {k: '/robot_%d/neighbors' % k for k in robot_ids}

    def on_radio():
        try:
            sent = outbound_connections('/simulator')  # one bus query for all the robots
        except Exception:  # noqa: BLE001 - the simulator not up yet: ask again
            return False
        return all((topic, '/robot_%d/robot' % k) in sent for k, topic in wanted.items())

    return wait_for(on_radio, timeout, period=0.2)


def wait_for(predicate, timeout, period=0.02):
    deadline = time.time() + timeout
    while time.time() < deadline and not rospy.is_shutdown():
        if predicate():
            return True
        time.sleep(period)
    return predicate()


def wait_connected(pub, timeout, at_least=1):
    """Waits until `pub` reaches every subscriber the master knows for its topic, and at least
    `at_least` of them (in lock-step: the simulator, which relays mission messages, the
    dispatcher and the observers)."""
    import rosgraph
    master = rosgraph.Master(rospy.get_name())

    def subscribers():
        _, subs, _ = master.getSystemState()
        return next((len(nodes) for topic, nodes in subs if topic == pub.resolved_name), 0)

    def connected():
        n = subscribers()
        return n >= at_least and pub.get_num_connections() >= n

    return wait_for(connected, timeout)


def wait_hears(sub, nodes, timeout):
    """Waits until subscriber `sub` is connected to the publisher of each node in `nodes` (e.g.
    '/robot_3/robot'): from then on everything those nodes publish on its topic reaches it."""
    import rosgraph
    master = rosgraph.Master(rospy.get_name())

    def connected():
        try:
            uris = [master.lookupNode(name) for name in nodes]
        except (rosgraph.MasterError, OSError):
            return False
        return all(sub.impl.has_connection(uri) for uri in uris)

    return wait_for(connected, timeout)


def outbound_connections(node):
    """(topic, destination node) of every connection `node` (a roscpp or rospy node) sends on
    now, from its own bus information (getBusInfo): what it knows, not what the master says."""
    import xmlrpc.client
    import rosgraph
    import rosnode
    caller = rospy.get_name()
    api = rosnode.get_api_uri(rosgraph.Master(caller), node, skip_cache=True)
    code, _, info = xmlrpc.client.ServerProxy(api).getBusInfo(caller)
    assert code == 1, 'no bus information of %s' % node
    # [connection id, destination, direction ('o': outbound), transport, topic, connected, ...]
    return {(c[4], c[1]) for c in info if c[2] == 'o' and c[5]}


def subscribers_of(node, topic):
    """The nodes `node` sends `topic` to now (outbound_connections)."""
    return {dest for t, dest in outbound_connections(node) if t == topic}


def dispatcher_tracks(mission_id, state=None):
    """True when the dispatcher's ~status table lists the mission (in `state`, e.g. 'DONE',
    when given)."""
    from std_srvs.srv import Trigger
    try:
        table = rospy.ServiceProxy('/mission_dispatcher/status', Trigger)().message
    except (rospy.ServiceException, rospy.ROSException):
        return False
    want = [str(mission_id)] + ([state] if state else [])
    return any(line.split()[:len(want)] == want for line in table.splitlines()[1:])


def dispatcher_positions_tick():
    """The tick of the newest /flock/world_poses the dispatcher has (the last line of its ~status:
    'positions of tick N'), or None."""
    from std_srvs.srv import Trigger
    try:
        table = rospy.ServiceProxy('/mission_dispatcher/status', Trigger)().message
    except (rospy.ServiceException, rospy.ROSException):
        return None
    for line in table.splitlines():
        if line.startswith('positions of tick '):
            return int(line.split()[-1])
    return None


def submit_before_first_tick(pub, msg, timeout):
    """Publishes a raw New_Mission (as `rostopic pub` would) while a lock-step swarm waits for
    its observers, and waits until the dispatcher took it in (its first status, QUEUED, comes
    from the first leader at tick 0): create the PositionLog only then, and the simulator
    relays the mission at tick 0, so a seed gives the same run on any machine. Returns a
    reason on failure, else ''."""
    if not wait_connected(pub, timeout, at_least=2):
        return 'the simulator and the dispatcher never subscribed to %s' % pub.resolved_name
    pub.publish(msg)
    try:
        rospy.wait_for_service('/mission_dispatcher/status', timeout)
    except rospy.ROSException:
        return 'the dispatcher\'s ~status service never came up'
    if not wait_for(lambda: dispatcher_tracks(msg.mission_id), timeout, period=0.05):
        return 'the dispatcher never took in mission %d' % msg.mission_id
    return ''


def robot_state(rid, timeout):
    """Robot `rid`'s typed state (its ~state service, swarm_transport/Robot_State)."""
    from swarm_transport.srv import Robot_State
    srv = rospy.ServiceProxy('/robot_%d/robot/state' % rid, Robot_State)
    srv.wait_for_service(timeout)
    return srv()


def play_simulator_for(rid, listed, timeout):
    """The test plays the simulator for a robot node alone: a publisher of its rounds
    (robot_<rid>/neighbors) and a latched /flock/robots naming robots [0, listed), returned once
    the robot subscribed to its rounds and says it is listed."""
    from swarm_transport.msg import Neighbors, Robot_Position
    rounds = rospy.Publisher('/robot_%d/neighbors' % rid, Neighbors, queue_size=10)
    robots = rospy.Publisher('/flock/robots', Robot_Positions, queue_size=1, latch=True)
    msg = Robot_Positions()
    msg.robots = [Robot_Position(robot_id=i, pos_x=1.0 + i, pos_y=1.0) for i in range(listed)]
    robots.publish(msg)
    assert wait_connected(rounds, timeout), 'robot %d never subscribed to its rounds' % rid
    assert wait_for(lambda: robot_state(rid, timeout).listed, timeout), \
        'robot %d never said it is listed' % rid
    return rounds, robots


def describe_robots(robot_ids, timeout=2.0):
    """Where each robot stands and what it says of itself, one line each: for the message of a
    failed assertion (swarm_transport.robot_views, which the soak uses too)."""
    from swarm_transport.robot_views import describe_robots as describe
    return describe(robot_ids, timeout)


def node_pid(name, timeout=30.0):
    """The process id of node `name`, from its own XML-RPC API (to stop or kill it by pid).
    Waits up to `timeout` s for the node to register with the master (a swarm that ticks may
    still be starting a node that does not tick: the dispatcher)."""
    import xmlrpc.client
    import rosgraph
    import rosnode
    caller = rospy.get_name()
    master = rosgraph.Master(caller)
    deadline = time.time() + timeout
    while True:
        # Not from rosnode's cache: a node of the same name in an earlier swarm had another API.
        api = rosnode.get_api_uri(master, name, skip_cache=True)
        if api or time.time() > deadline or rospy.is_shutdown():
            break
        time.sleep(0.1)
    assert api, 'node %s not registered with the master after %.0f s' % (name, timeout)
    code, _, pid = xmlrpc.client.ServerProxy(api).getPid(caller)
    assert code == 1, 'no pid for %s' % name
    return pid


def moved(a, b):
    return math.hypot(a[0] - b[0], a[1] - b[1])


NAMES = {0: 'QUEUED', 1: 'GATHERING', 2: 'LOADING', 3: 'TRANSPORT', 4: 'UNLOADING', 5: 'DONE',
         6: 'ABORTED', 7: 'REJECTED'}


class StatusLog(object):
    """The Mission_Status messages of /flock/mission/status (or of `topic`, e.g.
    /flock/mission/progress) as they arrive."""

    def __init__(self, topic='/flock/mission/status'):
        self.lock = threading.Lock()
        self.items = []
        self.sub = rospy.Subscriber(topic, Mission_Status, self._cb, queue_size=1000)

    def _cb(self, msg):
        with self.lock:
            self.items.append(msg)

    def wait_connected(self, timeout):
        """Waits until it is connected to every node that publishes its topic now: a status
        published later reaches it. (A fast lock-step run publishes a mission's statuses within
        milliseconds of its order: a subscriber made just before may not be connected yet.)"""
        import rosgraph
        master = rosgraph.Master(rospy.get_name())

        def connected():
            try:
                pubs, _, _ = master.getSystemState()
                nodes = next((n for topic, n in pubs if topic == self.sub.resolved_name), [])
                uris = [master.lookupNode(name) for name in nodes]
            except (rosgraph.MasterError, OSError):
                return False
            return bool(uris) and all(self.sub.impl.has_connection(uri) for uri in uris)

        return wait_for(connected, timeout)

    def of(self, mission_id):
        with self.lock:
            return [m for m in self.items if m.mission_id == mission_id]

    def states(self, mission_id):
        """The states as they arrived (each phase is reported once, on entry; progress within
        a phase goes to /flock/mission/progress)."""
        return [NAMES.get(m.state, str(m.state)) for m in self.of(mission_id)]

    def first(self, mission_id, state):
        for m in self.of(mission_id):
            if m.state == state:
                return m
        return None

    def final(self, mission_id):
        return any(m.state in (5, 6, 7) for m in self.of(mission_id))


def mission(mid, frm, to, leaders, obj, target):
    m = New_Mission()
    m.robot_index_from, m.robot_index_to = frm, to
    m.leader_number = leaders
    m.mission_id = mid
    m.object_position_x, m.object_position_y, m.object_size_x, m.object_size_y = obj
    m.target_x, m.target_y = target
    return m


def inside(p, obj, tol):
    return abs(p[0] - obj[0]) <= obj[2] / 2 + tol and abs(p[1] - obj[1]) <= obj[3] / 2 + tol


def depth_inside(p, centre, size):
    """How deep p is inside the rectangle (<= 0 when outside)."""
    return min(size[0] / 2 - abs(p[0] - centre[0]), size[1] / 2 - abs(p[1] - centre[1]))
