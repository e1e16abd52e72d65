#!/usr/bin/env python3
"""Generates the floor texture of tianracer_sim/worlds/lane_track.world: a road with lane markings.

The road follows racetrack.world's centreline (a rounded rectangle, x in [-4, 4], y in [0, 4],
corner radius 1.25 m; the car spawns at the origin facing +x on the bottom straight). The texture
covers the floor model, x in [-6, 6] and y in [-2, 6] (12 m x 8 m), at 100 px per metre, north
(+y) up: dark asphalt 1.2 m wide, solid white edge lines (5 cm) whose inner edges are 0.5 m from
the centreline, a dashed yellow centre line (4 cm; 0.3 m dashes, 0.3 m gaps), a white start line
across the road at x = 0, and light grass elsewhere. Deterministic; needs Pillow.
Usage: make_lane_track.py [--output PATH]
(default: ../worlds/models/lane_track/materials/textures/lane_track.png next to this file).
"""

import argparse
import math
import os

from PIL import Image, ImageDraw

LENGTH, HEIGHT, RADIUS = 8.0, 4.0, 1.25   # centreline, as racetrack.world
FLOOR_X, FLOOR_Y = (-6.0, 6.0), (-2.0, 6.0)
PX_PER_M = 100
SUPERSAMPLE = 2                           # drawn at 2x, then downsampled: smooth edges
ROAD_HALF_WIDTH = 0.6
EDGE_LINE = (0.5, 0.55)                   # m from the centreline: the white lines' inner/outer edge
CENTRE_LINE_WIDTH = 0.04
DASH, GAP = 0.3, 0.3
GRASS, ASPHALT = (112, 140, 92), (62, 62, 66)
WHITE, YELLOW = (235, 235, 235), (230, 190, 40)


def centreline(step=0.01):
    """Points along the centreline, counter-clockwise from the origin, about `step` apart."""
    hx, r = LENGTH / 2 - RADIUS, RADIUS
    pts = []
    def straight(p, q):
        n = max(1, int(math.dist(p, q) / step))
        pts.extend((p[0] + (q[0] - p[0]) * k / n, p[1] + (q[1] - p[1]) * k / n) for k in range(n))
    def arc(c, a0):
        n = max(1, int(r * math.pi / 2 / step))
        pts.extend((c[0] + r * math.cos(a0 + math.pi / 2 * k / n),
                    c[1] + r * math.sin(a0 + math.pi / 2 * k / n)) for k in range(n))
    straight((0.0, 0.0), (hx, 0.0))
    arc((hx, r), -math.pi / 2)
    straight((LENGTH / 2, r), (LENGTH / 2, HEIGHT - r))
    arc((hx, HEIGHT - r), 0.0)
    straight((hx, HEIGHT), (-hx, HEIGHT))
    arc((-hx, HEIGHT - r), math.pi / 2)
    straight((-LENGTH / 2, HEIGHT - r), (-LENGTH / 2, r))
    arc((-hx, r), math.pi)
    straight((-hx, 0.0), (0.0, 0.0))
    return pts


def to_px(x, y):
    s = PX_PER_M * SUPERSAMPLE
    return ((x - FLOOR_X[0]) * s, (FLOOR_Y[1] - y) * s)   # image rows go down, +y goes up


def band(draw, pts, half_width, colour):
    """A stroke of `half_width` metres each side of the polyline."""
    s = PX_PER_M * SUPERSAMPLE
    w = max(1, round(2 * half_width * s))
    draw.line([to_px(*p) for p in pts] + [to_px(*pts[0])], fill=colour, width=w, joint="curve")
    for p in pts[::10]:
        x, y = to_px(*p)
        draw.ellipse([x - w / 2, y - w / 2, x + w / 2, y + w / 2], fill=colour)


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    default = os.path.join(here, "..", "worlds", "models", "lane_track", "materials", "textures",
                           "lane_track.png")
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--output", default=os.path.normpath(default))
    args = parser.parse_args()
    s = PX_PER_M * SUPERSAMPLE
    size = (round((FLOOR_X[1] - FLOOR_X[0]) * s), round((FLOOR_Y[1] - FLOOR_Y[0]) * s))
    img = Image.new("RGB", size, GRASS)
    draw = ImageDraw.Draw(img)
    pts = centreline()
    band(draw, pts, ROAD_HALF_WIDTH, ASPHALT)
    # The white edge lines: a white band to the outer edge, asphalt again inside the inner edge.
    band(draw, pts, EDGE_LINE[1], WHITE)
    band(draw, pts, EDGE_LINE[0], ASPHALT)
    # Dashed centre line, by arc length.
    period, travelled = DASH + GAP, 0.0
    dash = []
    for a, b in zip(pts, pts[1:] + pts[:1]):
        if travelled % period < DASH:
            dash.append(a)
        elif dash:
            if len(dash) > 1:
                draw.line([to_px(*p) for p in dash], fill=YELLOW, width=round(CENTRE_LINE_WIDTH * s))
            dash = []
        travelled += math.dist(a, b)
    if len(dash) > 1:
        draw.line([to_px(*p) for p in dash], fill=YELLOW, width=round(CENTRE_LINE_WIDTH * s))
    # Start line across the road at x = 0 (bottom straight).
    draw.rectangle([to_px(-0.025, EDGE_LINE[0]), to_px(0.025, -EDGE_LINE[0])], fill=WHITE)
    img = img.resize((size[0] // SUPERSAMPLE, size[1] // SUPERSAMPLE), Image.LANCZOS)
    os.makedirs(os.path.dirname(args.output), exist_ok=True)
    img.save(args.output, optimize=True)
    print(f"wrote {args.output} ({img.size[0]}x{img.size[1]}, {os.path.getsize(args.output)} bytes)")


if __name__ == "__main__":
    main()
