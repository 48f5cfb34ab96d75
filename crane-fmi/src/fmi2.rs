//! The FMI 2.0 C types an exporter needs, written out from the standard's
//! headers (`fmi2TypesPlatform.h`, `fmi2FunctionTypes.h`): the scalar types,
//! the status and type enumerations, and the callback struct the host hands
//! to `fmi2Instantiate`.
//!
//! Why not `fmi-sys`: it generates these with bindgen at build time, which
//! needs libclang on the building machine (a plain CI machine has none), and
//! it is laid out for importing FMUs (a dynamically loaded function table);
//! the exporter side is these few declarations.

use std::ffi::{c_char, c_int, c_uint, c_void};

/// `fmi2Real`.
pub type Real = f64;
/// `fmi2Integer`.
pub type Integer = c_int;
/// `fmi2Boolean` (`fmi2True = 1`, `fmi2False = 0`).
pub type Boolean = c_int;
/// `fmi2ValueReference`.
pub type ValueReference = c_uint;
/// `fmi2String`.
pub type FmiString = *const c_char;
/// `fmi2Component`: the instance, opaque to the host.
pub type Component = *mut c_void;
/// `fmi2ComponentEnvironment`: the host's pointer handed back to the logger.
pub type ComponentEnvironment = *mut c_void;

/// `fmi2Status`.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Status {
    /// `fmi2OK`.
    Ok = 0,
    /// `fmi2Warning`.
    Warning = 1,
    /// `fmi2Discard`.
    Discard = 2,
    /// `fmi2Error`.
    Error = 3,
    /// `fmi2Fatal`.
    Fatal = 4,
    /// `fmi2Pending`.
    Pending = 5,
}

/// `fmi2Type` (as a plain integer: a host may pass any value).
pub type FmuType = c_int;
/// `fmi2CoSimulation`.
pub const CO_SIMULATION: FmuType = 1;

/// `fmi2StatusKind` (as a plain integer).
pub type StatusKind = c_int;
/// `fmi2LastSuccessfulTime`.
pub const LAST_SUCCESSFUL_TIME: StatusKind = 2;
/// `fmi2Terminated`.
pub const TERMINATED: StatusKind = 3;

/// `fmi2CallbackLogger`: `printf`-style, variadic.
pub type CallbackLogger =
    Option<unsafe extern "C" fn(ComponentEnvironment, FmiString, c_int, FmiString, FmiString, ...)>;

/// `fmi2CallbackFunctions`.
#[repr(C)]
#[derive(Debug, Clone, Copy)]
pub struct CallbackFunctions {
    /// Where messages go.
    pub logger: CallbackLogger,
    /// `calloc`-like (not used: the instance allocates with Rust's allocator).
    pub allocate_memory: Option<unsafe extern "C" fn(usize, usize) -> *mut c_void>,
    /// `free`-like (not used).
    pub free_memory: Option<unsafe extern "C" fn(*mut c_void)>,
    /// For asynchronous steps (not supported).
    pub step_finished: Option<unsafe extern "C" fn(ComponentEnvironment, c_int)>,
    /// Handed back to `logger`.
    pub component_environment: ComponentEnvironment,
}
