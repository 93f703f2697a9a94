#!/usr/bin/env python3
"""Writes the estimation-speed benchmark meshes (ASCII STL, millimetres) beside this script.

Parts of other sizes and shapes than the built-in ones, for bench_estimation --meshes, each with its
origin at the centre of its bounding box (a symmetry is found about the model origin). The files
are kept in the repository; run this only to change them.
  bearing_plate.stl     a revolved plate 120 mm across, 10 mm thick: a raceway groove, a stepped
                        bore, chamfers, 128 facets around (a fine CAD export, about 1.5 MB)
  toothed_wheel.stl     a spur wheel of 24 teeth, 64 mm across the tips, 10 mm wide, a 16 mm bore
  perforated_plate.stl  a sheet 110 x 70 x 3 mm with six square holes and two slots
  long_profile.stl      an extruded C-channel 160 mm long, 30 x 20 mm, 3 mm walls, lipped
"""
import math
import pathlib

from make_turned_meshes import revolve, write_stl

# (r, z) counter-clockwise, revolved about z.
BEARING_PLATE = [(9, -5), (20, -5), (21, -4), (52, -4), (52, -5), (59, -5), (60, -4), (60, 4), (59, 5),
                 (52, 5), (52, 4), (44, 4), (43, 2.5), (41.5, 1.8), (40, 1.5), (38.5, 1.8), (37, 2.5), (36, 4),
                 (21, 4), (20, 5), (12, 5), (12, 2), (9, 2)]


def quad(a, b, c, d):
    """Two triangles of the quad a b c d (counter-clockwise seen from outside)."""
    return [(a, b, c), (a, c, d)]


def extrude_star(outline, inner, height):
    """A prism between two star-shaped loops sampled at the same angles (outline counter-clockwise
    seen from +z, inner the bore): caps as strips between the loops, walls outside and in."""
    triangles = []
    n = len(outline)
    for i in range(n):
        j = (i + 1) % n
        o0, o1, i0, i1 = outline[i], outline[j], inner[i], inner[j]
        top = lambda p: (p[0], p[1], height)
        bottom = lambda p: (p[0], p[1], 0.0)
        triangles += quad(top(o0), top(o1), top(i1), top(i0))
        triangles += quad(bottom(o0), bottom(i0), bottom(i1), bottom(o1))
        triangles += quad(bottom(o0), bottom(o1), top(o1), top(o0))
        triangles += quad(bottom(i1), bottom(i0), top(i0), top(i1))
    return triangles


def toothed_wheel(teeth=24, tip=32.0, root=28.0, bore=8.0, width=10.0, per_tooth=12):
    """Trapezoid teeth: the tip a third of the pitch, the flanks a sixth each, every tooth mirror
    symmetric about its centre line (one lies on +x), so the wheel flips over onto itself."""
    outline, inner = [], []
    steps = teeth * per_tooth
    for k in range(steps):
        phase = (k % per_tooth) / per_tooth
        if phase < 1 / 3:
            r = root
        elif phase < 1 / 2:
            r = root + (tip - root) * (phase - 1 / 3) * 6
        elif phase < 5 / 6:
            r = tip
        else:
            r = tip - (tip - root) * (phase - 5 / 6) * 6
        angle = 2 * math.pi * (k / steps - (2 / 3) / teeth)  # the tip's centre, phase 2/3, on +x
        outline.append((r * math.cos(angle), r * math.sin(angle)))
        inner.append((bore * math.cos(angle), bore * math.sin(angle)))
    return extrude_star(outline, inner, width)


def grid_solid(xs, ys, solid, height):
    """A sheet on the grid lines xs, ys: cell (i, j) is material when solid(i, j); caps per cell,
    walls wherever material meets a hole or the outside."""
    triangles = []
    nx, ny = len(xs) - 1, len(ys) - 1
    filled = lambda i, j: 0 <= i < nx and 0 <= j < ny and solid(i, j)
    for i in range(nx):
        for j in range(ny):
            if not filled(i, j):
                continue
            x0, x1, y0, y1 = xs[i], xs[i + 1], ys[j], ys[j + 1]
            triangles += quad((x0, y0, height), (x1, y0, height), (x1, y1, height), (x0, y1, height))
            triangles += quad((x0, y0, 0), (x0, y1, 0), (x1, y1, 0), (x1, y0, 0))
            if not filled(i - 1, j):
                triangles += quad((x0, y0, 0), (x0, y0, height), (x0, y1, height), (x0, y1, 0))
            if not filled(i + 1, j):
                triangles += quad((x1, y0, 0), (x1, y1, 0), (x1, y1, height), (x1, y0, height))
            if not filled(i, j - 1):
                triangles += quad((x0, y0, 0), (x1, y0, 0), (x1, y0, height), (x0, y0, height))
            if not filled(i, j + 1):
                triangles += quad((x0, y1, 0), (x0, y1, height), (x1, y1, height), (x1, y1, 0))
    return triangles


def perforated_plate():
    # Grid lines through every hole's edges; holes are cells (i, j) listed by their lower corner.
    xs = [0, 10, 22, 33, 45, 55, 65, 77, 88, 100, 110]
    ys = [0, 10, 22, 28, 35, 42, 48, 60, 70]
    holes = {(1, 1), (4, 1), (7, 1), (1, 6), (4, 6), (7, 6)}  # 12 x 12 and 10 x 12 squares
    slots = {(2, 3), (3, 3), (4, 3), (5, 3), (6, 3)}  # one slot 44 x 7 ...
    slots |= {(2, 4), (6, 4)}  # ... and two short ones below it
    return grid_solid(xs, ys, lambda i, j: (i, j) not in holes | slots, 3.0)


def long_profile(length=160.0):
    """A lipped C-channel: the section in (x, y), extruded along z."""
    section = [(0, 0), (30, 0), (30, 20), (24, 20), (24, 17), (27, 17), (27, 3), (3, 3), (3, 17), (6, 17),
               (6, 20), (0, 20)]  # counter-clockwise
    # Caps: the section cut into rectangles (bottom web, two walls, two lips).
    rectangles = [((0, 0), (30, 3)), ((0, 3), (3, 20)), ((27, 3), (30, 20)), ((3, 17), (6, 20)), ((24, 17), (27, 20))]
    triangles = []
    for (x0, y0), (x1, y1) in rectangles:
        triangles += quad((x0, y0, length), (x1, y0, length), (x1, y1, length), (x0, y1, length))
        triangles += quad((x0, y0, 0), (x0, y1, 0), (x1, y1, 0), (x1, y0, 0))
    for k in range(len(section)):
        (x0, y0), (x1, y1) = section[k], section[(k + 1) % len(section)]
        triangles += quad((x0, y0, 0), (x1, y1, 0), (x1, y1, length), (x0, y0, length))
    return triangles


def centred(triangles):
    """The triangles moved so that their bounding box's centre is the origin."""
    points = [p for t in triangles for p in t]
    centre = [(min(p[i] for p in points) + max(p[i] for p in points)) / 2 for i in range(3)]
    return [tuple(tuple(p[i] - centre[i] for i in range(3)) for p in t) for t in triangles]


if __name__ == "__main__":
    here = pathlib.Path(__file__).resolve().parent
    write_stl(here / "bearing_plate.stl", "bearing_plate", centred(revolve(BEARING_PLATE, segments=128)))
    write_stl(here / "toothed_wheel.stl", "toothed_wheel", centred(toothed_wheel()))
    write_stl(here / "perforated_plate.stl", "perforated_plate", centred(perforated_plate()))
    write_stl(here / "long_profile.stl", "long_profile", centred(long_profile()))
