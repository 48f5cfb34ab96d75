//! Stopping a long computation from outside ([`Cancel`]): a host (a Python
//! interpreter whose user pressed Ctrl-C) sets the flag from another
//! thread, and the run polls it at every step, ending with
//! [`Error::Cancelled`] and nothing half-made returned.
//!
//! The flag is in scope for the computations [`Cancel::scope`] runs on its
//! thread; code that hands work to other threads (a pool) takes
//! [`Cancel::current`] along and opens the scope there.
//!
//! ```
//! use crane_runtime::cancel::{self, Cancel};
//! let cancel = Cancel::default();
//! assert!(cancel.scope(cancel::check).is_ok());
//! cancel.set();
//! assert!(cancel.scope(cancel::check).is_err());
//! // outside any scope nothing is cancelled
//! assert!(cancel::check().is_ok());
//! ```

use std::cell::RefCell;
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};

use crate::error::Error;

/// A flag that stops the computations in its [`scope`](Self::scope) once
/// set; clones share it.
#[derive(Debug, Clone, Default)]
pub struct Cancel(Arc<AtomicBool>);

thread_local! {
    /// The flag in scope on this thread.
    static CURRENT: RefCell<Option<Cancel>> = const { RefCell::new(None) };
}

impl Cancel {
    /// Stop the computations in scope at their next check.
    pub fn set(&self) {
        self.0.store(true, Ordering::Relaxed);
    }

    /// Whether it was set.
    pub fn is_set(&self) -> bool {
        self.0.load(Ordering::Relaxed)
    }

    /// Run `f` with this flag in scope on the current thread (the one in
    /// scope before is in scope again after).
    pub fn scope<R>(&self, f: impl FnOnce() -> R) -> R {
        let outer = CURRENT.with(|current| current.replace(Some(self.clone())));
        /// Puts the outer flag back, also where `f` unwinds.
        struct Restore(Option<Cancel>);
        impl Drop for Restore {
            fn drop(&mut self) {
                let outer = self.0.take();
                CURRENT.with(|current| *current.borrow_mut() = outer);
            }
        }
        let _restore = Restore(outer);
        f()
    }

    /// The flag in scope on the current thread, if any.
    pub fn current() -> Option<Cancel> {
        CURRENT.with(|current| current.borrow().clone())
    }
}

/// [`Error::Cancelled`] where the flag in scope on this thread was set.
pub fn check() -> Result<(), Error> {
    let cancelled = CURRENT.with(|current| current.borrow().as_ref().is_some_and(Cancel::is_set));
    if cancelled { Err(Error::Cancelled) } else { Ok(()) }
}
