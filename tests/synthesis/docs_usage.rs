//! `docs/synthesis.md`, "Using it", as written: its Rust block is here line for line, run on
//! targets sampled from a known design (so the search has an exact answer to find), and
//! `the_document_shows_this_code` fails when a line of the block is not here in the same order;
//! `docs/synthesis-literature.md`'s declaration is `literature.rs`'s, held to it the same way.

use crate::support::doc_snippets::{assert_written_in, rust_blocks};

/// The document's statements, on eight points of the coupler curve of `a = 1.1, b = 2.8` (the
/// declaration's other values) every 45 degrees of the crank; returns the search's report.
fn usage(targets: Vec<[f64; 2]>) -> Result<kinloop::synthesis::SynthesisReport, Box<dyn std::error::Error>> {
    use kinloop::synthesis::{Constraints, Design, Problem, Search, Task};

    kinloop::mechanism! {
        #[kinloop(sensitivities)]
        pub struct CouplerFourBar {
            params a = 1.0, b = 3.0, c = 2.5, d = 3.0, e = 1.5, alpha = 0.6;
            input phi;
            unknowns beta = 0.5, gamma = 1.5;
            loop abcd: a @ phi + b @ beta == (d, 0) + c @ gamma;
            point p = a @ phi + e @ (beta + alpha);
        }
    }

    // What may change, and within which bounds (the other parameters keep their values).
    let design = Design::new()
        .var("a", 0.2, 2.0)
        .var("b", 0.5, 5.0)
        .var("c", 0.5, 5.0)
        .var("d", 0.5, 8.0)
        .var("e", 0.0, 5.0)
        .var("alpha", -3.2, 3.2);
    // What the mechanism must do: the point `p` through these points, in order, at crank angles
    // the search chooses within one turn.
    let task = Task::path("p", targets).untimed(0.0, std::f64::consts::TAU);
    let problem = Problem::new(CouplerFourBar::default(), &design, &task)?
        .with_constraints(&Constraints::default().with_full_rotation())?;
    // How to search: which starts and which seed (`with_keep`: how many candidates to keep).
    let report = Search::default().with_starts(0..512).with_seed(1).run(&problem)?;
    if let Some(best) = report.best() {
        println!("{:?}: max error {:e}", best.values, best.max_error);
    }
    Ok(report)
}

#[test]
fn the_documents_search_finds_a_design_through_the_targets() {
    // The same four-bar, built by circle intersection: B = a @ phi, C at distance b from B and
    // c from (d, 0), on the side the declared guess picks; P = B + e @ (beta + alpha).
    let (a, b, c, d, e, alpha) = (1.1, 2.8, 2.5, 3.0, 1.5, 0.6);
    let targets: Vec<[f64; 2]> = (0..8)
        .map(|i| {
            let phi = f64::from(i) * std::f64::consts::FRAC_PI_4;
            let (bx, by) = (a * phi.cos(), a * phi.sin());
            let (dx, dy) = (d - bx, -by);
            let dist = dx.hypot(dy);
            let along = (b * b - c * c + dist * dist) / (2.0 * dist);
            let across = (b * b - along * along).sqrt();
            let (cx, cy) = (bx + (along * dx - across * dy) / dist, by + (along * dy + across * dx) / dist);
            let beta = (cy - by).atan2(cx - bx);
            [bx + e * (beta + alpha).cos(), by + e * (beta + alpha).sin()]
        })
        .collect();
    let report = usage(targets).unwrap();
    let (values, max_error) = report.best().map(|best| (&best.values, best.max_error)).expect("a candidate");
    // Eight points of the curve hold its six dimensions: the search finds them again.
    assert!(max_error < 1e-12, "{values:?}: {max_error:e}");
    for (found, hidden) in values.iter().zip([a, b, c, d, e, alpha]) {
        assert_close!(*found, hidden, rel = 1e-8, "{values:?}");
    }
}

#[test]
fn the_document_shows_this_code() {
    let blocks = rust_blocks("docs/synthesis.md", "## Using it");
    assert_written_in(include_str!("docs_usage.rs"), &blocks[0], "docs/synthesis.md, \"Using it\"");
    let blocks = rust_blocks("docs/synthesis-literature.md", "## The four-bar and its variables");
    assert_written_in(include_str!("literature.rs"), &blocks[0], "docs/synthesis-literature.md's declaration");
}
