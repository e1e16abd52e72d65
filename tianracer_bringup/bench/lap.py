"""The lap a benchmark car drives, from its base's track, the same way for every side (ours from
/ground_truth/odom, PyBullet and MuJoCo from their base pose): mean speed, turn radius and
whether it stayed on its wheels. Standard library only: the harness, the ROS client and the
peers' virtual environment all import it.

A sample is (t, x, y, up_z): sim time, the base's position on the ground, and the z component of
its body z axis (1 upright, < 0 upside down).
"""
import math

# Samples before this sim time are the start (the car accelerating, the steering turning in):
# left out of speed and radius when the run is longer than twice it. PyBullet's car needs about
# 3 s to reach its speed (0.30, 0.73, 0.996 m/s over the first three seconds), MuJoCo's and ours
# about 1 s.
SETTLE = 3.0  # s
# Tilted past 60 degrees counts as a flip (a car on its side has up_z near 0).
FLIPPED_UP_Z = 0.5


def up_z(qx, qy):
    """z of the body z axis for a unit quaternion (x, y, z, w): 1 - 2 (qx^2 + qy^2)."""
    return 1.0 - 2.0 * (qx * qx + qy * qy)


def fit_circle(points):
    """Radius of the least-squares circle through [(x, y)] (Kasa's algebraic fit: x^2 + y^2 + D x +
    E y + F = 0), or None for fewer than 3 points or points on a line."""
    n = len(points)
    if n < 3:
        return None
    mx = sum(p[0] for p in points) / n
    my = sum(p[1] for p in points) / n
    # Centred, for conditioning: u = x - mx, v = y - my; solve for the centre (uc, vc).
    suu = svv = suv = suuu = svvv = suvv = svuu = 0.0
    for x, y in points:
        u, v = x - mx, y - my
        suu += u * u
        svv += v * v
        suv += u * v
        suuu += u * u * u
        svvv += v * v * v
        suvv += u * v * v
        svuu += v * u * u
    det = suu * svv - suv * suv
    if abs(det) < 1e-12 * max(1.0, suu * svv):
        return None
    b1 = 0.5 * (suuu + suvv)
    b2 = 0.5 * (svvv + svuu)
    uc = (b1 * svv - b2 * suv) / det
    vc = (suu * b2 - suv * b1) / det
    return math.sqrt(uc * uc + vc * vc + (suu + svv) / n)


def lap(samples):
    """dict(speed m/s, radius m or None, flipped bool, start and end s of the window measured) of a
    track, or None when it has fewer than 3 samples. Speed is the path length over the time, both
    after SETTLE; flipped looks at the whole track."""
    if len(samples) < 3:
        return None
    samples = sorted(samples)
    t_end = samples[-1][0]
    window = [s for s in samples if s[0] >= SETTLE] if t_end >= 2 * SETTLE else samples
    if len(window) < 3:
        window = samples
    path = sum(math.hypot(b[1] - a[1], b[2] - a[2]) for a, b in zip(window, window[1:]))
    dt = window[-1][0] - window[0][0]
    return dict(speed=path / dt if dt > 0 else None, radius=fit_circle([(s[1], s[2]) for s in window]),
                flipped=any(s[3] < FLIPPED_UP_Z for s in samples), start=window[0][0], end=window[-1][0])


def summary(laps):
    """The laps of one side's cars as dict(cars, speed=(min, max), radius=(min, max), flipped=count);
    None when no car has a lap."""
    laps = [x for x in laps if x]
    if not laps:
        return None
    speeds = [x["speed"] for x in laps if x["speed"] is not None]
    radii = [x["radius"] for x in laps if x["radius"] is not None]
    return dict(cars=len(laps), start=min(x["start"] for x in laps), end=max(x["end"] for x in laps),
                speed=(min(speeds), max(speeds)) if speeds else None,
                radius=(min(radii), max(radii)) if radii else None,
                flipped=sum(1 for x in laps if x["flipped"]))


def parse_poses(text):
    """The peers' --poses: 'x,y,yaw x,y,yaw ...' -> [(x, y, yaw)]; ValueError naming a bad item."""
    poses = []
    for item in text.split():
        try:
            v = [float(x) for x in item.split(",")]
        except ValueError:
            v = []
        if len(v) != 3 or not all(math.isfinite(x) for x in v):
            raise ValueError("a pose is x,y,yaw (finite numbers), not %r" % item)
        poses.append(tuple(v))
    if not poses:
        raise ValueError("no pose in %r" % text)
    return poses


def format_poses(poses):
    return " ".join("%g,%g,%g" % tuple(x) for x in poses)
