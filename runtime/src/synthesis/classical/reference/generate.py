"""High-precision references for the classical synthesis tests (50 significant digits, mpmath).

Independent of kinloop and of the formulations the library uses:

* freudenstein_log10.csv -- y = log10(x), 1 <= x <= 2, mapped onto the input angle
  phi = 60 deg + 90 deg * (x - 1) and the output angle psi = 90 deg + 90 deg * log10(x) / log10(2).
  The three Chebyshev precision points, the 3x3 system of Freudenstein's equation solved by
  mpmath's LU at 50 digits, the link lengths (ground 1), then the output angle of that linkage
  at 11 arguments x, found by solving the two loop-closure equations (not Freudenstein's
  equation) with mpmath's Newton from the ideal angle. Then the same at 6 evenly spaced points
  in the least-squares sense (mpmath's QR), with the residual's 2-norm.
* burmester_random.csv -- twelve problems of five poses drawn from a seeded generator (points
  in [-2, 2]^2, angles in [-1.5, 1.5] rad; not made by any linkage), each with every Burmester
  pair found as above from 2000 starts at three scales. Four pairs means every one was found (no
  more exist); fewer can in principle mean a missed far one, which the test would show as a
  disagreement in count.
* burmester_five_poses.csv -- five poses of the coupler of a known four-bar (written with 17
  significant digits, then read back, so that the problem solved here is exactly the one the
  test solves), and every Burmester pair (center point, circle point in the first pose) found
  by solving the Cartesian conditions |k_j - M| = |k_1 - M|, j = 2..5 (k_j the circle point
  carried with the body into pose j): Newton's method in doubles from 300 pseudo-random
  starts, each converged one polished by mpmath's Newton at 50 digits.

Run: python3 generate.py   (writes the CSV files beside it)
"""
import math
import os
import random
from mpmath import mp, mpf, cos, sin, pi, log10, sqrt, atan2, matrix, lu_solve, qr_solve, findroot, nstr

mp.dps = 50
HERE = os.path.dirname(os.path.abspath(__file__))
DEG = pi / 180


def s(x):
    return nstr(x, 17)


def freudenstein(points):
    rows = [[cos(psi), -cos(phi), mpf(1)] for phi, psi in points]
    rhs = [cos(phi - psi) for phi, psi in points]
    if len(points) == 3:
        k = lu_solve(matrix(rows), matrix(rhs))
        res = mpf(0)
    else:
        k, res = qr_solve(matrix(rows), matrix(rhs))
    a, c = 1 / k[0], 1 / k[1]
    b = sqrt(a * a + c * c + 1 - 2 * a * c * k[2])
    return k, (a, b, c), res


def output_angle(links, phi, psi_guess):
    a, b, c = links
    d = mpf(1)

    def loop(theta, psi):
        return [a * cos(phi) + b * cos(theta) - d - c * cos(psi), a * sin(phi) + b * sin(theta) - c * sin(psi)]

    # coupler angle guess from the ideal output point
    cx, cy = d + c * cos(psi_guess), c * sin(psi_guess)
    theta_guess = atan2(cy - a * sin(phi), cx - a * cos(phi))
    theta, psi = findroot(loop, (theta_guess, psi_guess))
    return psi


def log10_case(out):
    x0, x1 = mpf(1), mpf(2)
    phi0, dphi, psi0, dpsi = 60 * DEG, 90 * DEG, 90 * DEG, 90 * DEG
    phi = lambda x: phi0 + (x - x0) / (x1 - x0) * dphi
    psi = lambda x: psi0 + (log10(x) - log10(x0)) / (log10(x1) - log10(x0)) * dpsi
    for name, xs in [
        ("exact", [(x0 + x1) / 2 - (x1 - x0) / 2 * cos((2 * j - 1) * pi / 6) for j in (1, 2, 3)]),
        ("least_squares", [x0 + (x1 - x0) * j / 5 for j in range(6)]),
    ]:
        points = [(phi(x), psi(x)) for x in xs]
        k, links, res = freudenstein(points)
        out.append(f"{name},residual_norm,{s(res)}")
        for i, x in enumerate(xs):
            out.append(f"{name},x{i},{s(x)}")
        for i, v in enumerate(k):
            out.append(f"{name},k{i + 1},{s(v)}")
        for n, v in zip(("input", "coupler", "output"), links):
            out.append(f"{name},{n},{s(v)}")
        for j in range(11):
            x = x0 + (x1 - x0) * j / 10
            out.append(f"{name},psi_at_{j},{s(output_angle(links, phi(x), psi(x)))}")


def poses():
    """Five poses of the coupler of a four-bar placed off the axes; its two dyads are known."""
    a, b, c, d, p, gamma = mpf("1.5"), mpf(4), mpf(3), mpf(4), mpf("2.5"), mpf("0.6")
    origin, turn = (mpf("0.3"), mpf("-0.2")), mpf("0.25")

    def place(x, y):
        return origin[0] + x * cos(turn) - y * sin(turn), origin[1] + x * sin(turn) + y * cos(turn)

    rows = []
    for phi_deg in (30, 55, 80, 110, 140):
        phi = phi_deg * DEG
        bx, by = a * cos(phi), a * sin(phi)
        # C: intersection of circle(B, b) and circle(D, c), on the open closure (C above the ground)
        ex, ey = bx - d, by
        l = sqrt(ex * ex + ey * ey)
        along = (c * c - b * b + l * l) / (2 * l)
        h = sqrt(c * c - along * along)
        ux, uy = ex / l, ey / l
        cx, cy = d + along * ux + h * uy, along * uy - h * ux
        if cy < 0:
            cx, cy = d + along * ux - h * uy, along * uy + h * ux
        theta = atan2(cy - by, cx - bx)
        px, py = bx + p * cos(theta + gamma), by + p * sin(theta + gamma)
        X, Y = place(px, py)
        rows.append((mpf(s(X)), mpf(s(Y)), mpf(s(theta + turn))))
    known = [place(0, 0), place(a * cos(30 * DEG), a * sin(30 * DEG)), place(d, 0)]
    return rows, known


def burmester(rows, starts=300, scales=(12,)):
    """Every Burmester pair of five poses: Newton's method in doubles from pseudo-random starts
    (cheap, so that many starts can be tried), each converged start then polished by mpmath's
    Newton at 50 digits."""
    x1, y1, t1 = rows[0]

    def carried(kx, ky, j, c, s):
        xj, yj, tj = rows[j]
        dt = tj - t1
        rx, ry = kx - x1, ky - y1
        return xj + rx * c(dt) - ry * s(dt), yj + rx * s(dt) + ry * c(dt)

    def eqs(mx, my, kx, ky):
        r1 = (kx - mx) ** 2 + (ky - my) ** 2
        out = []
        for j in range(1, 5):
            qx, qy = carried(kx, ky, j, cos, sin)
            out.append((qx - mx) ** 2 + (qy - my) ** 2 - r1)
        return out

    frows = [(float(x), float(y), float(a)) for x, y, a in rows]

    def float_newton(v):
        for _ in range(60):
            mx, my, kx, ky = v
            f, jac = [], []
            for j in range(1, 5):
                dt = frows[j][2] - frows[0][2]
                c, s = math.cos(dt), math.sin(dt)
                rx, ry = kx - frows[0][0], ky - frows[0][1]
                qx, qy = frows[j][0] + rx * c - ry * s, frows[j][1] + rx * s + ry * c
                ux, uy, wx, wy = qx - mx, qy - my, kx - mx, ky - my
                f.append(ux * ux + uy * uy - wx * wx - wy * wy)
                # d/dM: -2u + 2w; d/dk: 2 R^T u - 2w
                jac.append([-2 * ux + 2 * wx, -2 * uy + 2 * wy, 2 * (c * ux + s * uy) - 2 * wx, 2 * (-s * ux + c * uy) - 2 * wy])
            step = solve4(jac, f)
            if step is None:
                return None
            v = [a - b for a, b in zip(v, step)]
            if max(abs(x) for x in v) > 1e7:
                return None
            if max(abs(x) for x in step) < 1e-13 * max(1.0, max(abs(x) for x in v)):
                return v
        return None

    rng = random.Random(7)
    found = []
    for n in range(starts):
        scale = scales[n % len(scales)]
        v = float_newton([rng.uniform(-scale, scale) for _ in range(4)])
        if v is None:
            continue
        try:
            sol = findroot(eqs, [mpf(x) for x in v], tol=mpf(10) ** -45, maxsteps=20)
        except (ValueError, ZeroDivisionError):
            continue
        mx, my, kx, ky = sol
        if max(abs(v) for v in (mx, my, kx, ky)) > 1e6 or max(abs(v) for v in eqs(mx, my, kx, ky)) > mpf(10) ** -30:
            continue
        radius = sqrt((kx - mx) ** 2 + (ky - my) ** 2)
        if radius < mpf(10) ** -20:
            continue
        if all(max(abs(mx - f[0]), abs(my - f[1])) > mpf(10) ** -30 for f in found):
            found.append((mx, my, kx, ky))
    return sorted(found, key=lambda f: (f[0], f[1]))


def solve4(a, b):
    """Gaussian elimination with partial pivoting on a 4x4 system; None when singular."""
    m = [row[:] + [rhs] for row, rhs in zip(a, b)]
    for col in range(4):
        piv = max(range(col, 4), key=lambda r: abs(m[r][col]))
        if abs(m[piv][col]) < 1e-300:
            return None
        m[col], m[piv] = m[piv], m[col]
        for r in range(col + 1, 4):
            f = m[r][col] / m[col][col]
            for k in range(col, 5):
                m[r][k] -= f * m[col][k]
    x = [0.0] * 4
    for r in range(3, -1, -1):
        x[r] = (m[r][4] - sum(m[r][k] * x[k] for k in range(r + 1, 4))) / m[r][r]
    return x


def random_poses():
    """The generator of the twelve random problems: a 64-bit linear congruential generator whose
    top 53 bits make a double in [0, 1)."""
    seed = 12345
    mask = (1 << 64) - 1

    def rnd():
        nonlocal seed
        seed = (seed * 6364136223846793005 + 1442695040888963407) & mask
        return float(seed >> 11) / float(1 << 53)

    problems = []
    for _ in range(12):
        poses = []
        for _ in range(5):
            x = 4.0 * rnd() - 2.0
            y = 4.0 * rnd() - 2.0
            a = 3.0 * rnd() - 1.5
            poses.append((x, y, a))
        problems.append(poses)
    return problems


def main():
    out = ["case,name,value"]
    log10_case(out)
    with open(os.path.join(HERE, "freudenstein_log10.csv"), "w") as f:
        f.write("\n".join(out) + "\n")

    rows, known = poses()
    out = ["kind,x,y,angle_or_circle_x,circle_y"]
    for x, y, t in rows:
        out.append(f"pose,{s(x)},{s(y)},{s(t)},")
    for mx, my, kx, ky in burmester(rows):
        out.append(f"burmester,{s(mx)},{s(my)},{s(kx)},{s(ky)}")
    with open(os.path.join(HERE, "burmester_five_poses.csv"), "w") as f:
        f.write("\n".join(out) + "\n")
    out = ["problem,kind,x,y,angle_or_circle_x,circle_y"]
    for i, problem in enumerate(random_poses()):
        for x, y, a in problem:
            out.append(f"{i},pose,{x!r},{y!r},{a!r},")
        rows = [(mpf(x), mpf(y), mpf(a)) for x, y, a in problem]
        for mx, my, kx, ky in burmester(rows, starts=2000, scales=(3, 15, 80)):
            out.append(f"{i},burmester,{s(mx)},{s(my)},{s(kx)},{s(ky)}")
    with open(os.path.join(HERE, "burmester_random.csv"), "w") as f:
        f.write("\n".join(out) + "\n")
    print("known pivots (A, B in pose 1, D):", [(nstr(x, 12), nstr(y, 12)) for x, y in known])


main()
