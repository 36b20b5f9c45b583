"""References of the tests of an angle parameter beyond `largest_precise_angle` (`errors.rs`):
the class IV group of `kinloop_fixtures::CLASS_FOUR_TEXT` at phi = 0.5, its loops written out
here and solved in mpmath at 50 digits (120 about 1e80), independent of kinloop.

Run: python3 imprecise_angle_param.py (mpmath). Printed:
    1e80 mod 2pi = 1.9356985871207545587
    residuals of the answer returned before at alpha_b = 1e80: ['8.51213e-16', '-1.90908e-16', '-4.52387', '2.03454']
    q at alpha_b = 4.5e6: ['1.1172053298592558', '1.932314203432634', '-0.22708177666037728', '-1.2387915261821983']
    dq/dalpha_b: ['-0.607197', '-1.02264', '0.611031', '-0.427772']
"""
from mpmath import mp, mpf, cos, sin, pi, findroot, fmod

mp.dps = 50
oa, xb, yb, ac, ae, aa, bd, bf, cd, ef = [mpf(v) for v in "1.0 4.4 0.6 2.3 2.4 0.84 1.6 3.5 2.0 3.4".split()]


def res(phi, ab, q):
    th1, th2, p1, p2 = q
    ax, ay = oa * cos(phi), oa * sin(phi)
    return [ax + ac * cos(th1) + cd * cos(p1) - xb - bd * cos(th2),
            ay + ac * sin(th1) + cd * sin(p1) - yb - bd * sin(th2),
            ax + ae * cos(th1 + aa) + ef * cos(p2) - xb - bf * cos(th2 + ab),
            ay + ae * sin(th1 + aa) + ef * sin(p2) - yb - bf * sin(th2 + ab)]


def solve(phi, ab, start):
    q = findroot(lambda a, b, c, d: res(phi, ab, [a, b, c, d]), start)
    return [q[i] for i in range(4)]


phi = mpf(0.5)
# The double 1e80, exactly; the positions `kinloop solve --params alpha_b=1e80 --at 0.5` gave
# before the parameter was refused (the equations solved were those with `th2 + alpha_b` rounded
# to `alpha_b`).
# At 120 digits, so that `th2 + 1e80` keeps th2 to 40 digits (at 50 it would lose it as doubles do).
mp.dps = 120
big = mpf(1e80)
print("1e80 mod 2pi =", mp.nstr(fmod(big, 2 * pi), 20))
old = [mpf(v) for v in "-0.8431306081456537 4.708112988230118 0.11931583182504016 1.608032511190894".split()]
print("residuals of the answer returned before at alpha_b = 1e80:", [mp.nstr(v, 6) for v in res(phi, big, old)])

mp.dps = 50
A = mpf(4.5e6)
q = solve(phi, A, [mpf(1.4), mpf(3.0), mpf(-0.8), mpf(-1.0)])  # from the declared guess
print("q at alpha_b = 4.5e6:", [mp.nstr(v, 17) for v in q])
h = mpf("1e-20")
qp, qm = solve(phi, A + h, q), solve(phi, A - h, q)
print("dq/dalpha_b:", [mp.nstr((x - y) / (2 * h), 6) for x, y in zip(qp, qm)])
