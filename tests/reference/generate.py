"""High-precision references for tests/kinematics/reference_mpmath.rs (50 significant digits, mpmath).

Independent of kinloop: each mechanism's loop equations are written out here by hand, solved by
mpmath's multidimensional Newton (findroot) at 50 digits, and differentiated along the input by
central differences at 50 digits (h = 1e-12: truncation ~h^2 = 1e-24, cancellation ~1e-50/h^2 =
1e-26). Positions, velocity and acceleration analogs of the unknowns and of the points are written
with 17 significant digits, one row per input value, continuing the branch from row to row.

The gear-lever drive, the slotted lever, the two cam linkages and the roller edger are continued
from row to row through 16 substeps (`march`), so that each row stays on the branch of the first.

The five-bar has two inputs: its rows hold both, its first analogs by each input (th1 then th2
for each quantity) and its second analogs by the pairs (th1, th1), (th1, th2), (th2, th2), the
cross one by the four-point stencil (f(+h, +h) - f(+h, -h) - f(-h, +h) + f(-h, -h)) / 4h^2
(truncation ~h^2, cancellation ~1e-50/h^2, as above).

Run: python3 tests/reference/generate.py [name ...]   (writes tests/reference/<name>.csv, every
mechanism's without names)
"""
import os
import sys
from mpmath import mp, mpf, cos, sin, pi, findroot, matrix

mp.dps = 50
H = mpf("1e-12")
HERE = os.path.dirname(os.path.abspath(__file__))


def e(angle):
    return cos(angle), sin(angle)


def four_bar():
    a, b, c, d, p, alpha = mpf(1), mpf(3), mpf("2.5"), mpf("3.2"), mpf("1.5"), mpf("0.6")

    def loops(q, phi):
        beta, gamma = q
        return [a * cos(phi) + b * cos(beta) - d - c * cos(gamma), a * sin(phi) + b * sin(beta) - c * sin(gamma)]

    def points(q, phi):
        beta, _ = q
        return [a * cos(phi) + p * cos(beta + alpha), a * sin(phi) + p * sin(beta + alpha)]

    return "four_bar", loops, points, [0.5, 1.5], [2 * pi * k / 24 for k in range(25)]


def short_rocker_four_bar():
    # A crank-rocker whose rocker is a twelfth of its coupler: the coupler's end C stays within
    # 0.25 of the rocker's pivot D, so the angle at B between B -> D and the coupler is below
    # 3 degrees over the whole turn (where the dyad's root, taken from its coefficients alone,
    # loses digits to the cancellation of a^2 + b^2 - c^2).
    a, b, c, d = mpf("0.2"), mpf(3), mpf("0.25"), mpf(3)

    def loops(q, phi):
        beta, gamma = q
        return [a * cos(phi) + b * cos(beta) - d - c * cos(gamma), a * sin(phi) + b * sin(beta) - c * sin(gamma)]

    def points(q, phi):
        return []

    return "short_rocker_four_bar", loops, points, [0.05, 1.0], [2 * pi * k / 24 for k in range(25)]


def slider_crank():
    r, l, ecc = mpf(1), mpf(3), mpf("0.5")

    def loops(q, phi):
        psi, x = q
        return [r * cos(phi) + l * cos(psi) - x, r * sin(phi) + l * sin(psi) - ecc]

    def points(q, phi):
        return []

    return "slider_crank", loops, points, [0.1, 3.9], [2 * pi * k / 24 for k in range(25)]


def watt_six_bar():
    a, b, c, d = mpf(1), mpf(3), mpf("2.5"), mpf("3.2")
    c2, delta, e5, f6, gx, gy = mpf(2), mpf("0.5"), mpf("3.5"), mpf("2.5"), mpf(6), mpf(1)

    def loops(q, phi):
        beta, gamma, th5, th6 = q
        return [
            a * cos(phi) + b * cos(beta) - d - c * cos(gamma),
            a * sin(phi) + b * sin(beta) - c * sin(gamma),
            d + c2 * cos(gamma + delta) + e5 * cos(th5) - gx - f6 * cos(th6),
            c2 * sin(gamma + delta) + e5 * sin(th5) - gy - f6 * sin(th6),
        ]

    def points(q, phi):
        beta, gamma, th5, th6 = q
        return [d + c2 * cos(gamma + delta) + e5 * cos(th5), c2 * sin(gamma + delta) + e5 * sin(th5)]

    return "watt_six_bar", loops, points, [0.5, 1.5, 0.3, 1.6], [2 * pi * k / 24 for k in range(25)]


def class_four():
    oa, xb, yb, ac, ae, alpha_a = mpf(1), mpf("4.4"), mpf("0.6"), mpf("2.3"), mpf("2.4"), mpf("0.84")
    bd, bf, alpha_b, cd, ef = mpf("1.6"), mpf("3.5"), mpf("0.62"), mpf(2), mpf("3.4")

    def loops(q, phi):
        th1, th2, psi1, psi2 = q
        ax, ay = oa * cos(phi), oa * sin(phi)
        return [
            ax + ac * cos(th1) + cd * cos(psi1) - xb - bd * cos(th2),
            ay + ac * sin(th1) + cd * sin(psi1) - yb - bd * sin(th2),
            ax + ae * cos(th1 + alpha_a) + ef * cos(psi2) - xb - bf * cos(th2 + alpha_b),
            ay + ae * sin(th1 + alpha_a) + ef * sin(psi2) - yb - bf * sin(th2 + alpha_b),
        ]

    def points(q, phi):
        th1, th2, psi1, psi2 = q
        return [oa * cos(phi) + ac * cos(th1), oa * sin(phi) + ac * sin(th1)]

    return "class_four", loops, points, [1.4, 3.0, -0.8, -1.0], [2 * pi * k / 24 for k in range(25)]


def rhombic_drive():
    # The crank of the second rod is set gamma ahead: its sine and cosine are a sum of angles.
    # Its unknowns come first, as the test declares them.
    r_p, r_b, l_p, l_b = mpf(1), mpf("1.2"), mpf(3), mpf("3.5")
    e_p, de, gamma = mpf("0.5"), mpf("0.9"), mpf("0.7")

    def loops(q, phi):
        phi4, x_f, phi2, x_c = q
        return [
            r_b * cos(phi + gamma) - x_f - l_b * cos(phi4),
            e_p + r_b * sin(phi + gamma) - de - l_b * sin(phi4),
            r_p * cos(phi) - x_c - l_p * cos(phi2),
            e_p + r_p * sin(phi) - l_p * sin(phi2),
        ]

    def points(q, phi):
        return []

    return "rhombic_drive", loops, points, [pi, 3.5, 0, -3], [2 * pi * k / 24 for k in range(25)]


def five_bar():
    # Two cranks, a at the origin (th1) and e at (d, 0) (th2), links b from B and c from D
    # meeting at C. The inputs run along the line th2 = th1 - pi + 0.3 over a turn, where the
    # distance |BD| stays within [0.67, 3.68], away from |b - c| = 0.3 and b + c = 4.7 (the
    # links folded or stretched): one branch all the way round, the one findroot reaches from
    # the guess (1, 2) at the first inputs (C right of B -> D).
    a, b, c, d, e_ = mpf(1), mpf("2.5"), mpf("2.2"), mpf("1.5"), mpf("1.2")

    def loops(q, x):
        phi2, phi3 = q
        th1, th2 = x
        return [
            a * cos(th1) + b * cos(phi2) - d - e_ * cos(th2) - c * cos(phi3),
            a * sin(th1) + b * sin(phi2) - e_ * sin(th2) - c * sin(phi3),
        ]

    def points(q, x):
        phi2, _ = q
        th1, _ = x
        return [a * cos(th1) + b * cos(phi2), a * sin(th1) + b * sin(phi2)]

    inputs = [[2 * pi * k / 24, 2 * pi * k / 24 - pi + mpf("0.3")] for k in range(25)]
    return "five_bar", loops, points, [1.0, 2.0], inputs


def gear_lever():
    # The gear-lever drive: the planet pin, the sum of the carrier's and the planet's arms
    # (angles from the Y axis: direction a is (sin a, cos a)), slides in a rocker pivoted at the
    # origin; unknowns the pin's distance s and the rocker's angle phi (polar coordinates of the
    # pin, one block). The pin stays between l_c - l_p and l_c + l_p from the pivot; the rocker
    # turns once a carrier turn, with three stops.
    l_c, l_p, u = mpf(2), mpf("1.3"), mpf(3)

    def pin(alpha):
        return [l_c * sin(alpha) + l_p * sin((1 - u) * alpha), l_c * cos(alpha) + l_p * cos((1 - u) * alpha)]

    def loops(q, alpha):
        s, phi = q
        x, y = pin(alpha)
        return [x - s * sin(phi), y - s * cos(phi)]

    def points(q, alpha):
        return pin(alpha)

    return "gear_lever", loops, points, [3.3, 0], [2 * pi * k / 72 for k in range(73)]


def slotted_lever():
    # Slotted-lever quick return: the crank pin (r at phi about the origin) slides in a rocker
    # pivoted at (0, -d), at s from the pivot, rocker angle theta; the rocker's tip at l.
    r, d, l_tip = mpf(1), mpf(2), mpf(4)

    def loops(q, phi):
        s, theta = q
        return [r * cos(phi) - s * cos(theta), r * sin(phi) + d - s * sin(theta)]

    def points(q, phi):
        _, theta = q
        return [l_tip * cos(theta), -d + l_tip * sin(theta)]

    return "slotted_lever", loops, points, [2.24, 1.1], [2 * pi * k / 24 for k in range(25)]


def cam_linkage():
    # Disc cam (centre at e from the shaft) with a roller follower on a bell-crank rocker
    # pivoted at A, whose second arm drives a slider on the line y = h through a rod: the cam
    # pair is the four-bar O C P A (loop `cam`), the rod and slider a slider-crank on the
    # rocker's second arm (loop `rod`). Millimetres. Outputs: C, P, Q and the pressure angle.
    e_, r_cam, r_roller, a_x, a_y, l_arm = mpf(10), mpf(40), mpf(12), mpf(0), mpf(80), mpf(60)
    l_out, delta, l_rod, h = mpf(50), 140 * pi / 180, mpf(150), mpf(130)

    def loops(q, phi):
        beta, psi, gamma, x = q
        return [
            e_ * cos(phi) + (r_cam + r_roller) * cos(beta) - a_x - l_arm * cos(psi),
            e_ * sin(phi) + (r_cam + r_roller) * sin(beta) - a_y - l_arm * sin(psi),
            a_x + l_out * cos(psi + delta) + l_rod * cos(gamma) - x,
            a_y + l_out * sin(psi + delta) + l_rod * sin(gamma) - h,
        ]

    def points(q, phi):
        beta, psi, _, _ = q
        return [
            e_ * cos(phi), e_ * sin(phi),
            a_x + l_arm * cos(psi), a_y + l_arm * sin(psi),
            a_x + l_out * cos(psi + delta), a_y + l_out * sin(psi + delta),
            beta - psi - pi / 2,
        ]

    return "cam_linkage", loops, points, [0.85, -0.75, 0, 160], [2 * pi * k / 24 for k in range(25)]


def harmonic_cam_rocker():
    # A translating follower lifted by the double-harmonic law s(phi) drives a rocker pivoted at
    # D through a rod: one dyad whose base point moves by an explicit function of the input.
    lift, y0, l_rod, c, d_x, d_y = mpf(20), mpf(60), mpf(70), mpf(40), mpf(-40), mpf(140)

    def lifted(phi):
        return y0 + lift / 2 * ((1 - cos(phi)) - (1 - cos(2 * phi)) / 4)

    def loops(q, phi):
        gamma, psi = q
        return [l_rod * cos(gamma) - d_x - c * cos(psi), lifted(phi) + l_rod * sin(gamma) - d_y - c * sin(psi)]

    def points(q, phi):
        _, psi = q
        return [mpf(0), lifted(phi), d_x + c * cos(psi), d_y + c * sin(psi)]

    return "harmonic_cam_rocker", loops, points, [1.6, -0.25], [2 * pi * k / 24 for k in range(25)]


def roller_edger():
    # The roller edger (time input t, seconds): cylinder 1 of length v1 t + l1 and link 3 close
    # contour 1 with the frame l5 at alpha (a dyad whose first link's length moves with the
    # input); cylinder 2 (fixed length s2 + l2) and link 4 close contour 2 with link 3 and the
    # frame l6 at beta. Metres.
    l1, l3, l5, alpha, v1 = mpf("0.9"), mpf("0.6"), mpf("1.2"), mpf("0.2"), mpf("0.05")
    l2, s2, l4, l6, beta = mpf(1), mpf("0.1"), mpf("0.7"), mpf("1.4"), mpf("0.9")

    def loops(q, t):
        phi1, phi3, phi2, phi4 = q
        s1 = v1 * t + l1
        return [
            s1 * cos(phi1) + l3 * cos(phi3) - l5 * cos(alpha),
            s1 * sin(phi1) + l3 * sin(phi3) - l5 * sin(alpha),
            (s2 + l2) * cos(phi2) + l4 * cos(phi4) + l3 * cos(phi3) - l6 * cos(beta),
            (s2 + l2) * sin(phi2) + l4 * sin(phi4) + l3 * sin(phi3) - l6 * sin(beta),
        ]

    def points(q, t):
        return []

    return "roller_edger", loops, points, [1.2, -0.8, 2.0, 0.5], [mpf(6) * k / 24 for k in range(25)]


def solve(loops, phi, guess):
    q = findroot(lambda *q: loops(list(q), phi), [mpf(g) for g in guess], tol=mpf(10) ** -45, maxsteps=200)
    q = [q] if not isinstance(q, matrix) else [q[i] for i in range(len(guess))]
    res = max(abs(v) for v in loops(q, phi))
    assert res < mpf(10) ** -40, res
    return q


def row(loops, points, phi, guess):
    q0 = solve(loops, phi, guess)
    qp = solve(loops, phi + H, q0)
    qm = solve(loops, phi - H, q0)
    p0, pp, pm = points(q0, phi), points(qp, phi + H), points(qm, phi - H)
    dq = [(a - b) / (2 * H) for a, b in zip(qp, qm)]
    d2q = [(a - 2 * m + b) / H**2 for a, m, b in zip(qp, q0, qm)]
    dp = [(a - b) / (2 * H) for a, b in zip(pp, pm)]
    d2p = [(a - 2 * m + b) / H**2 for a, m, b in zip(pp, p0, pm)]
    return q0, [phi] + q0 + dq + d2q + p0 + dp + d2p


def row2(loops, points, x, guess):
    """`row` for two inputs: analogs by each input and by each pair of inputs."""
    q0 = solve(loops, x, guess)
    p0 = points(q0, x)

    def at(d1, d2):
        y = [x[0] + d1 * H, x[1] + d2 * H]
        q = solve(loops, y, q0)
        return q + points(q, y)

    f0 = q0 + p0
    plus, minus = [at(1, 0), at(0, 1)], [at(-1, 0), at(0, -1)]
    pp, pm, mp_, mm = at(1, 1), at(1, -1), at(-1, 1), at(-1, -1)
    first = [[(plus[i][k] - minus[i][k]) / (2 * H) for i in range(2)] for k in range(len(f0))]
    second = []
    for k in range(len(f0)):
        d11 = (plus[0][k] - 2 * f0[k] + minus[0][k]) / H**2
        d12 = (pp[k] - pm[k] - mp_[k] + mm[k]) / (4 * H**2)
        d22 = (plus[1][k] - 2 * f0[k] + minus[1][k]) / H**2
        second.append([d11, d12, d22])
    n = len(q0)
    values = list(x) + q0 + sum(first[:n], []) + sum(second[:n], [])
    values += p0 + sum(first[n:], []) + sum(second[n:], [])
    return q0, values


# Substeps of the continuation from one row's input to the next (the row's solve then starts
# from the last substep's root), for the mechanisms whose unknowns move far between rows: the
# gear-lever's rocker swings through most of a turn where the pin passes nearest its pivot.
MARCH = 16


def march(loops, q, frm, to):
    for k in range(1, MARCH):
        q = solve(loops, frm + (to - frm) * k / MARCH, q)
    return q


def main():
    wanted = sys.argv[1:]
    one_input = [four_bar(), short_rocker_four_bar(), slider_crank(), watt_six_bar(), class_four(), rhombic_drive()]
    marched = [gear_lever(), slotted_lever(), cam_linkage(), harmonic_cam_rocker(), roller_edger()]
    for name, loops, points, guess, angles in one_input + marched:
        if wanted and name not in wanted:
            continue
        n, npts = len(guess), len(points([mpf(g) for g in guess], mpf(0)))
        header = ["phi"] + [f"q{u}" for u in range(n)] + [f"dq{u}" for u in range(n)] + [f"d2q{u}" for u in range(n)]
        header += [f"p{k}" for k in range(npts)] + [f"dp{k}" for k in range(npts)] + [f"d2p{k}" for k in range(npts)]
        lines = [",".join(header)]
        q, last = guess, None
        for phi in angles:
            if name in [m[0] for m in marched] and last is not None:
                q = march(loops, q, last, phi)
            q, values = row(loops, points, phi, q)
            last = phi
            lines.append(",".join(mp.nstr(v, 17, min_fixed=0, max_fixed=0) for v in values))
        with open(os.path.join(HERE, f"{name}.csv"), "w") as out:
            out.write("\n".join(lines) + "\n")
        print(name, len(lines) - 1, "rows")
    for name, loops, points, guess, inputs in [five_bar()]:
        if wanted and name not in wanted:
            continue
        n, npts = len(guess), len(points([mpf(g) for g in guess], inputs[0]))
        pairs = ["11", "12", "22"]
        header = ["th1", "th2"] + [f"q{u}" for u in range(n)] + [f"dq{u}_{i}" for u in range(n) for i in "12"]
        header += [f"d2q{u}_{p}" for u in range(n) for p in pairs] + [f"p{k}" for k in range(npts)]
        header += [f"dp{k}_{i}" for k in range(npts) for i in "12"] + [f"d2p{k}_{p}" for k in range(npts) for p in pairs]
        lines = [",".join(header)]
        q = guess
        for x in inputs:
            q, values = row2(loops, points, x, q)
            lines.append(",".join(mp.nstr(v, 17, min_fixed=0, max_fixed=0) for v in values))
        with open(os.path.join(HERE, f"{name}.csv"), "w") as out:
            out.write("\n".join(lines) + "\n")
        print(name, len(lines) - 1, "rows")


if __name__ == "__main__":
    main()
