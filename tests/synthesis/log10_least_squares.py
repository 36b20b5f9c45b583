"""The 40-digit reference of `tests/synthesis/seeds.rs`'s least-squares function generator.

Freudenstein's log10 generator over seven evenly spaced points x = 1, 7/6, ..., 2 (input
60 deg + 90 deg (x - 1), output 90 deg + 90 deg log10(x) / log10(2)), ground link d = 1: no
design meets every point, so the optimum of the output angles' residuals is a least-squares
one. Gauss-Newton at 40 digits on the output angle in closed form, psi = arg(P) + s acos((|P|^2 +
c^2 - b^2) / 2 c |P|), P = a e^{i phi} - d, from a start near the optimum (the assembly mode s of
that start), until a step is below 1e-32; it prints the optimum links, the residual norm and the
Jacobian's singular values (the tolerances' argument in the test).

    python3 -m venv /tmp/venv && /tmp/venv/bin/pip install mpmath
    /tmp/venv/bin/python tests/synthesis/log10_least_squares.py
"""
from mpmath import mp, mpf, cos, sin, atan2, acos, sqrt, pi, log10, matrix, lu_solve, nint, svd_r

mp.dps = 40
N = 7
POINTS = []
for k in range(N):
    x = 1 + mpf(k) / (N - 1)
    POINTS.append((pi / 3 + pi / 2 * (x - 1), pi / 2 + pi / 2 * (log10(x) / log10(2))))
D = mpf(1)


def psi_of(a, b, c, phi, sign):
    px, py = a * cos(phi) - D, a * sin(phi)
    p = sqrt(px * px + py * py)
    return atan2(py, px) + sign * acos((p * p + c * c - b * b) / (2 * c * p))


def wrap(x):
    return x - 2 * pi * nint(x / (2 * pi))


def residuals(z, sign):
    return [wrap(psi_of(z[0], z[1], z[2], phi, sign) - psi) for phi, psi in POINTS]


def jacobian(z, sign):
    h = mpf(10) ** -18
    cols = []
    for i in range(3):
        zp, zm = list(z), list(z)
        zp[i] += h
        zm[i] -= h
        cols.append([(p - m) / (2 * h) for p, m in zip(residuals(zp, sign), residuals(zm, sign))])
    return matrix([[cols[i][k] for i in range(3)] for k in range(N)])


# A start near the optimum, on the assembly mode whose first output angle is near 89.84 deg.
z = [mpf("3.39"), mpf("1.90"), mpf("4.71")]
sign = 1 if abs(psi_of(*z, POINTS[0][0], 1) - POINTS[0][1]) < abs(psi_of(*z, POINTS[0][0], -1) - POINTS[0][1]) else -1
for _ in range(200):
    r, j = matrix(residuals(z, sign)), jacobian(z, sign)
    dz = lu_solve(j.T * j, -(j.T * r))
    z = [z[i] + dz[i] for i in range(3)]
    if max(abs(v) for v in dz) < mpf(10) ** -32:
        break
print("links a, b, c:", [mp.nstr(v, 25) for v in z])
print("residual norm:", mp.nstr(sqrt(sum(v * v for v in residuals(z, sign))), 25))
print("singular values:", [mp.nstr(v, 6) for v in svd_r(jacobian(z, sign), compute_uv=False)])
