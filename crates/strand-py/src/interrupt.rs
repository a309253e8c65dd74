//! Long runs from Python: run off the interpreter lock on a thread of their own, report
//! progress to a Python callback, and stop on Ctrl-C.
//!
//! The runner's progress hook is the one place a run calls back, so a stop is an unwind from
//! it (a [`Cancelled`] panic caught at the top): every value of the run is dropped and every
//! file closed; the files keep what was written until then. The calling thread waits for the
//! run, checking the interpreter's signals every 50 ms; the callback holds the interpreter
//! lock only while it runs.

use std::panic::{AssertUnwindSafe, catch_unwind, panic_any};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::mpsc::{self, RecvTimeoutError};
use std::sync::{Mutex, Once};
use std::time::{Duration, Instant};

use pyo3::exceptions::{PyRuntimeError, PyValueError};
use pyo3::prelude::*;

/// The unwind that stops a run (a signal, or an exception of the progress callback).
pub struct Cancelled;

/// Least interval between two calls of the progress callback.
const PROGRESS_INTERVAL: Duration = Duration::from_millis(100);

/// Interval at which the waiting thread checks the interpreter's signals.
const SIGNAL_INTERVAL: Duration = Duration::from_millis(50);

/// Stack of the run's thread, as the main thread of the `strand` command has.
const STACK: usize = 8 << 20;

/// Keeps the stop of a run ([`Cancelled`]) out of the panic messages on standard error; every
/// other panic is reported as before.
pub fn install_quiet_panic_hook() {
    static ONCE: Once = Once::new();
    ONCE.call_once(|| {
        let previous = std::panic::take_hook();
        std::panic::set_hook(Box::new(move |info| {
            if !info.payload().is::<Cancelled>() {
                previous(info);
            }
        }));
    });
}

/// Runs `job` without the interpreter lock on a thread of its own (in a rayon pool of
/// `threads` threads if given, else the global pool), giving it the progress hook `(model,
/// fraction)`. A signal (Ctrl-C raises `KeyboardInterrupt`) or an exception of `progress` stops
/// the run at its next progress report and is raised here.
pub fn run_interruptible<T: Send>(
    py: Python<'_>,
    threads: Option<usize>,
    progress: Option<Py<PyAny>>,
    job: impl FnOnce(&mut dyn FnMut(&str, f64)) -> T + Send,
) -> PyResult<T> {
    let pool = match threads {
        Some(0) => return Err(PyValueError::new_err("threads must be at least 1")),
        Some(n) => Some(
            rayon::ThreadPoolBuilder::new()
                .num_threads(n)
                .build()
                .map_err(|e| PyRuntimeError::new_err(format!("thread pool: {e}")))?,
        ),
        None => None,
    };
    let cancel = AtomicBool::new(false);
    let failure: Mutex<Option<PyErr>> = Mutex::new(None);
    let fail = |e: PyErr| {
        if let Ok(mut f) = failure.lock() {
            f.get_or_insert(e);
        }
        cancel.store(true, Ordering::SeqCst);
    };
    let (cancel, fail, progress) = (&cancel, &fail, &progress);
    let outcome = py.detach(move || {
        std::thread::scope(|s| {
            let (done, wait) = mpsc::channel::<()>();
            let worker = std::thread::Builder::new()
                .name("strand-run".into())
                .stack_size(STACK)
                .spawn_scoped(s, move || {
                    let r = catch_unwind(AssertUnwindSafe(|| {
                        let mut last: Option<Instant> = None;
                        let mut hook = |model: &str, fraction: f64| {
                            if cancel.load(Ordering::SeqCst) {
                                panic_any(Cancelled);
                            }
                            let Some(cb) = &progress else { return };
                            if last.is_some_and(|t| t.elapsed() < PROGRESS_INTERVAL)
                                && fraction < 1.0
                            {
                                return;
                            }
                            last = Some(Instant::now());
                            let called = Python::attach(|py| cb.call1(py, (model, fraction)));
                            if let Err(e) = called {
                                fail(e);
                                panic_any(Cancelled);
                            }
                        };
                        match &pool {
                            Some(p) => p.install(|| job(&mut hook)),
                            None => job(&mut hook),
                        }
                    }));
                    let _ = done.send(());
                    r
                });
            let worker = match worker {
                Ok(w) => w,
                Err(e) => return Err(format!("cannot start the run's thread: {e}")),
            };
            loop {
                match wait.recv_timeout(SIGNAL_INTERVAL) {
                    Ok(()) | Err(RecvTimeoutError::Disconnected) => break,
                    Err(RecvTimeoutError::Timeout) => {
                        if !cancel.load(Ordering::SeqCst)
                            && let Err(e) = Python::attach(|py| py.check_signals())
                        {
                            fail(e);
                        }
                    }
                }
            }
            worker
                .join()
                .map_err(|_| "the run's thread ended abnormally".to_string())
        })
    });
    let stored = failure.lock().ok().and_then(|mut f| f.take());
    match outcome {
        Err(message) => Err(PyRuntimeError::new_err(message)),
        Ok(Ok(value)) => match stored {
            // A signal that came after the last progress report: the run finished; the
            // signal is still raised, as the interpreter would have.
            Some(e) => Err(e),
            None => Ok(value),
        },
        Ok(Err(payload)) => Err(match stored {
            Some(e) => e,
            None => {
                let message = payload
                    .downcast_ref::<String>()
                    .map(String::as_str)
                    .or_else(|| payload.downcast_ref::<&str>().copied())
                    .unwrap_or("a panic");
                PyRuntimeError::new_err(format!("the run stopped on an internal error: {message}"))
            }
        }),
    }
}
