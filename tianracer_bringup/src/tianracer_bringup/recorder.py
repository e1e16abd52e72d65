"""The recorder of one batch run: subscribes to the car's topics, ends the run at its sim duration
(or earlier when `success.stop` and the goals are met) and writes metrics.json.

    python3 -m tianracer_bringup.recorder RUN_JSON METRICS_JSON READY_FILE GO_FILE

RUN_JSON is the run's config (scenario.Run.config). The recorder creates READY_FILE once its
subscriptions are connected; when the runner has seen the driver come up too it creates GO_FILE,
and the recorder unpauses the simulator (a service call from this node is much quicker than
starting `rosservice`).
"""
import json
import math
import os
import sys
import threading
import time

from tianracer_bringup.metrics import Metrics, get_field
from tianracer_sim.rotation import yaw_from_quaternion


def main(argv):
    run_json, out_json, ready_file, go_file = argv[1:5]
    with open(run_json) as f:
        cfg = json.load(f)
    import rosgraph
    # rospy reads /use_sim_time once, in init_node: wait until the launch has set it.
    deadline = time.time() + 120
    while True:
        try:
            if rosgraph.Master('/batch_recorder').getParam('/use_sim_time'):
                break
        except Exception:  # master not up yet, or the parameter not set yet
            pass
        if time.time() > deadline:
            print('ERROR [recorder] /use_sim_time never set', flush=True)
            return 2
        time.sleep(0.05)

    import roslib.message
    import rospy
    from nav_msgs.msg import Odometry
    try:
        from tianracer_sim.msg import Contact
    except ImportError:
        Contact = None
    rospy.init_node('batch_recorder', disable_signals=True)
    spawn = cfg['spawn']
    m = Metrics((spawn['x'], spawn['y'], spawn['yaw']), cfg.get('success') or {},
                contacts_measured=Contact is not None, duration=float(cfg['duration']))
    lock = threading.Lock()

    def on_truth(msg):
        p = msg.pose.pose.position
        v = msg.twist.twist.linear
        with lock:
            m.on_truth(msg.header.stamp.to_sec(), p.x, p.y, yaw_from_quaternion(msg.pose.pose.orientation),
                       math.sqrt(v.x * v.x + v.y * v.y + v.z * v.z))

    def on_odom(msg):
        p = msg.pose.pose.position
        with lock:
            m.on_odom(msg.header.stamp.to_sec(), p.x, p.y)

    subs = [rospy.Subscriber('/tianracer/ground_truth/odom', Odometry, on_truth, queue_size=200,
                             tcp_nodelay=True),
            rospy.Subscriber('/tianracer/odom', Odometry, on_odom, queue_size=200, tcp_nodelay=True)]
    if cfg['sensors']['lidar']:
        from sensor_msgs.msg import LaserScan

        def on_scan(msg):
            with lock:
                m.on_scan(msg.ranges, msg.range_min, msg.range_max)
        subs.append(rospy.Subscriber('/scan', LaserScan, on_scan, queue_size=50))
    if Contact is not None:
        def on_contact(msg):
            other = msg.other_model + ('::' + msg.other_link if msg.other_link else '')
            with lock:
                m.on_contact(msg.stamp.to_sec(), other, msg.link)
        subs.append(rospy.Subscriber('/tianracer/contacts', Contact, on_contact, queue_size=1000))

    classes = {}
    for spec in cfg['metrics']:
        m.add_user_metric(spec['name'], spec.get('stat') or 'mean')

        def on_user(raw, spec=spec):
            # AnyMsg: the type comes with the connection, so the topic need not exist yet. On a
            # topic the recorder reads itself (ground truth, odometry) rospy shares that typed
            # subscription: the message comes deserialized.
            if isinstance(raw, rospy.AnyMsg):
                cls = classes.get(spec['topic'])
                if cls is None:
                    cls = roslib.message.get_message_class(spec.get('type') or raw._connection_header['type'])
                    classes[spec['topic']] = cls
                msg = cls().deserialize(raw._buff)
            else:
                msg = raw
            try:
                value = float(get_field(msg, spec['field']))
            except (AttributeError, IndexError, TypeError, ValueError) as e:
                rospy.logerr_once('metric %s: field %r of %s: %s', spec['name'], spec['field'],
                                  spec['topic'], e)
                return
            with lock:
                m.on_user(spec['name'], value)
        rospy.Subscriber(spec['topic'], rospy.AnyMsg, on_user, queue_size=200)

    # Ready once the simulator's publishers are connected to us (it is paused until then).
    while not all(s.get_num_connections() > 0 for s in subs[:2]):
        time.sleep(0.02)
    with open(ready_file, 'w') as f:
        f.write('ready\n')
    print('[recorder] connected; waiting for the driver', flush=True)
    from std_srvs.srv import Empty
    unpause = rospy.ServiceProxy('/gazebo/unpause_physics', Empty)
    while not os.path.exists(go_file):
        time.sleep(0.01)
    unpause()
    print('[recorder] unpaused; recording %.1f s of sim time' % cfg['duration'], flush=True)

    stop_early = bool((cfg.get('success') or {}).get('stop'))
    wall0 = time.time()
    started = False
    while True:
        with lock:
            t0, ended, early = m.t0, m.ended, stop_early and m.done_early()
        if t0 is not None and not started:
            started, wall0 = True, time.time()
        if ended or early:
            break
        time.sleep(0.005)
    wall = time.time() - wall0
    with lock:
        out = m.finish()
        out['path'] = m.path
        out['collision_list'] = [[round(t, 4), o, l] for t, o, l in m.collisions[:50]]
        out['stopped_early'] = bool(early)
    out['recorder_wall_time'] = wall
    tmp = out_json + '.tmp'
    with open(tmp, 'w') as f:
        json.dump(out, f)
    os.replace(tmp, out_json)
    print('[recorder] done: %.2f s sim in %.2f s wall' % (out['sim_time'], wall), flush=True)
    return 0


if __name__ == '__main__':
    sys.exit(main(sys.argv))
