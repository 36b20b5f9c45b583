//! kinloop on the literature's four-bar path-synthesis cases (`docs/synthesis-literature.md`):
//! for each case, every start's local solve on both assembly modes, verified; prints the best
//! valid design with full digits, its sum of squared distances (the published measure), the
//! share of starts whose valid result reaches the case's threshold, and the wall time.
//!
//! `cargo run --release -p kinloop-bench --bin literature [-- STARTS [SEED [CASE]]]` (default
//! 256 starts per assembly mode, seed 1, every case; `CASE`: the first letters of the cases to
//! run, e.g. `b`). One thread.

use kinloop_bench::literature::{THRESHOLDS, cases, polish, search, sum_of_squares, variables};
use std::time::Instant;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut args = std::env::args().skip(1);
    let starts: usize = args.next().map_or(Ok(256), |s| s.parse())?;
    let seed: u64 = args.next().map_or(Ok(1), |s| s.parse())?;
    let only = args.next().unwrap_or_default();
    println!("case | starts | valid | best sum of squares | reaching threshold | evaluations | wall time");
    for (case, threshold) in cases().iter().zip(THRESHOLDS).filter(|(c, _)| c.name.starts_with(only.as_str())) {
        let clock = Instant::now();
        let out = search(case, starts, seed, 400)?;
        let time = clock.elapsed().as_secs_f64();
        let reached = out.valid.iter().filter(|&&e| e <= threshold).count();
        let best = out.best.as_ref().map_or(f64::NAN, sum_of_squares);
        println!(
            "{} | {} | {} | {best:.6e} | {reached}/{} ({:.1} %) at <= {threshold:e} | {} | {time:.2} s",
            case.name,
            out.starts,
            out.valid.len(),
            out.starts,
            100.0 * reached as f64 / out.starts as f64,
            out.evaluations
        );
        let r = &out.rejected;
        println!(
            "    unassembled {}; rejected: {} order, {} branch, {} circuit, {} no assembly, {} no full rotation; \
             best rejected {:.3e}",
            out.unassembled, r.order, r.branch, r.circuit, r.no_assembly, r.full_rotation, out.best_rejected
        );
        if let Some(b) = &out.best {
            println!(
                "    found from start {} (mode guess {:?}, crank window {:?}) in {} evaluations: {:e}",
                b.start,
                out.best_at.0,
                out.best_at.1,
                b.local.evaluations,
                sum_of_squares(b)
            );
        }
        if let Some(b) = polish(case, &out)? {
            println!(
                "    polished by a longer local solve: {:e} ({} evaluations)",
                sum_of_squares(&b),
                b.local.evaluations
            );
            let names = variables(case);
            let values: Vec<String> = names.iter().zip(&b.values).map(|(n, v)| format!("{n} = {v:?}")).collect();
            println!("    design: {}", values.join(", "));
            let th2: Vec<String> = b.inputs.iter().map(|x| format!("{:?}", x[0])).collect();
            println!("    th2: [{}]", th2.join(", "));
            println!("    [th3, th4] at the first target: {:?}", b.positions[0]);
        }
    }
    Ok(())
}
