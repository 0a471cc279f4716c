#!/usr/bin/env python3
"""Writes a billiards scene: a cue ball shot into a triangle of N-1 balls on a
table with four fixed rails, no gravity. Usage:
  billiards.py N [--impulses] [--all-pairs] [--no-rails] [--name NAME] > Scene.mo
"""
import math, sys

args = sys.argv[1:]
n = int(args[0])
impulses = "--impulses" in args
all_pairs = "--all-pairs" in args
rails = "--no-rails" not in args
name = args[args.index("--name") + 1] if "--name" in args else "Billiards%d" % n
# Penalty contact starts every contact with an onset event (the approach speed sets
# the restitution damping), so the rack has a small gap; impulses take touching balls.
gap = 0.0 if impulses else 1e-5
R, m = 0.0286, 0.17
pos = [(-0.6, 0.0)]
k = 0
while len(pos) < n:
    for j in range(k + 1):
        if len(pos) == n:
            break
        pos.append((0.3 + k * math.sqrt(3) * (R + gap / 2), (j - k / 2) * (2 * R + gap)))
    k += 1
xs = [p[0] for p in pos]; ys = [p[1] for p in pos]
# Table: at least the standard 2.54 x 1.27 m, grown to hold the rack.
hx = max(1.27, max(abs(x) for x in xs) + 0.3)
hy = max(0.635, max(abs(y) for y in ys) + 0.3)
law = "impulses = true, e = 1" if impulses else "K = 1e8, n = 1.5, law = DampingLaw.Flores, e = 0.95"
bp = ", broadphase = 1" if all_pairs else ""
out = []
out.append('model %s "Billiards: a cue ball into a triangle of %d balls%s%s"' % (
    name, n - 1, ", impulse impacts" if impulses else ", penalty contact", ", all-pairs broadphase" if all_pairs else ""))
out.append("  import Unimo.Collision.*;")
out.append("  parameter Real R = %r;" % R)
out.append("  parameter Real m = %r;" % m)
out.append("  inner CollisionWorld world(g = {0, 0, 0}, %s%s);" % (law, bp))
out.append("  Ball cue(radius = R, m = m, r0 = {%r, 0, 0}, v0 = {5, 0.05, 0});" % pos[0][0])
for i, (x, y) in enumerate(pos[1:], 1):
    out.append("  Ball b%d(radius = R, m = m, r0 = {%r, %r, 0});" % (i, x, y))
if rails:
    out.append("  Obstacle railN(dims = {%r, 0.1, 0.1}, r0 = {0, %r, 0});" % (2 * hx + 0.2, hy + 0.05))
    out.append("  Obstacle railS(dims = {%r, 0.1, 0.1}, r0 = {0, %r, 0});" % (2 * hx + 0.2, -hy - 0.05))
    out.append("  Obstacle railE(dims = {0.1, %r, 0.1}, r0 = {%r, 0, 0});" % (2 * hy, hx + 0.05))
    out.append("  Obstacle railW(dims = {0.1, %r, 0.1}, r0 = {%r, 0, 0});" % (2 * hy, -hx - 0.05))
balls = ["cue"] + ["b%d" % i for i in range(1, n)]
for c in "xyz":
    k = "xyz".index(c) + 1
    out.append("  Real P%s = %s \"Momentum\";" % (c, " + ".join("m * %s.v[%d]" % (b, k) for b in balls)))
out.append("  Real E = %s \"Kinetic energy\";" % " + ".join("0.5 * m * (%s.v * %s.v) + 0.5 * %s.J * (%s.w * %s.w)" % (b, b, b, b, b) for b in balls))
out.append("  annotation(experiment(StopTime = 1, Tolerance = 1e-6, Interval = 0.01));")
out.append("end %s;" % name)
print("\n".join(out))
