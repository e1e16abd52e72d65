"""The racetrack's centreline and a pure-pursuit steering law (the headless demo's, as a library
for drivers)."""
import math

# Racetrack centreline (tianracer_sim/scripts/make_racetrack.py): a rounded rectangle,
# x in [-4, 4], y in [0, 4], corner radius 1.25 m, counter-clockwise from the origin.
TRACK = dict(length=8.0, height=4.0, radius=1.25)


def centreline(step=0.05):
    """Points of the racetrack's centreline every ~step m, counter-clockwise from (0, 0)."""
    L, H, R = TRACK['length'], TRACK['height'], TRACK['radius']
    hx = L / 2.0
    out = []

    def straight(a, b):
        n = max(1, int(math.hypot(b[0] - a[0], b[1] - a[1]) / step))
        out.extend((a[0] + (b[0] - a[0]) * k / n, a[1] + (b[1] - a[1]) * k / n) for k in range(n))

    def arc(c, a0):
        n = max(2, int(R * math.pi / 2 / step))
        out.extend((c[0] + R * math.cos(a0 + math.pi / 2 * k / n),
                    c[1] + R * math.sin(a0 + math.pi / 2 * k / n)) for k in range(n))

    straight((0.0, 0.0), (hx - R, 0.0))
    arc((hx - R, R), -math.pi / 2)
    straight((hx, R), (hx, H - R))
    arc((hx - R, H - R), 0.0)
    straight((hx - R, H), (-hx + R, H))
    arc((-hx + R, H - R), math.pi / 2)
    straight((-hx, H - R), (-hx, R))
    arc((-hx + R, R), math.pi)
    straight((-hx + R, 0.0), (0.0, 0.0))
    return out


def pure_pursuit(path, x, y, yaw, index, lookahead):
    """Curvature towards the path point `lookahead` ahead of the nearest point at or after
    `index` (searched over the next 60 points); returns (curvature, new index)."""
    n = len(path)
    best, best_d = index, float('inf')
    for k in range(60):
        i = (index + k) % n
        d = math.hypot(path[i][0] - x, path[i][1] - y)
        if d < best_d:
            best, best_d = i, d
    j = best
    for _ in range(n):
        if math.hypot(path[j][0] - x, path[j][1] - y) >= lookahead:
            break
        j = (j + 1) % n
    alpha = math.atan2(path[j][1] - y, path[j][0] - x) - yaw
    return 2.0 * math.sin(alpha) / lookahead, best


class LapProgress:
    """Distance along a closed path covered as the pursuit's nearest-point index advances."""

    def __init__(self, path):
        n = len(path)
        self.segments = [math.hypot(path[(i + 1) % n][0] - path[i][0], path[(i + 1) % n][1] - path[i][1])
                         for i in range(n)]
        self.lap_length = sum(self.segments)
        self.distance = 0.0

    def advance(self, old, new):
        """Adds the segments from index `old` forward to `new` (wrapping round the lap)."""
        n = len(self.segments)
        for k in range((new - old) % n):
            self.distance += self.segments[(old + k) % n]
        return self.distance
