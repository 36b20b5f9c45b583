//! Macro expansion time: `kinloop_codegen::expand` (what `mechanism!` runs inside the compiler)
//! on the token stream of each paper mechanism's declaration; tokenising the text is not timed.
//!
//! `cargo bench -p kinloop-bench --bench expand`.

use std::time::Duration;

use criterion::{BatchSize, Criterion, criterion_group, criterion_main};
use kinloop_bench::decls::paper_mechanisms;
use kinloop_bench::expansion::{four_bar_chain, tokens};

fn expansion(c: &mut Criterion) {
    let mut g = c.benchmark_group("expand");
    let mut cases: Vec<(String, String)> =
        paper_mechanisms().iter().map(|d| (d.name.to_string(), d.text.to_string())).collect();
    for k in [1, 2, 4, 8, 16] {
        cases.push((format!("FourBarChain{k}"), four_bar_chain(k)));
    }
    for (name, text) in &cases {
        // Expands cleanly (no compile_error!) before it is timed.
        kinloop_bench::expansion::size(text);
        g.bench_function(name.as_str(), |b| {
            b.iter_batched(|| tokens(text), kinloop_codegen::expand, BatchSize::SmallInput)
        });
    }
    g.finish();
}

criterion_group! {
    name = expand;
    config = Criterion::default().sample_size(50).measurement_time(Duration::from_secs(4));
    targets = expansion
}
criterion_main!(expand);
