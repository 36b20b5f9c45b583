//! What a program that uses threads relies on: the errors, states, sweeps and results of a
//! compiled mechanism are `Send + Sync` (an error goes through `?` into `Box<dyn Error + Send +
//! Sync>`, or `anyhow`; a sweep or a table is handed to another thread). A field that is not (an
//! `Rc`, a `RefCell`, a closure not thread-safe) fails this file's compilation. The mechanisms
//! read at run time have the same test (`model/tests/auto_traits.rs`).

use kinloop::dynamics::{Cycle, DynamicsError, Trajectory};
use kinloop::synthesis::SynthesisReport;
use kinloop::{Error, Kin, Sweep, Table};
use kinloop_fixtures::FourBar;

fn send_sync<T: Send + Sync>() {}

#[test]
fn compiled_mechanisms_errors_and_results_cross_threads() {
    send_sync::<Error>();
    send_sync::<DynamicsError>();
    send_sync::<Kin<2, 1, 2>>();
    send_sync::<kinloop::analysis::Sampled<'static, FourBar, 2, 2>>();
    send_sync::<Sweep<'static, FourBar, Kin<2, 1, 2>, 2, 1, 2>>();
    send_sync::<Table>();
    send_sync::<Trajectory>();
    send_sync::<Cycle>();
    send_sync::<SynthesisReport>();
}
