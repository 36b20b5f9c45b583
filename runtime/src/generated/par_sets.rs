//! The parallel distribution of independent sets over rayon's thread pool, one workspace per
//! job: written once for the compiled `par_scan` and a run-time model's `par_scan` (hidden:
//! not part of the public API).

/// `one(workspace, set)` for every set of `sets` on rayon's global thread pool, the results in
/// the sets' order: the parallel half of [`par_scan`](crate::paths::scan::par_scan) (whose sets need no workspace) and of
/// `kinloop_model::Model::par_scan` (whose workspace is a clone of the model: a model is one
/// mutable workspace).
///
/// Each rayon job makes its workspace by `workspace()` once and runs its sets with it, one after
/// the other; a job holds at least a sixteenth of a thread's share of the sets, so at most
/// about sixteen workspaces are made per thread, however many sets there are, and the sets are
/// still spread finely enough for work stealing to even out slow and fast ones. Each result is
/// computed by `one` from its set and a workspace: bitwise the same as one after the other
/// whenever `one`'s result does not depend on what the workspace computed before.
pub fn par_sets<T, W, R>(
    sets: &[T],
    workspace: impl Fn() -> W + Sync + Send,
    one: impl Fn(&mut W, &T) -> R + Sync + Send,
) -> Vec<R>
where
    T: Sync,
    R: Send,
{
    use rayon::prelude::*;
    let per_job = (sets.len() / (16 * rayon::current_num_threads())).max(1);
    sets.par_iter().with_min_len(per_job).map_init(workspace, |w, set| one(w, set)).collect()
}

#[cfg(test)]
mod tests {
    use super::par_sets;
    use std::sync::atomic::{AtomicUsize, Ordering};

    /// The results are in the sets' order, each computed with some job's workspace, and the
    /// workspaces are made per job, not per set: at most about sixteen per thread.
    #[test]
    fn par_sets_keeps_the_order_and_makes_few_workspaces() {
        let sets: Vec<u64> = (0..1000).collect();
        let made = AtomicUsize::new(0);
        let workspace = || {
            made.fetch_add(1, Ordering::Relaxed);
            Vec::<u64>::new()
        };
        let results = par_sets(&sets, workspace, |seen, &s| {
            seen.push(s);
            s * s
        });
        assert_eq!(results, sets.iter().map(|s| s * s).collect::<Vec<_>>());
        let (made, threads) = (made.load(Ordering::Relaxed), rayon::current_num_threads());
        // A job holds at least floor(1000 / (16 threads)) sets.
        let bound = sets.len() / (sets.len() / (16 * threads)).max(1);
        eprintln!("{made} workspaces for {} sets on {threads} threads (at most {bound})", sets.len());
        assert!(made >= 1 && made <= bound, "{made} workspaces for {threads} threads");
        assert!(par_sets(&sets[..0], workspace, |_, &s| s).is_empty());
    }
}
