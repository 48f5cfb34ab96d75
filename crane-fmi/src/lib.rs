//! Any crane as an FMI 2.0 co-simulation FMU: the inverse model behind the
//! standard C interface, so that Simulink, OpenModelica, Dymola or Python
//! (FMPy) can run it as a feedforward block.
//!
//! At each communication step the host hands over the load target (or lets
//! the FMU follow its built-in move) and gets back the inputs, coordinates,
//! multipliers and rope tensions, computed by the redundant-coordinate
//! stepper of `crane-runtime` in `h / dt` internal steps.
//!
//! - [`variables`]: the FMU's variables for a crane, named as the model
//!   declares them (one table for the description and the instance);
//! - [`description`]: `modelDescription.xml` and its GUID;
//! - [`instance`]: the co-simulation state machine in safe Rust;
//! - [`ffi`] and [`export_fmu!`]: the C entry points;
//! - [`package`](mod@package): the `.fmu` archive;
//! - [`start`]: the run an FMU starts from, the crane's default or a
//!   packaged scenario's (a spline move's shape travels in `resources/`);
//! - [`fmi2`]: the FMI 2.0 C types.
//!
//! # Exporting a crane
//!
//! A `cdylib` crate whose `lib.rs` declares the crane, describes its
//! default move ([`Crane`]) and exports it:
//!
//! ```ignore
//! crane_fmi::export_fmu!(MyCraneDescription);
//! ```
//!
//! then, after `cargo build --release`, package it (from a build script, a
//! test or a small binary of the same crate):
//!
//! ```ignore
//! use crane_fmi::start::Start;
//! crane_fmi::package::package::<MyCraneDescription, 4, 1, 2>(
//!     "target/release/libmy_crane.so".as_ref(), "MyCrane.fmu".as_ref(),
//!     &Start::default_for::<MyCraneDescription, 4, 1>())?;
//! ```
//!
//! The built-in cranes are exported by the `crane-fmu` library, and
//! `crane fmu MODEL --out MODEL.fmu` packages one.
//!
//! # The instance in Rust
//!
//! The state machine behind the C functions can be driven directly:
//!
//! ```
//! use crane_fmi::instance::{Component, Instance};
//! use crane_models::navy_planar;
//!
//! let mut fmu = Instance::<navy_planar::Description, 7, 3, 2>::new().unwrap();
//! fmu.setup_experiment(0.0).unwrap();
//! fmu.enter_initialization_mode().unwrap();
//! fmu.exit_initialization_mode().unwrap();   // the consistent start
//! for k in 0..150 {
//!     fmu.do_step(k as f64 * 0.01, 0.01).unwrap();
//! }
//! let start = crane_fmi::start::Start::default_for::<navy_planar::Description, 7, 3>();
//! let table = crane_fmi::variables::variables::<navy_planar::Description, 7, 3, 2>(&start).unwrap();
//! let u2 = table.iter().find(|v| v.name == "u2").unwrap().value_reference;
//! let mut value = [0.0];
//! fmu.get_real(&[u2], &mut value).unwrap();
//! assert!(value[0].is_finite());
//! assert!(fmu.do_step(1.5, 0.015).is_err()); // not a multiple of dt
//! ```
#![warn(missing_docs)]

pub mod description;
pub mod ffi;
pub mod fmi2;
pub mod instance;
pub mod package;
pub mod start;
pub mod variables;

pub use crane_models::{Crane, Maneuver, PathSpec, Profile, Registry};

/// The FMU entries of every crane of `registry`.
pub fn entries<R: Registry>(registry: &R) -> Vec<ffi::Entry> {
    struct MakeEntry;
    impl crane_models::Visit for MakeEntry {
        type Output = ffi::Entry;
        fn visit<C: Crane<N, M, A>, const N: usize, const M: usize, const A: usize>(self) -> ffi::Entry {
            ffi::Entry::of::<C, N, M, A>()
        }
    }
    registry
        .entries()
        .iter()
        .filter_map(|e| registry.visit(e.name, MakeEntry))
        .collect()
}

/// The FMU entries of every built-in crane.
pub fn built_in() -> Vec<ffi::Entry> {
    entries(&crane_models::BuiltIn)
}

/// Export the FMI 2.0 co-simulation functions (`fmi2Instantiate`,
/// `fmi2DoStep`, ...) from a `cdylib` for the cranes listed
/// (`export_fmu!(A, B)`, each a [`Crane`]), for the cranes of a
/// [`Registry`] (`export_fmu!(registry = MyCranes)`, the registry a tool's
/// `fmu` command packages from) or for the entries a function returns
/// (`export_fmu!(entries = crane_fmi::built_in)`). The host's GUID picks
/// the crane.
#[macro_export]
macro_rules! export_fmu {
    (registry = $registry:expr) => {
        fn __crane_fmi_entries() -> ::std::vec::Vec<$crate::ffi::Entry> {
            $crate::entries(&$registry)
        }
        $crate::export_fmu!(@functions __crane_fmi_entries);
    };
    ($($crane:ty),+ $(,)?) => {
        fn __crane_fmi_entries() -> ::std::vec::Vec<$crate::ffi::Entry> {
            ::std::vec![$($crate::ffi::Entry::of::<$crane, _, _, _>()),+]
        }
        $crate::export_fmu!(@functions __crane_fmi_entries);
    };
    (entries = $entries:path) => {
        $crate::export_fmu!(@functions $entries);
    };
    (@functions $entries:path) => {
        const _: () = {
            use $crate::fmi2::{
                Boolean, CallbackFunctions, Component, FmiString, FmuType, Integer, Real, Status, StatusKind, ValueReference,
            };
            use $crate::ffi;
            use ::std::ffi::c_char;

            #[unsafe(no_mangle)]
            pub extern "C" fn fmi2GetTypesPlatform() -> *const c_char { ffi::get_types_platform() }
            #[unsafe(no_mangle)]
            pub extern "C" fn fmi2GetVersion() -> *const c_char { ffi::get_version() }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi2SetDebugLogging(
                c: Component,
                on: Boolean,
                _n: usize,
                _categories: *const FmiString,
            ) -> Status {
                unsafe { ffi::set_debug_logging(c, on) }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi2Instantiate(
                name: FmiString, kind: FmuType, guid: FmiString, resources: FmiString,
                callbacks: *const CallbackFunctions, _visible: Boolean, logging: Boolean,
            ) -> Component {
                let entries = $entries();
                unsafe { ffi::instantiate(&entries, name, kind, guid, resources, callbacks, logging) }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi2FreeInstance(c: Component) { unsafe { ffi::free_instance(c) } }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi2SetupExperiment(
                c: Component,
                _tol_defined: Boolean,
                _tol: Real,
                start: Real,
                _stop_defined: Boolean,
                _stop: Real,
            ) -> Status {
                unsafe { ffi::setup_experiment(c, start) }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi2EnterInitializationMode(
                c: Component,
            ) -> Status {
                unsafe { ffi::enter_initialization_mode(c) }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi2ExitInitializationMode(
                c: Component,
            ) -> Status {
                unsafe { ffi::exit_initialization_mode(c) }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi2Terminate(c: Component) -> Status { unsafe { ffi::terminate(c) } }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi2Reset(c: Component) -> Status { unsafe { ffi::reset(c) } }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi2GetReal(
                c: Component,
                vr: *const ValueReference,
                n: usize,
                v: *mut Real,
            ) -> Status {
                unsafe { ffi::get_real(c, vr, n, v) }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi2SetReal(
                c: Component,
                vr: *const ValueReference,
                n: usize,
                v: *const Real,
            ) -> Status {
                unsafe { ffi::set_real(c, vr, n, v) }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi2GetInteger(
                c: Component,
                vr: *const ValueReference,
                n: usize,
                v: *mut Integer,
            ) -> Status {
                unsafe { ffi::get_integer(c, vr, n, v) }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi2SetInteger(
                c: Component,
                vr: *const ValueReference,
                n: usize,
                v: *const Integer,
            ) -> Status {
                unsafe { ffi::set_integer(c, vr, n, v) }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi2GetBoolean(
                c: Component,
                _vr: *const ValueReference,
                n: usize,
                _v: *mut Boolean,
            ) -> Status {
                unsafe { ffi::no_variables(c, "fmi2GetBoolean", n) }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi2SetBoolean(
                c: Component,
                _vr: *const ValueReference,
                n: usize,
                _v: *const Boolean,
            ) -> Status {
                unsafe { ffi::no_variables(c, "fmi2SetBoolean", n) }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi2GetString(
                c: Component,
                _vr: *const ValueReference,
                n: usize,
                _v: *mut FmiString,
            ) -> Status {
                unsafe { ffi::no_variables(c, "fmi2GetString", n) }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi2SetString(
                c: Component,
                _vr: *const ValueReference,
                n: usize,
                _v: *const FmiString,
            ) -> Status {
                unsafe { ffi::no_variables(c, "fmi2SetString", n) }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi2GetFMUstate(
                c: Component,
                _s: *mut *mut ::std::ffi::c_void,
            ) -> Status {
                unsafe { ffi::unsupported(c, "fmi2GetFMUstate") }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi2SetFMUstate(
                c: Component,
                _s: *mut ::std::ffi::c_void,
            ) -> Status {
                unsafe { ffi::unsupported(c, "fmi2SetFMUstate") }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi2FreeFMUstate(
                c: Component,
                _s: *mut *mut ::std::ffi::c_void,
            ) -> Status {
                unsafe { ffi::unsupported(c, "fmi2FreeFMUstate") }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi2SerializedFMUstateSize(
                c: Component,
                _s: *mut ::std::ffi::c_void,
                _size: *mut usize,
            ) -> Status {
                unsafe { ffi::unsupported(c, "fmi2SerializedFMUstateSize") }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi2SerializeFMUstate(
                c: Component,
                _s: *mut ::std::ffi::c_void,
                _b: *mut c_char,
                _size: usize,
            ) -> Status {
                unsafe { ffi::unsupported(c, "fmi2SerializeFMUstate") }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi2DeSerializeFMUstate(
                c: Component,
                _b: *const c_char,
                _size: usize,
                _s: *mut *mut ::std::ffi::c_void,
            ) -> Status {
                unsafe { ffi::unsupported(c, "fmi2DeSerializeFMUstate") }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi2GetDirectionalDerivative(
                c: Component,
                _u: *const ValueReference,
                _nu: usize,
                _k: *const ValueReference,
                _nk: usize,
                _dk: *const Real,
                _du: *mut Real,
            ) -> Status { unsafe { ffi::unsupported(c, "fmi2GetDirectionalDerivative") } }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi2SetRealInputDerivatives(
                c: Component,
                _vr: *const ValueReference,
                _n: usize,
                _o: *const Integer,
                _v: *const Real,
            ) -> Status {
                unsafe { ffi::unsupported(c, "fmi2SetRealInputDerivatives") }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi2GetRealOutputDerivatives(
                c: Component,
                _vr: *const ValueReference,
                _n: usize,
                _o: *const Integer,
                _v: *mut Real,
            ) -> Status {
                unsafe { ffi::unsupported(c, "fmi2GetRealOutputDerivatives") }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi2DoStep(
                c: Component,
                t: Real,
                h: Real,
                _no_set_prior: Boolean,
            ) -> Status {
                unsafe { ffi::do_step(c, t, h) }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi2CancelStep(
                c: Component,
            ) -> Status {
                unsafe { ffi::unsupported(c, "fmi2CancelStep") }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi2GetStatus(
                c: Component,
                _k: StatusKind,
                _v: *mut Status,
            ) -> Status {
                unsafe { ffi::unsupported(c, "fmi2GetStatus") }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi2GetRealStatus(
                c: Component,
                k: StatusKind,
                v: *mut Real,
            ) -> Status {
                unsafe { ffi::get_real_status(c, k, v) }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi2GetIntegerStatus(
                c: Component,
                _k: StatusKind,
                _v: *mut Integer,
            ) -> Status {
                unsafe { ffi::unsupported(c, "fmi2GetIntegerStatus") }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi2GetBooleanStatus(
                c: Component,
                k: StatusKind,
                v: *mut Boolean,
            ) -> Status {
                unsafe { ffi::get_boolean_status(c, k, v) }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi2GetStringStatus(
                c: Component,
                _k: StatusKind,
                _v: *mut FmiString,
            ) -> Status {
                unsafe { ffi::unsupported(c, "fmi2GetStringStatus") }
            }
        };
    };
}
