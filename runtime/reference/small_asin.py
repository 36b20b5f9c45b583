"""Coefficients of `small_asin` in runtime/src/trig.rs, and their error.

`asin x = x + x^3 p(x^2)` on |x| <= ANCHOR_RANGE: `p` is the Chebyshev approximation (near
minimax) of `(asin x - x) / x^3` as a polynomial in `t = x^2` on [0, ANCHOR_RANGE^2], computed with
mpmath at 50 digits. The error printed is that of the polynomial with its coefficients rounded to
doubles, evaluated exactly, on a grid of 4000 points of the range: what the Rust code's
polynomial adds to the rounding of its own evaluation.

    python3 -m venv /tmp/venv && /tmp/venv/bin/pip install mpmath
    /tmp/venv/bin/python runtime/reference/small_asin.py 8 5     # 1/ANCHOR_RANGE, degree in t
"""

import sys

import mpmath as mp

mp.mp.dps = 50


def p_exact(t):
    """(asin x - x) / x^3 at t = x^2 (its limit 1/6 at 0)."""
    if t == 0:
        return mp.mpf(1) / 6
    x = mp.sqrt(t)
    return (mp.asin(x) - x) / x**3


def main():
    inverse_range = int(sys.argv[1]) if len(sys.argv) > 1 else 8
    degree = int(sys.argv[2]) if len(sys.argv) > 2 else 5
    r = mp.mpf(1) / inverse_range
    poly, _ = mp.chebyfit(p_exact, [0, r * r], degree + 1, error=True)
    coeffs = [float(c) for c in poly]  # highest degree first, rounded to doubles
    worst = mp.mpf(0)
    for i in range(1, 4001):
        x = r * i / 4000
        t = x * x
        p = mp.mpf(0)
        for c in coeffs:
            p = p * t + mp.mpf(c)
        worst = max(worst, abs(x + x**3 * p - mp.asin(x)))
    print(f"|x| <= 1/{inverse_range}, p of degree {degree} in x^2: largest error {mp.nstr(worst, 3)}")
    print("coefficients from t^0:", ", ".join(repr(c) for c in reversed(coeffs)))


if __name__ == "__main__":
    main()
