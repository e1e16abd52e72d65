"""Per-run metrics from what the car's topics say, ROS-free so that it is tested without a master.

The recorder node (recorder.py) feeds messages in sim time; `finish()` gives one flat dict.
"""
import math

# A lap is counted when the car crosses the start line (through the spawn point, across the spawn
# heading, within LAP_HALF_WIDTH of the spawn point) forwards, after having been LAP_ARM_DISTANCE
# away from the start since the last crossing.
LAP_HALF_WIDTH = 1.0
LAP_ARM_DISTANCE = 2.0
# Contacts with one model less than this apart (sim s) are one collision.
COLLISION_GAP = 0.1
PATH_PERIOD = 0.02  # sim s between recorded path points (every ground-truth message at 50 Hz)


class Metrics:
    def __init__(self, spawn=(0.0, 0.0, 0.0), success=None, contacts_measured=False,
                 duration=None):
        """duration: sim seconds from the first ground-truth message; later messages are not
        counted (the simulator runs on while the run is being stopped)."""
        self.spawn = spawn
        self.duration = duration
        self.ended = False
        self.success = success or {}
        self.contacts_measured = contacts_measured
        self.t0 = None
        self.t_last = None
        self.last_xy = None
        self.distance = 0.0
        self.max_speed = 0.0
        self.path = []  # (t, x, y)
        self.lap_times = []
        self._lap_start_t = None
        self._armed = False
        self._s_prev = None
        self.goal_time = None
        self.goal_min_dist = None
        self.truth_latest = None  # (t, x, y, yaw)
        self.drift_end = None
        self.drift_max = 0.0
        self.min_clearance = None
        self.scans = 0
        self.collisions = []  # (t, other, own link)
        self._last_contact = {}  # other -> last t
        self.user = {}  # name -> [stat, values]

    # -- inputs ----------------------------------------------------------------------------------
    def on_truth(self, t, x, y, yaw, speed):
        if self.ended:
            return
        if self.t0 is None:
            self.t0 = t
            self._lap_start_t = t
        if self.duration is not None and t - self.t0 >= self.duration - 1e-6:
            self.ended = True
        self.t_last = t
        if self.last_xy is not None:
            self.distance += math.hypot(x - self.last_xy[0], y - self.last_xy[1])
        self.last_xy = (x, y)
        self.max_speed = max(self.max_speed, abs(speed))
        if not self.path or t - self.path[-1][0] >= PATH_PERIOD - 1e-9:
            self.path.append((round(t, 3), round(x, 4), round(y, 4)))
        self.truth_latest = (t, x, y, yaw)
        self._laps(t, x, y)
        goal = self.success.get('goal')
        if goal:
            d = math.hypot(x - goal['x'], y - goal['y'])
            self.goal_min_dist = d if self.goal_min_dist is None else min(self.goal_min_dist, d)
            if d <= goal['radius'] and self.goal_time is None:
                self.goal_time = t

    def _laps(self, t, x, y):
        sx, sy, syaw = self.spawn
        hx, hy = math.cos(syaw), math.sin(syaw)
        dx, dy = x - sx, y - sy
        s = dx * hx + dy * hy  # along the spawn heading
        lateral = -dx * hy + dy * hx
        if math.hypot(dx, dy) > LAP_ARM_DISTANCE:
            self._armed = True
        if self._armed and self._s_prev is not None and self._s_prev < 0.0 <= s \
                and abs(lateral) < LAP_HALF_WIDTH:
            self.lap_times.append(t - self._lap_start_t)
            self._lap_start_t = t
            self._armed = False
        self._s_prev = s

    def on_odom(self, t, x, y):
        """Wheel odometry in the odom frame, which sits at the spawn pose in the world."""
        if self.ended:
            return
        if self.truth_latest is None:
            return
        sx, sy, syaw = self.spawn
        c, s = math.cos(syaw), math.sin(syaw)
        wx, wy = sx + c * x - s * y, sy + s * x + c * y
        _, tx, ty, _ = self.truth_latest
        self.drift_end = math.hypot(wx - tx, wy - ty)
        self.drift_max = max(self.drift_max, self.drift_end)

    def on_scan(self, ranges, range_min, range_max):
        if self.ended:
            return
        self.scans += 1
        valid = [r for r in ranges if range_min <= r <= range_max]
        if valid:
            m = min(valid)
            self.min_clearance = m if self.min_clearance is None else min(self.min_clearance, m)

    def on_contact(self, t, other, own_link):
        if self.ended:
            return
        last = self._last_contact.get(other)
        if last is None or t - last > COLLISION_GAP:
            self.collisions.append((t, other, own_link))
        self._last_contact[other] = t

    def add_user_metric(self, name, stat):
        self.user[name] = [stat, []]

    def on_user(self, name, value):
        if self.ended:
            return
        self.user[name][1].append(float(value))

    # -- the result ------------------------------------------------------------------------------
    def done_early(self):
        """All positive success conditions (laps, goal) met: a run with success.stop ends here."""
        s = self.success
        if not s.get('laps') and not s.get('goal'):
            return False
        return len(self.lap_times) >= (s.get('laps') or 0) and \
            (not s.get('goal') or self.goal_time is not None)

    def finish(self):
        sim_time = (self.t_last - self.t0) if self.t0 is not None else 0.0
        out = {
            'sim_time': sim_time,
            'distance': self.distance,
            'mean_speed': self.distance / sim_time if sim_time > 0 else 0.0,
            'max_speed': self.max_speed,
            'laps': len(self.lap_times),
            'lap_times': [round(x, 3) for x in self.lap_times],
            'best_lap': min(self.lap_times) if self.lap_times else None,
            'min_clearance': self.min_clearance,
            'odom_drift': self.drift_end,
            'odom_drift_max': self.drift_max if self.drift_end is not None else None,
            'odom_drift_pct': 100.0 * self.drift_end / self.distance
            if self.drift_end is not None and self.distance > 0.05 else None,
            'goal_time': (self.goal_time - self.t0) if self.goal_time is not None else None,
        }
        if self.contacts_measured:
            out['collisions'] = len(self.collisions)
            first = self.collisions[0] if self.collisions else None
            out['first_collision_time'] = first[0] if first else None  # sim time (from 0)
            out['first_collision_with'] = first[1] if first else None
            out['collided_with'] = sorted({c[1] for c in self.collisions})
        else:
            out['collisions'] = None  # not measured: the simulator publishes no contacts
            out['first_collision_time'] = None
            out['first_collision_with'] = None
            out['collided_with'] = None
        for name, (stat, values) in self.user.items():
            if not values:
                out[name] = None
            elif stat == 'min':
                out[name] = min(values)
            elif stat == 'max':
                out[name] = max(values)
            elif stat == 'last':
                out[name] = values[-1]
            else:
                out[name] = sum(values) / len(values)
        ok, why = self.verdict(out)
        out['success'] = ok
        out['reason'] = why
        return out

    def verdict(self, out):
        s = self.success
        problems, notes = [], []
        if s.get('laps'):
            if out['laps'] < s['laps']:
                problems.append('%d of %d laps' % (out['laps'], s['laps']))
        if s.get('goal'):
            if out['goal_time'] is None:
                problems.append('goal not reached (closest %.2f m)' % (self.goal_min_dist or float('nan')))
        if s.get('no_collision'):
            if out['collisions'] is None:
                notes.append('collisions not measured')
            elif out['collisions']:
                problems.append('collided with %s at %.2f s' % (out['first_collision_with'],
                                                                out['first_collision_time']))
        if problems:
            return False, '; '.join(problems + notes)
        return True, '; '.join(['conditions met'] + notes) if s else 'ran its duration'


def get_field(msg, dotted):
    """A field of a message by dotted path, with [i] for array elements (e.g. 'ranges[0]',
    'twist.twist.linear.x')."""
    v = msg
    for part in dotted.split('.'):
        name, _, index = part.partition('[')
        if name:
            v = getattr(v, name)
        while index:
            i, _, rest = index.partition(']')
            v = v[int(i)]
            index = rest[1:] if rest.startswith('[') else ''
    return v
