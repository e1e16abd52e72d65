#!/usr/bin/env python3
"""Generates tianracer_sim/worlds/racetrack.world: a closed loop with inner and outer walls and cones.

The centreline is a rounded rectangle: x in [-L/2, L/2], y in [0, H], corner radius R, driven
counter-clockwise. The bottom straight runs along y = 0 through the origin, so a car spawned at the
origin facing +x sits on the centreline. Walls are chains of static boxes whose track-facing faces
lie on chords of the wall curves (inscribed polygons, at most SAGITTA deep). Deterministic; stdlib
only. Usage: make_racetrack.py [--output PATH] (default: ../worlds/racetrack.world next to this file).
"""

import argparse
import math
import os

LENGTH = 8.0        # m, centreline extent along x
HEIGHT = 4.0        # m, centreline extent along y
RADIUS = 1.25       # m, centreline corner radius (the car's minimum turning radius is ~0.45 m)
WIDTH = 1.0         # m, between the walls' track-facing faces
WALL_THICKNESS = 0.05
WALL_HEIGHT = 0.3
SAGITTA = 0.005     # m, max depth of a wall chord under its arc
CONE_RADIUS = 0.06
CONE_HEIGHT = 0.3


def corner_centres():
    """Corner arc centres, counter-clockwise from the bottom-right, with start angles."""
    hx, r = LENGTH / 2 - RADIUS, RADIUS
    return [((hx, r), -math.pi / 2), ((hx, HEIGHT - r), 0.0),
            ((-hx, HEIGHT - r), math.pi / 2), ((-hx, r), math.pi)]


def loop(offset):
    """Closed polyline at `offset` from the centreline (+ outwards), counter-clockwise."""
    r = RADIUS + offset
    n = max(2, math.ceil((math.pi / 2) / (2 * math.acos(1 - SAGITTA / r))))
    pts = []
    for (cx, cy), a0 in corner_centres():
        for k in range(n + 1):
            a = a0 + (math.pi / 2) * k / n
            pts.append((cx + r * math.cos(a), cy + r * math.sin(a)))
    return pts


def f(v):
    s = "%.6f" % v
    return "0.000000" if s == "-0.000000" else s


def wall_boxes(offset, outward):
    """Boxes along the polyline at `offset`; `outward` = +1 puts the wall outside the line."""
    pts = loop(offset)
    boxes = []
    for i in range(len(pts)):
        (x0, y0), (x1, y1) = pts[i], pts[(i + 1) % len(pts)]
        length = math.hypot(x1 - x0, y1 - y0)
        if length < 1e-9:
            continue
        yaw = math.atan2(y1 - y0, x1 - x0)
        # Left normal of a counter-clockwise loop points inwards; the wall body goes away from
        # the track: outwards for the outer wall, inwards for the inner one.
        nx, ny = math.sin(yaw), -math.cos(yaw)  # right normal = outwards
        s = outward * WALL_THICKNESS / 2
        cx, cy = (x0 + x1) / 2 + s * nx, (y0 + y1) / 2 + s * ny
        # Overlap neighbours by one thickness so that the chain has no gaps.
        boxes.append((cx, cy, yaw, length + WALL_THICKNESS))
    return boxes


def wall_model(name, boxes, material):
    out = ['    <model name="%s">' % name, "      <static>true</static>",
           '      <link name="link">']
    for i, (x, y, yaw, length) in enumerate(boxes):
        pose = "%s %s %s 0 0 %s" % (f(x), f(y), f(WALL_HEIGHT / 2), f(yaw))
        size = "%s %s %s" % (f(length), f(WALL_THICKNESS), f(WALL_HEIGHT))
        for kind in ("collision", "visual"):
            out.append('        <%s name="segment_%03d">' % (kind, i))
            out.append("          <pose>%s</pose>" % pose)
            out.append("          <geometry><box><size>%s</size></box></geometry>" % size)
            if kind == "visual":
                out.append("          <material><script><name>%s</name></script></material>"
                           % material)
            out.append("        </%s>" % kind)
    out += ["      </link>", "    </model>"]
    return out


def cones():
    """Four at the corner apexes, 0.2 m off the inner wall; two on the top straight near the
    outer wall. Each leaves more than 0.2 m between its edge and the centreline."""
    pos = []
    for (cx, cy), a0 in corner_centres():
        a = a0 + math.pi / 4
        r = RADIUS - WIDTH / 2 + 0.2
        pos.append((cx + r * math.cos(a), cy + r * math.sin(a)))
    pos.append((1.0, HEIGHT + WIDTH / 2 - 0.15))
    pos.append((-1.0, HEIGHT + WIDTH / 2 - 0.15))
    return pos


def cone_model(i, x, y):
    geometry = ("<geometry><cylinder><radius>%s</radius><length>%s</length></cylinder></geometry>"
                % (f(CONE_RADIUS), f(CONE_HEIGHT)))
    return ['    <model name="cone_%d">' % i, "      <static>true</static>",
            "      <pose>%s %s %s 0 0 0</pose>" % (f(x), f(y), f(CONE_HEIGHT / 2)),
            '      <link name="link">',
            '        <collision name="collision">', "          " + geometry,
            "        </collision>",
            '        <visual name="visual">', "          " + geometry,
            "          <material><script><name>Gazebo/Orange</name></script></material>",
            "        </visual>", "      </link>", "    </model>"]


def world():
    straight_x = LENGTH - 2 * RADIUS
    straight_y = HEIGHT - 2 * RADIUS
    lap = 2 * straight_x + 2 * straight_y + 2 * math.pi * RADIUS
    inner, outer = wall_boxes(-WIDTH / 2, -1), wall_boxes(WIDTH / 2, +1)
    lines = [
        '<?xml version="1.0"?>',
        "<!--",
        "  racetrack: GENERATED by tianracer_sim/scripts/make_racetrack.py; edit the script, not this.",
        "",
        "  Centreline: a rounded rectangle, x in [%g, %g], y in [0, %g], corner radius %g m,"
        % (-LENGTH / 2, LENGTH / 2, HEIGHT, RADIUS),
        "  driven counter-clockwise; straights %g m (along x, y = 0 and y = %g) and %g m (along y,"
        % (straight_x, HEIGHT, straight_y),
        "  x = +-%g); lap length %.3f m." % (LENGTH / 2, lap),
        "  Track width %g m between the walls' faces (centreline +-%g m); walls %g m high, %g m thick,"
        % (WIDTH, WIDTH / 2, WALL_HEIGHT, WALL_THICKNESS),
        "  made of %d (inner) and %d (outer) static boxes on chords at most %g m under the arcs."
        % (len(inner), len(outer), SAGITTA),
        "  Inner wall corner radius %g m, outer %g m." % (RADIUS - WIDTH / 2, RADIUS + WIDTH / 2),
        "  Spawn: the origin facing +x is on the centreline of the bottom straight (the start line).",
        "  Cones (static cylinders r %g m, %g m high, Gazebo/Orange) at:" % (CONE_RADIUS, CONE_HEIGHT),
    ]
    for i, (x, y) in enumerate(cones()):
        lines.append("    cone_%d (%.3f, %.3f)" % (i, x, y))
    lines += [
        "-->",
        '<sdf version="1.6">',
        '  <world name="racetrack">',
        '    <physics name="default_physics" default="0" type="ode">',
        "      <max_step_size>0.001</max_step_size>",
        "      <real_time_factor>1</real_time_factor>",
        "      <real_time_update_rate>1000</real_time_update_rate>",
        "    </physics>",
        "    <gravity>0 0 -9.8</gravity>",
        "    <include>", "      <uri>model://ground_plane</uri>", "    </include>",
        "    <include>", "      <uri>model://sun</uri>", "    </include>",
        # Start line: visual only, so it neither trips the car nor shows in the lidar.
        '    <model name="start_line">', "      <static>true</static>",
        "      <pose>0 0 0.001 0 0 0</pose>", '      <link name="link">',
        '        <visual name="visual">',
        "          <geometry><box><size>0.05 %s 0.002</size></box></geometry>" % f(WIDTH),
        "          <material><script><name>Gazebo/White</name></script></material>",
        "        </visual>", "      </link>", "    </model>",
    ]
    lines += wall_model("inner_wall", inner, "Gazebo/Red")
    lines += wall_model("outer_wall", outer, "Gazebo/White")
    for i, (x, y) in enumerate(cones()):
        lines += cone_model(i, x, y)
    lines += ["  </world>", "</sdf>"]
    return "\n".join(lines) + "\n"


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--output", default=os.path.join(here, "..", "worlds", "racetrack.world"))
    args = parser.parse_args()
    with open(args.output, "w") as out:
        out.write(world())


if __name__ == "__main__":
    main()
