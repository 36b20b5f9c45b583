//! What a program that uses threads relies on: a mechanism read at run time, its errors and
//! states are `Send + Sync` (a `Model` shared between threads, an error through `?` into `Box<dyn
//! Error + Send + Sync>`), and the views of a model that borrow it mutably (a sampled sweep, a
//! traced curve) are `Send`. A field that is not (an `Rc`, a `RefCell` in a shared type, a
//! closure not thread-safe) fails this file's compilation.

fn send_sync<T: Send + Sync>() {}

fn send<T: Send>() {}

#[test]
fn models_read_at_run_time_and_their_errors_cross_threads() {
    send_sync::<kinloop_model::Model>();
    send_sync::<kinloop_model::ReadError>();
    send_sync::<kinloop_model::StepError>();
    send_sync::<kinloop_model::State>();
    send_sync::<kinloop_model::Diagnostics>();
    send_sync::<kinloop_model::SharedModelKernel>();
    send::<kinloop_model::ModelSampled>();
    send::<kinloop_model::ModelTraced>();
}
