"""High-precision references for the classical synthesis tests (50 significant digits, mpmath).

Independent of kinloop and of the formulations the library uses:

* freudenstein_log10.csv -- y = log10(x), 1 <= x <= 2, mapped onto the input angle
  phi = 60 deg + 90 deg * (x - 1) and the output angle psi = 90 deg + 90 deg * log10(x) / log10(2).
  The three Chebyshev precision points, the 3x3 system of Freudenstein's equation solved by
  mpmath's LU at 50 digits, the link lengths (ground 1), then the output angle of that linkage
  at 11 arguments x, found by solving the two loop-closure equations (not Freudenstein's
  equation) with mpmath's Newton from the ideal angle. Then the same at 6 evenly spaced points
  in the least-squares sense (mpmath's QR), with the residual's 2-norm.
* burmester_five_poses.csv -- five poses of the coupler of a known four-bar (written with 17
  significant digits, then read back, so that the problem solved here is exactly the one the
  test solves), and every Burmester pair (center point, circle point in the first pose) found
  by solving the Cartesian conditions |k_j - M| = |k_1 - M|, j = 2..5 (k_j the circle point
  carried with the body into pose j), with mpmath's Newton from 300 pseudo-random starts.

Run: python3 generate.py   (writes the CSV files beside it)
"""
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


def burmester(rows):
    x1, y1, t1 = rows[0]

    def carried(kx, ky, j):
        xj, yj, tj = rows[j]
        dt = tj - t1
        rx, ry = kx - x1, ky - y1
        return xj + rx * cos(dt) - ry * sin(dt), yj + rx * sin(dt) + ry * cos(dt)

    def eqs(mx, my, kx, ky):
        r1 = (kx - mx) ** 2 + (ky - my) ** 2
        out = []
        for j in range(1, 5):
            qx, qy = carried(kx, ky, j)
            out.append((qx - mx) ** 2 + (qy - my) ** 2 - r1)
        return out

    rng = random.Random(7)
    found = []
    for _ in range(300):
        start = [mpf(rng.uniform(-12, 12)) for _ in range(4)]
        try:
            sol = findroot(eqs, start, tol=mpf(10) ** -45, maxsteps=60)
        except (ValueError, ZeroDivisionError):
            continue
        mx, my, kx, ky = sol
        if max(abs(v) for v in (mx, my, kx, ky)) > 1e6:
            continue
        radius = sqrt((kx - mx) ** 2 + (ky - my) ** 2)
        if radius < mpf(10) ** -20:
            continue
        if all(max(abs(mx - f[0]), abs(my - f[1])) > mpf(10) ** -30 for f in found):
            found.append((mx, my, kx, ky))
    return sorted(found, key=lambda f: (f[0], f[1]))


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
    print("known pivots (A, B in pose 1, D):", [(nstr(x, 12), nstr(y, 12)) for x, y in known])


main()
