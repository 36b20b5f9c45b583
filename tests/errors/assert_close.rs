//! The tests' own `assert_close!` (`tests/support/`): it fails where the difference reaches the
//! tolerance (or passes the bound of the inclusive form) or is NaN, and its message carries the
//! label, both values, the difference and the tolerance, so that a failing check elsewhere says
//! what it compared.

use crate::support::tol;

#[test]
fn passes_within_the_tolerance_in_both_forms() {
    assert_close!(1.0 + 0.5e-12, 1.0, tol::SOLVE);
    assert_close!(-2.0, -2.0 - 1e-15, tol::ULPS, "a label with {}", "arguments");
    // Relative: 1e-9 of 1000 admits 1e-6; absolute (1e-9) below 1 in magnitude.
    assert_close!(1000.0 + 5e-7, 1000.0, rel = tol::FD_FIRST);
    assert_close!(0.5e-9, 0.0, rel = tol::FD_FIRST, "near zero");
}

#[test]
#[should_panic(expected = "crank angle: expected 1e0, actual 1.5e0, difference 5e-1, tolerance 2.5e-1")]
fn fails_beyond_the_tolerance_with_its_context() {
    assert_close!(1.5, 1.0, 0.25, "crank angle");
}

#[test]
#[should_panic(expected = "at 3: expected 5e-1, actual 7.5e-1, difference 2.5e-1, tolerance 2.5e-1")]
fn fails_at_the_tolerance_itself() {
    // The difference must stay below the tolerance (binary fractions: no rounding here).
    assert_close!(0.75, 0.5, 0.25, "at {}", 3);
}

#[test]
#[should_panic(expected = "actual NaN")]
fn fails_on_nan() {
    assert_close!(f64::NAN, 0.0, 1.0);
}

#[test]
#[should_panic(expected = "x_c: expected 2e3, actual 2.004e3, difference 4e0, tolerance 1e-3 relative (2e0 absolute)")]
fn the_relative_form_fails_beyond_its_scaled_tolerance() {
    let x_c = 2004.0;
    assert_close!(x_c, 2000.0, rel = 1e-3);
}

#[test]
fn the_inclusive_form_admits_the_bound_itself() {
    // 0.75 - 0.5 is exactly 0.25: inside `<= 0.25`, outside `< 0.25` (above).
    assert_close!(0.75, 0.5, <= 0.25, "at the bound");
}

#[test]
#[should_panic(expected = "beyond: expected 5e-1, actual 1e0, difference 5e-1, tolerance 2.5e-1 (inclusive)")]
fn the_inclusive_form_fails_beyond_the_bound() {
    assert_close!(1.0, 0.5, <= 0.25, "beyond");
}
