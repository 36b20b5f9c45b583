//! Grids of several inputs (`GridMotion::record`) without a browser: three inputs (a five-bar
//! whose frame length is an input too), every reachable cell's pose against the closed form and
//! one assembly mode over the whole grid; the page has a slider per input; and mistakes are
//! typed errors.

use kinloop::Mechanism;
use kinloop_viz::draw::{Draw, DrawError, GridMotion, HtmlConfig, HtmlError, MAX_GRID_CELLS, html_grid};

kinloop::mechanism! {
    /// A five-bar whose frame length `s` is a third input.
    pub struct Stretch {
        params a = 1.0, b = 1.6, c = 1.6, d = 1.0;
        inputs th1, th2, s;
        unknowns al = 1.2, be = 2.0;
        loop l: a @ th1 + b @ al == (s, 0) + d @ th2 + c @ be;
        point p = a @ th1 + b @ al;
    }
}

/// Where the circles (`a`, `ra`) and (`b`, `rb`) meet, to the left of a->b; `None` where they
/// do not.
fn meet_left(a: [f64; 2], ra: f64, b: [f64; 2], rb: f64) -> Option<[f64; 2]> {
    let v = [b[0] - a[0], b[1] - a[1]];
    let dist = v[0].hypot(v[1]);
    let along = (ra * ra - rb * rb + dist * dist) / (2.0 * dist);
    let h2 = ra * ra - along * along;
    (h2 >= 0.0).then(|| {
        let h = h2.sqrt();
        [a[0] + (along * v[0] - h * v[1]) / dist, a[1] + (along * v[1] + h * v[0]) / dist]
    })
}

#[test]
fn three_inputs_are_a_grid_of_slices_on_one_assembly_mode() {
    let m = Stretch::default();
    let (from, to, counts) = ([0.5, 0.0, 1.6], [3.0, 2.5, 2.4], [11, 9, 5]);
    let grid = GridMotion::record(&m, from, to, counts, m.guess_flat(&from)).unwrap();
    assert_eq!(grid.counts(), counts);
    assert_eq!(grid.cells.len(), 11 * 9 * 5);
    assert_eq!(grid.cell(&[3, 2, 4]), Some(3 + 11 * (2 + 9 * 4)));
    assert_eq!(grid.cell(&[11, 0, 0]), None);
    let (mut reached, mut beyond) = (0, 0);
    for k in 0..5 {
        for j in 0..9 {
            for i in 0..11 {
                let x = [grid.axes[0][i], grid.axes[1][j], grid.axes[2][k]];
                let pa = [m.a * x[0].cos(), m.a * x[0].sin()];
                let pc = [x[2] + m.d * x[1].cos(), m.d * x[1].sin()];
                let apart = (pc[0] - pa[0]).hypot(pc[1] - pa[1]);
                match grid.cells[grid.cell(&[i, j, k]).unwrap()] {
                    Some(n) => {
                        let pose = &grid.motion.poses[n];
                        assert!(pose.x.iter().zip(&x).all(|(a, b)| (a - b).abs() < 1e-12), "{:?} vs {x:?}", pose.x);
                        let p = meet_left(pa, m.b, pc, m.c).expect("reachable cells assemble");
                        if apart < m.b + m.c - 1e-3 {
                            let d = (pose.out[0] - p[0]).hypot(pose.out[1] - p[1]);
                            assert!(d < 1e-9, "cell {i}:{j}:{k}: p off by {d}");
                        }
                        reached += 1;
                    }
                    None => beyond += usize::from(apart > m.b + m.c),
                }
            }
        }
    }
    // Cells beyond the links' reach are never reached; every cell whose straight path from a
    // reached neighbour stays within reach (by a margin: no limit position on the way) is.
    assert!(reached > 300 && beyond > 0, "{reached} reached, {beyond} beyond");
    let apart = |x: [f64; 3]| {
        let (pa, pc) = ([m.a * x[0].cos(), m.a * x[0].sin()], [x[2] + m.d * x[1].cos(), m.d * x[1].sin()]);
        (pc[0] - pa[0]).hypot(pc[1] - pa[1])
    };
    let at = |c: [usize; 3]| [grid.axes[0][c[0]], grid.axes[1][c[1]], grid.axes[2][c[2]]];
    let is_reached = |c: [usize; 3]| grid.cells[grid.cell(&c).unwrap()].is_some();
    for k in 0..5 {
        for j in 0..9 {
            for i in 0..11 {
                let c: [usize; 3] = [i, j, k];
                for axis in 0..3 {
                    for step in [usize::MAX, 1usize] {
                        let mut n = c;
                        n[axis] = n[axis].wrapping_add(step);
                        if n[axis] >= counts[axis] || !is_reached(n) {
                            continue;
                        }
                        let (x0, x1) = (at(n), at(c));
                        let clear = (0..=64).all(|s| {
                            let t = s as f64 / 64.0;
                            apart(std::array::from_fn(|q| x0[q] + t * (x1[q] - x0[q]))) < m.b + m.c - 1e-3
                        });
                        assert!(!clear || is_reached(c), "cell {c:?} not reached from its neighbour {n:?}");
                    }
                }
            }
        }
    }
    let page = html_grid(&m, &m.drawing().into_drawing(), &grid, &HtmlConfig::new("three")).unwrap();
    for k in 0..3 {
        assert!(page.contains(&format!(r#"id="kl-slider-{k}""#)));
    }
    assert!(!page.contains("NaN") && !page.contains("kl-slider-3"));
}

#[test]
fn bad_grids_are_errors() {
    let m = Stretch::default();
    let g = m.guess_flat(&[0.5, 0.0, 2.0]);
    let bad = |from: [f64; 3], to: [f64; 3], counts: [usize; 3]| GridMotion::record(&m, from, to, counts, g);
    let setting = |r: Result<GridMotion, DrawError>| matches!(r, Err(DrawError::InvalidSetting(_)));
    assert!(setting(bad([0.5, 0.0, 2.0], [1.0, 1.0, 2.5], [0, 3, 3])), "no value");
    assert!(setting(bad([0.5, 0.0, 2.0], [1.0, 0.0, 2.5], [3, 3, 3])), "a range of one value");
    assert!(setting(bad([0.5, f64::NAN, 2.0], [1.0, 1.0, 2.5], [3, 3, 3])), "NaN");
    assert!(setting(bad([0.5, 0.0, 2.0], [1.0, 1.0, 2.5], [100, 100, 100])), "more than {MAX_GRID_CELLS} cells");
    assert!(setting(bad([0.5, 0.0, 2.0], [1.0, 1.0, 2.5], [usize::MAX, 2, 2])), "overflowing count");
    // One value on an axis is a slice: allowed, with the same value at both ends; with another
    // end the range would be ignored.
    assert_eq!(bad([0.5, 0.0, 2.0], [1.0, 1.0, 2.0], [3, 3, 1]).unwrap().cells.len(), 9);
    let ignored = bad([0.5, 0.0, 2.0], [1.0, 1.0, 2.5], [3, 3, 1]);
    assert!(
        matches!(&ignored, Err(DrawError::InvalidSetting(m)) if m.contains("one value of input `s`")),
        "{ignored:?}"
    );
    // Not assembled at the first cell (the frame longer than every link together).
    let far = GridMotion::record(&m, [0.5, 0.0, 9.0], [1.0, 1.0, 9.5], [3, 3, 3], g);
    assert!(matches!(far, Err(DrawError::Sweep(_))), "{far:?}");
    // A page: a grid of too many cells for its poses, and one of another mechanism.
    let grid = bad([0.5, 0.0, 2.0], [1.0, 1.0, 2.5], [10, 10, 10]).unwrap();
    let d = m.drawing().into_drawing();
    let small = html_grid(&m, &d, &grid, &HtmlConfig::new("x").with_max_frames(999));
    assert!(matches!(small, Err(HtmlError::InvalidSetting(_))));
    assert!(html_grid(&m, &d, &grid, &HtmlConfig::new("x").with_max_frames(1000)).is_ok());
    let mut other = grid.clone();
    other.motion.inputs.pop();
    assert!(matches!(html_grid(&m, &d, &other, &HtmlConfig::new("x")), Err(HtmlError::InvalidSetting(_))));
    let mut broken = grid;
    broken.cells.pop();
    assert!(matches!(html_grid(&m, &d, &broken, &HtmlConfig::new("x")), Err(HtmlError::InvalidSetting(_))));
}

/// A range no sweep follows is refused before any neighbour is swept, naming the input: past a
/// sweep's million turns between two cells (each cell's sweep refused its range, and the cells
/// read as if the mechanism could not be assembled there), and within it between cells but not
/// over all the grid's lines along the input (each cell a sweep of up to a million turns: hours).
#[test]
fn ranges_no_sweep_follows_are_refused_not_unreached() {
    let m = Stretch::default();
    let from = [0.5, 0.0, 2.0];
    let g = m.guess_flat(&from);
    for (to, counts) in [([1e12, 1.0, 2.5], [3, 3, 3]), ([2e6, 1.0, 2.5], [3, 3, 3]), ([1.0, 1.0, 1e12], [2, 2, 2])] {
        let r = GridMotion::record(&m, from, to, counts, g);
        let Err(e @ DrawError::GridRange { input, .. }) = &r else { panic!("to {to:?}: {r:?}") };
        let (name, index) = if to[2] > 1e3 { ("`s`", 2) } else { ("`th1`", 0) };
        assert_eq!(*input, index);
        let msg = e.to_string();
        assert!(msg.contains(name) && msg.contains("turns a sweep follows"), "{msg}");
    }
    // Between cells 1.2e5 turns of `th1`, within what a sweep follows; on its 9 lines (3 values
    // of each other input) 1.08e6 turns in all, which the message counts (an angle input's
    // unit is the radian).
    let to = [0.5 + std::f64::consts::TAU * 1.2e5, 1.0, 2.5];
    let r = GridMotion::record(&m, from, to, [2, 3, 3], g);
    let Err(e) = r else { panic!("{r:?}") };
    let msg = e.to_string();
    assert!(msg.contains("1.080e6 turns") && msg.contains("radians"), "{msg}");
    // Written in degrees for a caller that reads angles so, where the input is an angle.
    let deg = e.in_degrees(|i| i == 0, f64::to_degrees).to_string();
    assert!(deg.contains("over its range 28.64788975654116 to ") && deg.contains("(degrees)"), "{deg}");
    assert!(deg.contains("1.080e6 turns"), "{deg}");
}

/// The gallery's five-bar over a whole turn of each crank: where the links cannot span the
/// pins (closer than `|b - c|`) a row is interrupted, and the cells after the interruption are
/// reached around it (from the neighbouring rows) on the same assembly mode; every cell whose
/// straight path from a reached neighbour stays clear of the limits is reached.
#[test]
fn cells_past_an_interruption_of_their_row_are_reached_around_it() {
    use kinloop_fixtures::FiveBar;
    use std::f64::consts::TAU;
    let m = FiveBar::default();
    let from = [0.0, 0.0];
    let grid = GridMotion::record(&m, from, [TAU, TAU], [25, 25], m.guess_flat(&from)).unwrap();
    let apart = |x: [f64; 2]| {
        let (pb, pd) = ([m.a * x[0].cos(), m.a * x[0].sin()], [m.d + m.e * x[1].cos(), m.e * x[1].sin()]);
        (pd[0] - pb[0]).hypot(pd[1] - pb[1])
    };
    let clear = |s: f64| s > (m.b - m.c).abs() + 1e-3 && s < m.b + m.c - 1e-3;
    let at = |c: [usize; 2]| [grid.axes[0][c[0]], grid.axes[1][c[1]]];
    let is_reached = |c: [usize; 2]| grid.cells[grid.cell(&c).unwrap()].is_some();
    let mut around = 0;
    for j in 0..25usize {
        for i in 0..25usize {
            let c = [i, j];
            if is_reached(c) {
                assert!(apart(at(c)) >= (m.b - m.c).abs(), "cell {c:?} reached where the links cannot meet");
                around += usize::from((0..i).any(|k| !is_reached([k, j])));
            }
            for (axis, step) in [(0, usize::MAX), (0, 1), (1, usize::MAX), (1, 1)] {
                let mut n = c;
                n[axis] = n[axis].wrapping_add(step);
                if n[axis] >= 25 || !is_reached(n) {
                    continue;
                }
                let (x0, x1) = (at(n), at(c));
                let path_clear = (0..=64).all(|s| {
                    let t = s as f64 / 64.0;
                    clear(apart([x0[0] + t * (x1[0] - x0[0]), x0[1] + t * (x1[1] - x0[1])]))
                });
                assert!(!path_clear || is_reached(c), "cell {c:?} not reached from its neighbour {n:?}");
            }
        }
    }
    assert!(around > 0, "no cell reached past an interruption of its row");
}

/// A grid whose public fields were set by hand with an axis of no value (no cell at all), or
/// with every cell unreachable, is an error of the page, not a panic (a chunk of zero cells, an
/// index past the cells).
#[test]
fn hand_made_grids_without_cells_are_errors() {
    let m = Stretch::default();
    let from = [0.5, 0.0, 2.0];
    let grid = GridMotion::record(&m, from, [1.0, 1.0, 2.5], [3, 3, 3], m.guess_flat(&from)).unwrap();
    let d = m.drawing().into_drawing();
    let page = |g: &GridMotion| html_grid(&m, &d, g, &HtmlConfig::new("x"));
    let mut empty = grid.clone();
    empty.axes[0].clear();
    empty.cells.clear();
    assert!(matches!(page(&empty), Err(HtmlError::InvalidSetting(_))), "an axis of no value");
    let mut all_empty = grid.clone();
    all_empty.axes.iter_mut().for_each(Vec::clear);
    all_empty.cells.clear();
    assert!(matches!(page(&all_empty), Err(HtmlError::InvalidSetting(_))), "no axis has a value");
    // An axis too many (the cells as many as the axes make): the page names the axes, not
    // the inputs, which agree.
    let mut extra = grid.clone();
    extra.axes.push(vec![0.0]);
    let Err(HtmlError::InvalidSetting(e)) = page(&extra) else { panic!("a grid of an axis too many made a page") };
    assert!(e.contains("4 axes"), "{e}");
    // Every cell unreachable: the page shows the pivots and says so at every cell.
    let mut none = grid;
    none.cells.iter_mut().for_each(|c| *c = None);
    assert!(page(&none).is_ok(), "no cell reached");
}

kinloop::mechanism! {
    /// A five-bar whose links are as long as its cranks: where the cranks' pins coincide (`th1 =
    /// 0`, `th2 = pi`) the links' circles are one, and the mechanism, assembled, is singular.
    pub struct PinsMeet {
        params a = 1.0, b = 1.0, c = 1.0, d = 1.0, e = 2.0;
        inputs th1, th2;
        unknowns al = 1.2, be = 2.0;
        loop l: a @ th1 + b @ al == (e, 0) + d @ th2 + c @ be;
        point p = a @ th1 + b @ al;
    }
}

/// A cell the grid does not reach is not said to be one where the mechanism cannot be
/// assembled: the five-bar's cell where the cranks' pins coincide is unreached (singular: a
/// sweep stops there), and the closed form assembles it (the pins `1.2e-16` apart, well within
/// `b + c = 2` and beyond `|b - c| = 0`: the links' circles meet). The page said "cannot be
/// assembled here"; it says the cell was not reached.
#[test]
fn an_unreached_cell_that_assembles_is_not_said_to_be_unassemblable() {
    let m = PinsMeet::default();
    let pi = std::f64::consts::PI;
    let (from, to) = ([-0.4, pi - 0.4], [0.4, pi + 0.4]);
    let grid = GridMotion::record(&m, from, to, [9, 9], m.guess_flat(&from)).unwrap();
    let unreached: Vec<usize> = (0..81).filter(|&c| grid.cells[c].is_none()).collect();
    let centre = grid.cell(&[4, 4]).unwrap();
    assert_eq!(unreached, [centre], "only the cell where the pins meet");
    let (th1, th2) = (grid.axes[0][4], grid.axes[1][4]);
    let (pa, pc) = ([m.a * th1.cos(), m.a * th1.sin()], [m.e + m.d * th2.cos(), m.d * th2.sin()]);
    let apart = (pc[0] - pa[0]).hypot(pc[1] - pa[1]);
    assert!(apart < 1e-15 && meet_left(pa, m.b, pc, m.c).is_some(), "the closed form assembles it: {apart}");
    let page = html_grid(&m, &m.drawing().into_drawing(), &grid, &HtmlConfig::new("pins")).unwrap();
    assert!(!page.contains("cannot be assembled here"), "an unreached cell is said not to assemble");
    assert!(page.contains("not reached on this assembly mode"));
}
