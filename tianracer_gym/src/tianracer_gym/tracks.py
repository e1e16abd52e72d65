"""Centrelines of the shipped worlds, for the progress reward and the start poses."""
from tianracer_sim.simulator import Centreline


def centreline_for(world):
    """The centreline of a shipped world, or None. racetrack: the headless demo's
    (tianracer_bringup.track), a closed lap of 21.85 m counter-clockwise from the origin."""
    if world == 'racetrack':
        from tianracer_bringup.track import centreline
        return Centreline(centreline(0.05), True)
    return None


def make_centreline(points, closed=True):
    """A Centreline from an (N, 2) sequence of points, or a Centreline as it is."""
    if isinstance(points, Centreline):
        return points
    pts = [(float(p[0]), float(p[1])) for p in points]
    return Centreline(pts, closed)
