#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Random bodies for scripts/dev/random_bodies.sh (issue 34: validate on scenes nobody chose).

random_bodies.py SEED COUNT OUTDIR writes, for body k = 0 .. COUNT-1, OUTDIR/bodyK/body.geo
(a simple polygon of 4 to 8 vertices, convex or star-shaped, one whole side in contact, each
other side clamped or free, at least one clamped, and a free neighbour for a contact side too
short to have a free node between two clamped ones: every body is one nceig accepts) and
OUTDIR/bodyK/body.txt with the
scene's values (nu in [0, 0.49], lambda in [-20, 20], the sizes of its meshes). The same
SEED gives the same bodies on any machine (Python's random.Random is specified).
"""
import math
import os
import random
import sys

MIN_ANGLE = math.radians(25.0)    # no sharper interior angle: the meshes stay reasonable
MAX_ANGLE = math.radians(330.0)
MIN_EDGE_RATIO = 0.2              # shortest side at least this times the longest
# The coarsest mesh random_bodies.sh makes (hp_start.msh: P1, size L/2, L the body's size).
# nceig refuses a contact side without a free node (exit 2): its ends are free where a free
# side meets it, its inner nodes always, so a contact side between two clamped sides needs
# an inner node in that mesh. Gmsh (4.8.4, measured on a rectangle's side) splits a side 1.05
# times the mesh size in two and leaves one 1.0 times it whole: a shorter contact side
# between two clamped ones gets a free neighbour.
COARSEST_SIZE = 0.5
INNER_NODE_MARGIN = 1.05


def polygon(rng):
    """Vertices (anticlockwise) of a random simple polygon and whether it is convex."""
    n = rng.randint(4, 8)
    convex = rng.random() < 0.5
    while True:
        angles = sorted(rng.uniform(0.0, 2.0 * math.pi) for _ in range(n))
        if convex:
            radii = [1.0] * n
        else:
            radii = [rng.uniform(0.45, 1.0) for _ in range(n)]
        aspect = rng.uniform(0.5, 1.0)
        pts = [(r * math.cos(a), aspect * r * math.sin(a)) for r, a in zip(radii, angles)]
        if acceptable(pts):
            return pts, convex


def interior_angles(pts):
    n = len(pts)
    out = []
    for i in range(n):
        ax, ay = pts[i - 1]
        bx, by = pts[i]
        cx, cy = pts[(i + 1) % n]
        a1 = math.atan2(ay - by, ax - bx)
        a2 = math.atan2(cy - by, cx - bx)
        # interior angle of an anticlockwise polygon at b: from b->c round to b->a
        out.append((a1 - a2) % (2.0 * math.pi))
    return out


def acceptable(pts):
    n = len(pts)
    edges = [math.dist(pts[i], pts[(i + 1) % n]) for i in range(n)]
    if min(edges) < MIN_EDGE_RATIO * max(edges):
        return False
    area = 0.5 * sum(pts[i][0] * pts[(i + 1) % n][1] - pts[(i + 1) % n][0] * pts[i][1]
                     for i in range(n))
    if area <= 0.0:
        return False
    return all(MIN_ANGLE <= a <= MAX_ANGLE for a in interior_angles(pts))


def write_body(k, rng, outdir):
    pts, _ = polygon(rng)
    # scale to a longest side of 1.5 and move to the first quadrant
    n = len(pts)
    longest = max(math.dist(pts[i], pts[(i + 1) % n]) for i in range(n))
    pts = [(1.5 * x / longest, 1.5 * y / longest) for x, y in pts]
    x0 = min(p[0] for p in pts)
    y0 = min(p[1] for p in pts)
    pts = [(x - x0, y - y0) for x, y in pts]
    contact = rng.randrange(n)
    parts = []
    for i in range(n):
        if i == contact:
            parts.append('contact')
        else:
            parts.append('clamped' if rng.random() < 0.4 else 'free')
    if 'clamped' not in parts:
        others = [i for i in range(n) if i != contact]
        parts[rng.choice(others)] = 'clamped'
    nu = round(rng.uniform(0.0, 0.49), 4)
    lam = round(rng.uniform(-20.0, 20.0), 4)
    size = max(max(p[0] for p in pts), max(p[1] for p in pts))
    # only bodies nceig accepts (COARSEST_SIZE); without a draw, so every other body, and
    # this one's shape, nu and lambda, are those the seed gave before this rule
    before, after = (contact - 1) % n, (contact + 1) % n
    if parts[before] == 'clamped' and parts[after] == 'clamped' and \
            math.dist(pts[contact], pts[after]) <= INNER_NODE_MARGIN * COARSEST_SIZE * size:
        parts[after] = 'free'
    body = os.path.join(outdir, 'body%02d' % k)
    os.makedirs(body, exist_ok=True)
    with open(os.path.join(body, 'body.geo'), 'w') as geo:
        for i, (x, y) in enumerate(pts):
            geo.write('Point(%d) = {%.12g, %.12g, 0, 1};\n' % (i + 1, x, y))
        for i in range(n):
            geo.write('Line(%d) = {%d, %d};\n' % (i + 1, i + 1, (i + 1) % n + 1))
        geo.write('Curve Loop(1) = {%s};\nPlane Surface(1) = {1};\n'
                  % ', '.join(str(i + 1) for i in range(n)))
        for name in ('contact', 'clamped', 'free'):
            lines = [str(i + 1) for i in range(n) if parts[i] == name]
            if lines:
                geo.write('Physical Curve("%s") = {%s};\n' % (name, ', '.join(lines)))
        geo.write('Physical Surface("body") = {1};\n')
    angles = interior_angles(pts)
    with open(os.path.join(body, 'body.txt'), 'w') as txt:
        txt.write('vertices=%d\nconvex=%d\nnu=%s\nlambda=%s\nsize=%.6g\n'
                  % (n, int(max(angles) < math.pi), nu, lam, size))
        txt.write('neumann=%s\n' % ('free' if 'free' in parts else ''))
        # side i runs from vertex i to i + 1: the contact side's ends meet sides contact - 1
        # and contact + 1
        start, end = contact, (contact + 1) % n
        txt.write("corner_start='%s %.3f'\n" % (parts[(contact - 1) % n], math.degrees(angles[start])))
        txt.write("corner_end='%s %.3f'\n" % (parts[(contact + 1) % n], math.degrees(angles[end])))


def main():
    if len(sys.argv) != 4:
        sys.exit('usage: random_bodies.py SEED COUNT OUTDIR')
    seed, count, outdir = int(sys.argv[1]), int(sys.argv[2]), sys.argv[3]
    for k in range(count):
        write_body(k, random.Random(seed * 100003 + k), outdir)


if __name__ == '__main__':
    main()
