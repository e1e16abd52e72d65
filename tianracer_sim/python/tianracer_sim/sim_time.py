"""Waiting on a running tianracer_sim from Python (the rostests, scripts): on what the
simulator guarantees, in sim time.

The simulator guarantees: /clock advances while it runs and stands still while it is paused
(pause_physics publishes the paused time once more, so that every node's clock reaches it);
every message it publishes is stamped with the sim time of the step it describes, on a fixed
sim-time schedule; reset_simulation starts sim time again at 0. It guarantees nothing in wall
time. And ROS delivers a message to a subscriber that reads late only while the queues hold
it: roscpp drops from a publisher's full queue, and rospy keeps only the last `queue_size` of
the messages it reads at once. rospy's own /clock subscription is made with queue_size=1 and
the connection keeps that (a later Subscriber's queue_size does not reach a connection that
exists already): a process that reads /clock late sees only the last of what arrived.

So a test
- records what it reads without losses (Stream: no rospy queue limit, also on /clock);
- waits for a message by its stamp (Stream.first_stamped), never for "the next message";
- waits for connections between publisher and subscriber (wait_connected, node_connected),
  not for registrations at the master, which come first;
- measures in sim time (sim_sleep, stamps); wall time only bounds a wait, so that a wedged
  simulator fails the test instead of hanging it.
"""
import threading
import time
import xmlrpc.client

import rosgraph
import rospy

WALL_TIMEOUT = 60.0  # s of wall time: a bound on a wedged sim, never a measurement


def wait_for(predicate, what, wall_timeout=WALL_TIMEOUT, poll=0.01):
    """Polls `predicate` until it returns a true value, and returns that value.
    AssertionError naming `what` when it is still false after `wall_timeout` s of wall time."""
    end = time.time() + wall_timeout
    while True:
        value = predicate()
        if value:
            return value
        if time.time() > end or rospy.is_shutdown():
            raise AssertionError('timed out after %.0f s of wall time waiting for %s (sim time '
                                 '%.3f)' % (wall_timeout, what, rospy.get_time()))
        time.sleep(poll)


def action_finished(client, what, wall_timeout=WALL_TIMEOUT):
    """Waits until an actionlib SimpleActionClient's goal is done with its result, and returns
    (state, result). The goal's status and its result come on two topics, and ROS does not
    order two connections: the status may say REJECTED or SUCCEEDED before the result is in
    (get_result() is then None). The client's simple state turns DONE only with the result."""
    from actionlib.simple_action_client import SimpleGoalState
    wait_for(lambda: client.simple_state == SimpleGoalState.DONE, what, wall_timeout)
    return client.get_state(), client.get_result()


def sim_sleep(seconds, wall_timeout=None, each=None, poll=0.01):
    """Returns once `seconds` of sim time have passed on this process's clock, calling `each`
    every `poll` s of wall time meanwhile. Across a reset (the clock going back) the count goes
    on from the new timeline's start. Bounded by WALL_TIMEOUT + 10 s of wall time a second of
    sim time (a sim slower than 0.1 x real time is wedged) unless `wall_timeout` is given."""
    if wall_timeout is None:
        wall_timeout = WALL_TIMEOUT + 10.0 * seconds
    state = {'last': rospy.get_time(), 'left': seconds}

    def passed():
        if each:
            each()
        now = rospy.get_time()
        if now >= state['last']:
            state['left'] -= now - state['last']
        state['last'] = now
        return state['left'] <= 1e-9

    wait_for(passed, '%.3f s of sim time to pass' % seconds, wall_timeout, poll)


def drive_twist(pub, seconds, v, w=0.0, period=0.02, wall_timeout=None):
    """Publishes Twist(linear.x v, angular.z w) on `pub` every `period` s of wall time (well
    inside a cmd_vel timeout of 0.5 s of sim time at real_time_factor <= 10) while `seconds`
    of sim time pass, counted from when `pub` is connected: a command sent before that is
    lost. Returns the sim time at the start."""
    from geometry_msgs.msg import Twist
    wait_connected(pub)
    msg = Twist()
    msg.linear.x, msg.angular.z = v, w
    start = rospy.get_time()
    sim_sleep(seconds, wall_timeout, each=lambda: pub.publish(msg), poll=period)
    return start


def header_stamp(msg):
    return msg.header.stamp.to_sec()


def clock_stamp(msg):
    return msg.clock.to_sec()


def lossless(subscriber):
    """Lets rospy keep every message of the subscriber's topic that reaches this process: no
    queue limit on the topic's connections, those it has and those made later. (rospy makes
    one connection per topic and process, with the queue_size its first Subscriber had: for
    /clock, rospy's own sim-time subscriber's, 1.)"""
    impl = subscriber.impl
    impl.set_queue_size(-1)  # None: no limit for connections made from now on
    with impl.c_lock:
        for connection in impl.connections:
            connection.protocol.queue_size = None
    return subscriber


class Stream(object):
    """Every message of a topic that reaches this process, in arrival order, with its stamp
    (sim time, read by `stamp`). Positions count from the first message received and stay
    valid when `keep` trims the oldest."""

    def __init__(self, topic, cls, stamp=header_stamp, keep=None, buff_size=1 << 22,
                 callback=None):
        self.stamp = stamp
        self.keep = keep
        self.callback = callback
        self.lock = threading.Lock()
        self._items = []   # (stamp, msg)
        self._first = 0    # position of _items[0]
        self._checked = False
        self.subscriber = lossless(rospy.Subscriber(topic, cls, self._on_message,
                                                    buff_size=buff_size))
        self.topic = self.subscriber.resolved_name

    def _on_message(self, msg):
        if not self._checked:  # a connection made while lossless() ran
            self._checked = True
            lossless(self.subscriber)
        item = (self.stamp(msg), msg)
        if self.callback:
            self.callback(msg)
        with self.lock:
            self._items.append(item)
            if self.keep and len(self._items) > 2 * self.keep:
                drop = len(self._items) - self.keep
                del self._items[:drop]
                self._first += drop

    def unregister(self):
        self.subscriber.unregister()

    def count(self):
        """Messages received so far (the position the next one will have)."""
        with self.lock:
            return self._first + len(self._items)

    def latest(self):
        """The last message received, or None."""
        with self.lock:
            return self._items[-1][1] if self._items else None

    def latest_stamp(self):
        with self.lock:
            return self._items[-1][0] if self._items else None

    def since(self, position=0):
        """[(stamp, msg)] from `position` on (as far as kept)."""
        with self.lock:
            return self._items[max(0, position - self._first):]

    def messages(self, position=0):
        return [m for _, m in self.since(position)]

    def stamps(self, position=0):
        return [s for s, _ in self.since(position)]

    def between(self, t0, t1, position=0):
        """Messages stamped t0 <= stamp <= t1, from `position` on, in arrival order."""
        return [m for s, m in self.since(position) if t0 <= s <= t1]

    def first(self, predicate, what, position=0, wall_timeout=WALL_TIMEOUT):
        """Waits for the first message from `position` on for which predicate(stamp, msg)
        holds; returns (position, stamp, msg)."""
        cursor = [position]

        def find():
            with self.lock:
                start = max(0, cursor[0] - self._first)
                items = self._items[start:]
                base = self._first + start
            for k, (s, m) in enumerate(items):
                if predicate(s, m):
                    return base + k, s, m
            cursor[0] = base + len(items)
            return None

        return wait_for(find, '%s on %s' % (what, self.topic), wall_timeout)

    def first_stamped(self, t, position=0, wall_timeout=WALL_TIMEOUT):
        """The first message (from `position` on) stamped t or later: the simulator publishes
        one whatever came before it."""
        return self.first(lambda s, m: s >= t - 1e-9, 'a message stamped >= %.3f' % t,
                          position, wall_timeout)[2]

    def wait_count(self, n, wall_timeout=WALL_TIMEOUT):
        """Until `n` messages in all have been received; returns the latest."""
        wait_for(lambda: self.count() >= n, '%d message(s) on %s' % (n, self.topic),
                 wall_timeout)
        return self.latest()


def published_rate(messages):
    """Messages a roscpp publisher sent per second of sim time, from the first and last of
    `messages` (stamped, in order): roscpp numbers its messages in header.seq, so the rate does
    not depend on how many this process received."""
    a, b = messages[0].header, messages[-1].header
    return (b.seq - a.seq) / (b.stamp - a.stamp).to_sec()


# ---- the graph -----------------------------------------------------------------------------

def _master():
    return rosgraph.Master(rospy.get_name())


def _node(node):
    return xmlrpc.client.ServerProxy(_master().lookupNode(node))


def wait_connected(endpoint, wall_timeout=WALL_TIMEOUT):
    """Until a Publisher or Subscriber of this process is connected to every node the master
    lists at the other end of its topic, and there is at least one: from then on a message
    published reaches them all. (Registration at the master comes first, the connection
    later.)"""
    impl, me = endpoint.impl, rospy.get_name()
    publisher = isinstance(endpoint, rospy.Publisher)

    def connected():
        pubs, subs, _ = _master().getSystemState()
        peers = {n for t, nodes in (subs if publisher else pubs) if t == impl.resolved_name
                 for n in nodes if n != me}
        if not peers:
            return False
        if not publisher:  # a subscriber's connections are named by the publisher's URI
            peers = {_master().lookupNode(n) for n in peers}
        with impl.c_lock:
            ends = {c.endpoint_id for c in impl.connections}
        return peers <= ends

    wait_for(connected, '%s %s connected to every %s' % (
        'our publisher of' if publisher else 'our subscription to', impl.resolved_name,
        'subscriber' if publisher else 'publisher'), wall_timeout)
    return endpoint


def bus_info(node):
    """`node`'s connections (its getBusInfo): [id, other end, 'i' or 'o', transport, topic,
    connected, ...]; the other end of an outgoing connection is the subscriber's name, of an
    incoming one the publisher's URI."""
    code, _, info = _node(node).getBusInfo(rospy.get_name())
    return info if code == 1 else []


def node_connected(node):
    """True when `node` is up and every topic it publishes or subscribes to is connected to
    every node at the other end (what a node restarted under the same name needs before it
    can be relied on: its registration at the master comes first)."""
    master = _master()
    try:
        pubs, subs, _ = master.getSystemState()
        have = {(c[2], c[4], c[1]) for c in bus_info(node) if c[5]}
    except (rosgraph.MasterError, OSError, xmlrpc.client.Error):
        return False
    publishers = {t: set(n) for t, n in pubs}
    subscribers = {t: set(n) for t, n in subs}
    for topic, nodes in publishers.items():
        if node in nodes:
            for other in subscribers.get(topic, set()) - {node}:
                if ('o', topic, other) not in have:
                    return False
    for topic, nodes in subscribers.items():
        if node in nodes:
            for other in publishers.get(topic, set()) - {node}:
                try:
                    other_uri = master.lookupNode(other)
                except rosgraph.MasterError:
                    return False
                if ('i', topic, other_uri) not in have:
                    return False
    return True


def _bus_stats(proxy):
    """(publications, subscriptions) of a node's getBusStats: rospy answers [code, message,
    [publications, subscriptions, services]], roscpp [publications, subscriptions]."""
    reply = proxy.getBusStats(rospy.get_name())
    stats = reply[2] if isinstance(reply[0], int) else reply
    return stats[0], stats[1]


def messages_received(node, topic):
    """How many messages `node` has read from `topic` (its getBusStats), summed over its
    connections; 0 when it has none."""
    _, subscriptions = _bus_stats(_node(node))
    # [topic, [[connection id, bytes, messages, ...], ...]] (roscpp and rospy alike)
    return sum(c[2] for t, conns in subscriptions if t == topic for c in conns)


def messages_sent(node, topic, subscriber=None):
    """How many messages `node` has sent on `topic` to `subscriber` (this process by default),
    from its getBusStats: roscpp counts a message when it queues it for the subscriber, rospy
    when it writes it; a message a full publisher queue then drops is counted all the same.
    So the count is what the node published; it is what the subscriber receives only while
    the subscriber keeps up with the queue."""
    proxy = _node(node)
    subscriber = subscriber or rospy.get_name()
    _, _, info = proxy.getBusInfo(rospy.get_name())
    ids = {c[0] for c in info if c[2] == 'o' and c[4] == topic and c[1] == subscriber}
    publications, _ = _bus_stats(proxy)
    total = 0
    for entry in publications:  # roscpp: [topic, conns]; rospy: [topic, data bytes, conns]
        for c in entry[-1] if entry[0] == topic else ():
            if c[0] in ids:
                # roscpp: [id, bytes, data bytes, messages, 0]; rospy: [id, bytes, messages, ok]
                total += c[3] if len(c) == 5 else c[2]
    return total


# ---- gazebo_ros's services -----------------------------------------------------------------

def connect_gazebo(owner, kinds, wall_timeout=WALL_TIMEOUT):
    """Each /gazebo service of `kinds` ({service name: service class}), once every one is
    there, as a ServiceProxy in the attribute of `owner` (a test case's class, say) that bears
    the service's name. rospy.ROSException after `wall_timeout` s without one of them."""
    for name in kinds:
        rospy.wait_for_service('/gazebo/' + name, timeout=wall_timeout)
    for name, kind in kinds.items():
        setattr(owner, name, rospy.ServiceProxy('/gazebo/' + name, kind))
    return owner


# ---- pause ---------------------------------------------------------------------------------

class Paused(object):
    """pause_physics, and this process's clock at the paused sim time (pause_physics publishes
    it once more): `t` is that time. Used as a context manager it unpauses at the end."""

    def __init__(self, wall_timeout=WALL_TIMEOUT):
        from gazebo_msgs.srv import GetWorldProperties
        from std_srvs.srv import Empty
        connect_gazebo(self, {'pause_physics': Empty, 'unpause_physics': Empty,
                              'get_world_properties': GetWorldProperties}, wall_timeout)
        self.pause_physics()
        self.t = self.get_world_properties().sim_time
        wait_for(lambda: abs(rospy.get_time() - self.t) < 1e-6,
                 'our clock at the paused time %.3f' % self.t, wall_timeout)

    def unpause(self):
        self.unpause_physics()

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.unpause()
