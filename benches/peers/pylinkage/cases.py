"""pylinkage's path generation on the literature's four-bar path-synthesis cases.

Run with pylinkage installed in a virtual environment outside the repository:

    python3 -m venv /tmp/venv && /tmp/venv/bin/pip install pylinkage==1.3.0
    /tmp/venv/bin/python benches/peers/pylinkage/cases.py

(a) and (d) go to ``path_generation_with_timing`` (crank rotations between the targets given;
pylinkage takes them as the coupler's rotations and uses the first five targets), (b) and (c)
to ``path_generation``. pylinkage is deterministic (a grid over the coupler's orientations and
Burmester theory): one run per case, with its default ``require_grashof=True`` and again with
``False``. Every design returned is scored here, in the literature's
measure, with a closed-form four-bar written below (not pylinkage's): with timing, the coupler
point at the crank angles of the targets (the first target's angle is the design's initial
crank angle, the others follow by the given rotations); without timing, each target's squared
distance to the nearest of 36 000 points of the coupler curve (order not enforced, a lower
bound of the ordered error). Whether the design lies within the case's bounds is reported.
"""

import math
import time

import pylinkage
from pylinkage.synthesis import path_generation, path_generation_with_timing

CASES = {
    "a: 5 points, timed": dict(
        targets=[(3.0, 3.0), (2.759, 3.363), (2.372, 3.663), (1.890, 3.862), (1.355, 3.943)],
        crank=[math.pi / 6, math.pi / 4, math.pi / 3, 5 * math.pi / 12, math.pi / 2],
        links=(0.0, 5.0), coords=(-5.0, 5.0), threshold=1e-4),
    "b: 6 points on a line, untimed": dict(
        targets=[(20.0, 20.0 + 5.0 * k) for k in range(6)], crank=None,
        links=(5.0, 60.0), coords=(-60.0, 60.0), threshold=1e-2),
    "c: 10 points on an ellipse, untimed": dict(
        targets=[(20, 10), (17.66, 15.142), (11.736, 17.878), (5, 16.928), (0.60307, 12.736),
                 (0.60307, 7.2638), (5, 3.0718), (11.736, 2.1215), (17.66, 4.8577), (20, 10)],
        crank=None, links=(5.0, 80.0), coords=(-80.0, 80.0), threshold=1e-2),
    "d: 18 points of a closed curve, timed": dict(
        targets=[(0.5, 1.1), (0.4, 1.1), (0.3, 1.1), (0.2, 1.0), (0.1, 0.9), (0.005, 0.75),
                 (0.02, 0.6), (0, 0.5), (0, 0.4), (0.03, 0.3), (0.1, 0.25), (0.15, 0.2),
                 (0.2, 0.3), (0.3, 0.4), (0.4, 0.5), (0.5, 0.7), (0.6, 0.9), (0.6, 1.0)],
        crank=[math.radians(20 * k) for k in range(18)],
        links=(0.0, 50.0), coords=(-50.0, 50.0), threshold=2e-2),
}


def cross(u, v):
    return u[0] * v[1] - u[1] * v[0]


class FourBar:
    """A four-bar from pylinkage's solution, in the literature's variables, in closed form."""

    def __init__(self, s):
        (ax, ay), (dx, dy) = s.ground_pivot_a, s.ground_pivot_d
        (bx, by), (cx, cy) = s.crank_pivot_b, s.coupler_pivot_c
        px, py = s.coupler_point
        self.a, self.d = (ax, ay), (dx, dy)
        self.r1 = math.hypot(dx - ax, dy - ay)
        self.r2 = math.hypot(bx - ax, by - ay)
        self.r3 = math.hypot(cx - bx, cy - by)
        self.r4 = math.hypot(cx - dx, cy - dy)
        self.th0 = math.atan2(dy - ay, dx - ax)
        beta = math.atan2(cy - by, cx - bx)
        # The coupler point in the coupler's frame (along B->C, and across it).
        ex, ey = px - bx, py - by
        self.rcx = ex * math.cos(beta) + ey * math.sin(beta)
        self.rcy = -ex * math.sin(beta) + ey * math.cos(beta)
        # The assembly mode: the side of C from the line B->D.
        self.side = math.copysign(1.0, cross((dx - bx, dy - by), (cx - bx, cy - by)))
        self.theta0 = math.atan2(by - ay, bx - ax)

    def point(self, theta):
        """The coupler point at the world crank angle theta, None where it cannot assemble."""
        bx, by = self.a[0] + self.r2 * math.cos(theta), self.a[1] + self.r2 * math.sin(theta)
        dx, dy = self.d[0] - bx, self.d[1] - by
        l = math.hypot(dx, dy)
        if l == 0.0:
            return None
        # Circle intersection: C at distance r3 from B and r4 from D, on the design's side.
        x = (self.r3 ** 2 - self.r4 ** 2 + l * l) / (2 * l)
        h2 = self.r3 ** 2 - x * x
        if h2 < 0:
            return None
        h = self.side * math.sqrt(h2)
        ux, uy = dx / l, dy / l
        cx, cy = bx + x * ux - h * uy, by + x * uy + h * ux
        beta = math.atan2(cy - by, cx - bx)
        cb, sb = math.cos(beta), math.sin(beta)
        return (bx + self.rcx * cb - self.rcy * sb, by + self.rcx * sb + self.rcy * cb)

    def within(self, links, coords):
        ok = all(links[0] <= r <= links[1] for r in (self.r1, self.r2, self.r3, self.r4))
        return ok and all(coords[0] <= c <= coords[1] for c in (self.rcx, self.rcy, *self.a))


def timed_sse(fb, targets, crank):
    total = 0.0
    for (tx, ty), c in zip(targets, crank):
        p = fb.point(fb.theta0 + c - crank[0])
        if p is None:
            return math.inf
        total += (p[0] - tx) ** 2 + (p[1] - ty) ** 2
    return total


def untimed_sse(fb, targets, n=36000):
    curve = [p for p in (fb.point(2 * math.pi * k / n) for k in range(n)) if p is not None]
    if not curve:
        return math.inf
    return sum(min((x - tx) ** 2 + (y - ty) ** 2 for x, y in curve) for tx, ty in targets)


def main():
    print(f"pylinkage {pylinkage.__version__}")
    print("case | designs returned | best sum of squares | reaching threshold | within bounds | wall time")
    for (name, c), grashof in [(item, g) for g in (True, False) for item in CASES.items()]:
        name = f"{name} (require_grashof={grashof})"
        clock = time.perf_counter()
        if c["crank"] is None:
            result = path_generation(c["targets"], require_grashof=grashof)
        else:
            result = path_generation_with_timing(c["targets"], c["crank"], require_grashof=grashof)
        elapsed = time.perf_counter() - clock
        scores = []
        for s in result.raw_solutions:
            if s.coupler_point is None:
                continue
            fb = FourBar(s)
            e = timed_sse(fb, c["targets"], c["crank"]) if c["crank"] else untimed_sse(fb, c["targets"])
            scores.append((e, fb.within(c["links"], c["coords"]), fb))
        scores.sort(key=lambda t: t[0])
        best = scores[0][0] if scores else math.inf
        reached = sum(1 for e, _, _ in scores if e <= c["threshold"])
        inside = sum(1 for _, w, _ in scores if w)
        print(f"{name} | {len(scores)} | {best:.6e} | {reached} at <= {c['threshold']:g} | {inside} | "
              f"{elapsed:.2f} s (search) | warnings: {result.warnings[:2]}")
        if scores:
            e, w, fb = scores[0]
            print(f"    best: r1={fb.r1:.6g} r2={fb.r2:.6g} r3={fb.r3:.6g} r4={fb.r4:.6g} "
                  f"rcx={fb.rcx:.6g} rcy={fb.rcy:.6g} x0={fb.a[0]:.6g} y0={fb.a[1]:.6g} "
                  f"th0={fb.th0:.6g}, within bounds {w}")


if __name__ == "__main__":
    main()
