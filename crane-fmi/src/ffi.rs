//! The FMI 2.0 co-simulation entry points, as plain functions that
//! [`export_fmu!`](crate::export_fmu) wraps in `extern "C"` symbols: they
//! check pointers, call the instance's [`Component`] methods, log failures
//! through the host's logger and turn them into status codes. A panic is
//! caught here and reported as `fmi2Error`; nothing unwinds into the host.

use std::ffi::{CStr, CString, c_char, c_int};
use std::panic::{AssertUnwindSafe, catch_unwind};
use std::ptr;

use crane_models::Crane;

use crate::description::model_description;
use crate::fmi2::{
    self, Boolean, CallbackFunctions, Component as RawComponent, FmiString, FmuType, Integer, Real, Status, StatusKind,
    ValueReference,
};
use crate::instance::{Component, Instance};
use crate::start::{Start, StartError};

/// One crane an exported library can instantiate: found by the GUID the
/// host passes to `fmi2Instantiate`.
#[derive(Clone, Copy)]
pub struct Entry {
    /// The crane's name.
    pub name: &'static str,
    /// Its model description and GUID, for its default run or the
    /// packaged one whose text is given ([`start`](crate::start)); `None`
    /// if that run is another crane's.
    pub description: fn(Option<&str>) -> Result<Option<Described>, String>,
    /// A new instance, of its default run or the packaged one.
    pub instantiate: fn(Option<&str>) -> Result<Boxed, String>,
}

/// An instance behind the C interface.
pub type Boxed = Box<dyn Component>;

/// A model description and its GUID.
pub type Described = (String, String);

impl Entry {
    /// The entry of crane `C`.
    pub fn of<C: Crane<N, M, A>, const N: usize, const M: usize, const A: usize>() -> Self {
        Self {
            name: C::NAME,
            description: |packaged| {
                let Some(start) = start_of::<C, N, M, A>(packaged)? else {
                    return Ok(None);
                };
                model_description::<C, N, M, A>(&start)
                    .map(Some)
                    .map_err(|e| e.to_string())
            },
            instantiate: |packaged| {
                let start = start_of::<C, N, M, A>(packaged)?
                    .ok_or_else(|| format!("the packaged run is not {}'s", C::NAME))?;
                Instance::<C, N, M, A>::starting_from(start)
                    .map(|i| Box::new(i) as Box<dyn Component>)
                    .map_err(|e| e.to_string())
            },
        }
    }
}

/// Crane `C`'s default run, or the packaged run `packaged` holds (`None`
/// if it is another crane's).
fn start_of<C: Crane<N, M, A>, const N: usize, const M: usize, const A: usize>(
    packaged: Option<&str>,
) -> Result<Option<Start<A>>, String> {
    match packaged.map(Start::read::<C, N, M>) {
        None => Ok(Some(Start::default_for::<C, N, M>())),
        Some(Ok(start)) => Ok(Some(start)),
        Some(Err(StartError::WrongModel { .. })) => Ok(None),
        Some(Err(e)) => Err(e.to_string()),
    }
}

/// The packaged run in the folder of the `file:` URI `location` (the
/// host's `fmuResourceLocation`), if the folder has one: a regular file of
/// at most [`MAX_RESOURCE_BYTES`](crate::start::MAX_RESOURCE_BYTES) (a
/// FIFO or a device there is refused, not waited on or read without end).
fn packaged_run(location: Option<&str>) -> Result<Option<String>, String> {
    let Some(location) = location.filter(|l| !l.is_empty()) else {
        return Ok(None);
    };
    let folder = folder_of_uri(location)
        .ok_or_else(|| format!("the resource location {location} is not a file: URI of a local folder"))?;
    let path = folder.join(crate::start::RESOURCE);
    if std::fs::symlink_metadata(&path).is_err() {
        return Ok(None);
    }
    if let Some(kind) = crane_models::files::not_a_regular_file(&path) {
        return Err(format!("{} is {kind}, not a packaged run", path.display()));
    }
    let limit = crate::start::MAX_RESOURCE_BYTES;
    let file = std::fs::File::open(&path).map_err(|e| format!("reading {}: {e}", path.display()))?;
    let mut bytes = Vec::new();
    std::io::Read::read_to_end(&mut std::io::Read::take(file, limit + 1), &mut bytes)
        .map_err(|e| format!("reading {}: {e}", path.display()))?;
    if bytes.len() as u64 > limit {
        return Err(format!(
            "{} has more than a packaged run's {limit} bytes",
            path.display()
        ));
    }
    String::from_utf8(bytes)
        .map(Some)
        .map_err(|_| format!("{} is not UTF-8 text", path.display()))
}

/// The local folder a `file:` URI names (`file:///tmp/x/resources/`,
/// `file:/tmp/x/resources`, `file://localhost/tmp/x`), percent-escapes
/// decoded, a query or fragment dropped; `None` for another scheme or
/// host.
pub fn folder_of_uri(uri: &str) -> Option<std::path::PathBuf> {
    // the scheme is case-insensitive; a query or a fragment names no folder
    let (scheme, rest) = uri.split_at_checked(5)?;
    if !scheme.eq_ignore_ascii_case("file:") {
        return None;
    }
    let rest = rest.split(['?', '#']).next().unwrap_or_default();
    let path = match rest.strip_prefix("//") {
        Some(authority_and_path) => {
            let slash = authority_and_path.find('/')?;
            let (host, path) = authority_and_path.split_at(slash);
            if !(host.is_empty() || host.eq_ignore_ascii_case("localhost")) {
                return None;
            }
            path
        }
        None => rest,
    };
    if !path.starts_with('/') {
        return None;
    }
    let bytes = path.as_bytes();
    let mut decoded = Vec::with_capacity(bytes.len());
    let mut i = 0;
    while i < bytes.len() {
        if bytes[i] == b'%' {
            let hex = std::str::from_utf8(bytes.get(i + 1..i + 3)?).ok()?;
            decoded.push(u8::from_str_radix(hex, 16).ok()?);
            i += 3;
        } else {
            decoded.push(bytes[i]);
            i += 1;
        }
    }
    use std::os::unix::ffi::OsStringExt;
    Some(std::ffi::OsString::from_vec(decoded).into())
}

/// The addresses of the instances `instantiate` made and `free_instance`
/// has not freed: every entry point checks its component against it, so a
/// host that frees an instance twice or steps a freed one gets `fmi2Error`
/// instead of a crash (FMI 2.0 leaves that undefined; a new instance at a
/// freed one's address is not told apart).
static LIVE: std::sync::Mutex<Vec<usize>> = std::sync::Mutex::new(Vec::new());

/// Whether `c` is a live instance.
fn live(c: RawComponent) -> bool {
    !c.is_null() && LIVE.lock().is_ok_and(|live| live.contains(&(c as usize)))
}

/// What the host's `fmi2Component` points to.
struct Slave {
    component: Box<dyn Component>,
    name: CString,
    callbacks: CallbackFunctions,
    logging: bool,
}

impl Slave {
    /// Send `message` to the host's logger (if it gave one).
    fn log(&self, status: Status, category: &str, message: &str) {
        log(&self.callbacks, &self.name, status, category, message);
    }
}

/// `logger(env, name, status, category, "%s", message)`: the message is
/// never read as a format string.
fn log(callbacks: &CallbackFunctions, name: &CStr, status: Status, category: &str, message: &str) {
    let Some(logger) = callbacks.logger else { return };
    let category = CString::new(category).unwrap_or_default();
    let message = CString::new(message.replace('\0', " ")).unwrap_or_default();
    // SAFETY: the host's logger, called as FMI 2.0 specifies, with
    // NUL-terminated strings that live across the call
    unsafe {
        logger(
            callbacks.component_environment,
            name.as_ptr(),
            status as c_int,
            category.as_ptr(),
            c"%s".as_ptr(),
            message.as_ptr(),
        );
    }
}

/// A C string argument, if not null and UTF-8.
unsafe fn text<'a>(s: FmiString) -> Option<&'a str> {
    if s.is_null() {
        return None;
    }
    // SAFETY: the host passes NUL-terminated strings (FMI 2.0)
    unsafe { CStr::from_ptr(s) }.to_str().ok()
}

/// Run `f` on the slave behind `c`; failures and panics are logged and
/// become `fmi2Error`.
unsafe fn with_slave(c: RawComponent, what: &str, f: impl FnOnce(&mut dyn Component) -> Result<(), String>) -> Status {
    if !live(c) {
        return Status::Error;
    }
    // SAFETY: `c` came from `instantiate` and was not freed (FMI 2.0)
    let slave = unsafe { &mut *c.cast::<Slave>() };
    let result = catch_unwind(AssertUnwindSafe(|| f(slave.component.as_mut())));
    match result {
        Ok(Ok(())) => match slave.component.take_warning() {
            Some(warning) => {
                slave.log(Status::Warning, "logStatusWarning", &format!("{what}: {warning}"));
                Status::Warning
            }
            None => Status::Ok,
        },
        Ok(Err(message)) => {
            slave.log(Status::Error, "logStatusError", &format!("{what}: {message}"));
            Status::Error
        }
        Err(_) => {
            slave.log(
                Status::Error,
                "logStatusError",
                &format!("{what}: internal error (panic); the instance must be reset"),
            );
            Status::Error
        }
    }
}

/// A slice from a host array, empty for `n = 0` (the pointer may be null
/// then); `None` for a null pointer with `n > 0`.
unsafe fn slice<'a, T>(p: *const T, n: usize) -> Option<&'a [T]> {
    match (p.is_null(), n) {
        (_, 0) => Some(&[]),
        (true, _) => None,
        // SAFETY: the host passes `n` valid elements (FMI 2.0)
        (false, _) => Some(unsafe { std::slice::from_raw_parts(p, n) }),
    }
}

/// The mutable counterpart of [`slice`].
unsafe fn slice_mut<'a, T>(p: *mut T, n: usize) -> Option<&'a mut [T]> {
    match (p.is_null(), n) {
        (_, 0) => Some(&mut []),
        (true, _) => None,
        // SAFETY: as `slice`
        (false, _) => Some(unsafe { std::slice::from_raw_parts_mut(p, n) }),
    }
}

/// `fmi2GetTypesPlatform`.
pub fn get_types_platform() -> *const c_char {
    c"default".as_ptr()
}

/// `fmi2GetVersion`.
pub fn get_version() -> *const c_char {
    c"2.0".as_ptr()
}

/// `fmi2Instantiate`: the entry whose GUID is `guid`, as a co-simulation
/// slave; null (with a logged reason) otherwise.
///
/// # Safety
/// The arguments as FMI 2.0 specifies them.
pub unsafe fn instantiate(
    entries: &[Entry],
    instance_name: FmiString,
    fmu_type: FmuType,
    guid: FmiString,
    resource_location: FmiString,
    callbacks: *const CallbackFunctions,
    logging_on: Boolean,
) -> RawComponent {
    if callbacks.is_null() {
        return ptr::null_mut();
    }
    // SAFETY: checked for null; the host's struct (FMI 2.0)
    let callbacks = unsafe { *callbacks };
    let name = CString::new(unsafe { text(instance_name) }.unwrap_or("crane")).unwrap_or_default();
    let result = catch_unwind(AssertUnwindSafe(|| -> Result<Box<dyn Component>, String> {
        if fmu_type != fmi2::CO_SIMULATION {
            return Err("this FMU supports co-simulation only (fmi2CoSimulation)".into());
        }
        let guid = unsafe { text(guid) }.ok_or("no GUID given")?;
        let packaged = packaged_run(unsafe { text(resource_location) })?;
        for entry in entries {
            // a packaged run names its crane: the other entries pass
            let Some((_, entry_guid)) = (entry.description)(packaged.as_deref())? else {
                continue;
            };
            if entry_guid == guid {
                return (entry.instantiate)(packaged.as_deref());
            }
        }
        let cranes = entries.iter().map(|e| e.name).collect::<Vec<_>>().join(", ");
        Err(match &packaged {
            Some(_) => format!(
                "GUID {guid} is not that of this library's crane with the run in resources/{}: the run's text \
                 enters the GUID, so an edited resources/{0} (or a binary it was not packaged with) is refused; \
                 package the FMU anew (`crane fmu MODEL --scenario FILE`)",
                crate::start::RESOURCE
            ),
            None => {
                let given = if resource_location.is_null() {
                    "gave none".to_string()
                } else {
                    match unsafe { text(resource_location) } {
                        Some("") => "gave an empty one".to_string(),
                        Some(location) => format!("gave {location}, where there is none"),
                        None => "gave one that is not UTF-8".to_string(),
                    }
                };
                format!(
                    "GUID {guid} matches none of this library's cranes ({cranes}) without a packaged run; an FMU \
                     packaged with a scenario reads its resources/{} from the resource location, of which the host \
                     {given}; was the FMU packaged with this binary?",
                    crate::start::RESOURCE
                )
            }
        })
    }));
    match result {
        Ok(Ok(component)) => {
            let slave = Box::new(Slave {
                component,
                name,
                callbacks,
                logging: logging_on != 0,
            });
            let c: RawComponent = Box::into_raw(slave).cast();
            if let Ok(mut live) = LIVE.lock() {
                live.push(c as usize);
            }
            c
        }
        Ok(Err(message)) => {
            log(
                &callbacks,
                &name,
                Status::Error,
                "logStatusError",
                &format!("fmi2Instantiate: {message}"),
            );
            ptr::null_mut()
        }
        Err(_) => {
            log(
                &callbacks,
                &name,
                Status::Error,
                "logStatusError",
                "fmi2Instantiate: internal error (panic)",
            );
            ptr::null_mut()
        }
    }
}

/// `fmi2FreeInstance`.
///
/// # Safety
/// `c` from [`instantiate`], not freed before.
pub unsafe fn free_instance(c: RawComponent) {
    let was_live = LIVE
        .lock()
        .is_ok_and(|mut live| match live.iter().position(|&a| a == c as usize) {
            Some(k) => {
                live.swap_remove(k);
                true
            }
            None => false,
        });
    if was_live {
        // SAFETY: made by `Box::into_raw` in `instantiate`
        let slave = unsafe { Box::from_raw(c.cast::<Slave>()) };
        let _ = catch_unwind(AssertUnwindSafe(move || drop(slave)));
    }
}

/// `fmi2SetDebugLogging`: whether informational messages are logged
/// (errors always are).
///
/// # Safety
/// `c` from [`instantiate`].
pub unsafe fn set_debug_logging(c: RawComponent, logging_on: Boolean) -> Status {
    if !live(c) {
        return Status::Error;
    }
    // SAFETY: as `with_slave`
    unsafe { (*c.cast::<Slave>()).logging = logging_on != 0 };
    Status::Ok
}

/// `fmi2SetupExperiment`.
///
/// # Safety
/// `c` from [`instantiate`].
pub unsafe fn setup_experiment(c: RawComponent, start_time: Real) -> Status {
    unsafe { with_slave(c, "fmi2SetupExperiment", |s| s.setup_experiment(start_time)) }
}

/// `fmi2EnterInitializationMode`.
///
/// # Safety
/// `c` from [`instantiate`].
pub unsafe fn enter_initialization_mode(c: RawComponent) -> Status {
    unsafe { with_slave(c, "fmi2EnterInitializationMode", |s| s.enter_initialization_mode()) }
}

/// `fmi2ExitInitializationMode`: the crane, its consistent start and stepper.
///
/// # Safety
/// `c` from [`instantiate`].
pub unsafe fn exit_initialization_mode(c: RawComponent) -> Status {
    let status = unsafe { with_slave(c, "fmi2ExitInitializationMode", |s| s.exit_initialization_mode()) };
    if matches!(status, Status::Ok | Status::Warning) {
        // SAFETY: as `with_slave` (not null: the call succeeded)
        let slave = unsafe { &*c.cast::<Slave>() };
        if slave.logging {
            slave.log(
                Status::Ok,
                "logAll",
                &format!("consistent start found at t = {} s", slave.component.time()),
            );
        }
    }
    status
}

/// `fmi2Terminate`.
///
/// # Safety
/// `c` from [`instantiate`].
pub unsafe fn terminate(c: RawComponent) -> Status {
    unsafe { with_slave(c, "fmi2Terminate", |s| s.terminate()) }
}

/// `fmi2Reset`.
///
/// # Safety
/// `c` from [`instantiate`].
pub unsafe fn reset(c: RawComponent) -> Status {
    unsafe {
        with_slave(c, "fmi2Reset", |s| {
            s.reset();
            Ok(())
        })
    }
}

/// `fmi2GetReal`.
///
/// # Safety
/// `c` from [`instantiate`]; `vr` and `value` hold `nvr` elements.
pub unsafe fn get_real(c: RawComponent, vr: *const ValueReference, nvr: usize, value: *mut Real) -> Status {
    unsafe {
        with_slave(c, "fmi2GetReal", |s| {
            let (vr, value) = (
                slice(vr, nvr).ok_or("null array")?,
                slice_mut(value, nvr).ok_or("null array")?,
            );
            s.get_real(vr, value)
        })
    }
}

/// `fmi2SetReal`.
///
/// # Safety
/// `c` from [`instantiate`]; `vr` and `value` hold `nvr` elements.
pub unsafe fn set_real(c: RawComponent, vr: *const ValueReference, nvr: usize, value: *const Real) -> Status {
    unsafe {
        with_slave(c, "fmi2SetReal", |s| {
            let (vr, value) = (
                slice(vr, nvr).ok_or("null array")?,
                slice(value, nvr).ok_or("null array")?,
            );
            s.set_real(vr, value)
        })
    }
}

/// `fmi2GetInteger`.
///
/// # Safety
/// `c` from [`instantiate`]; `vr` and `value` hold `nvr` elements.
pub unsafe fn get_integer(c: RawComponent, vr: *const ValueReference, nvr: usize, value: *mut Integer) -> Status {
    unsafe {
        with_slave(c, "fmi2GetInteger", |s| {
            let (vr, value) = (
                slice(vr, nvr).ok_or("null array")?,
                slice_mut(value, nvr).ok_or("null array")?,
            );
            s.get_integer(vr, value)
        })
    }
}

/// `fmi2SetInteger`.
///
/// # Safety
/// `c` from [`instantiate`]; `vr` and `value` hold `nvr` elements.
pub unsafe fn set_integer(c: RawComponent, vr: *const ValueReference, nvr: usize, value: *const Integer) -> Status {
    unsafe {
        with_slave(c, "fmi2SetInteger", |s| {
            let (vr, value) = (
                slice(vr, nvr).ok_or("null array")?,
                slice(value, nvr).ok_or("null array")?,
            );
            s.set_integer(vr, value)
        })
    }
}

/// `fmi2Get/SetBoolean`, `fmi2Get/SetString`: the FMU has no such
/// variables, so only empty requests succeed.
///
/// # Safety
/// `c` from [`instantiate`].
pub unsafe fn no_variables(c: RawComponent, what: &str, nvr: usize) -> Status {
    unsafe {
        with_slave(c, what, |_| {
            if nvr == 0 {
                Ok(())
            } else {
                Err("this FMU has no variables of that type".into())
            }
        })
    }
}

/// A function this FMU does not provide (FMU state, directional
/// derivatives, input derivatives, asynchronous steps).
///
/// # Safety
/// `c` from [`instantiate`].
pub unsafe fn unsupported(c: RawComponent, what: &str) -> Status {
    unsafe {
        with_slave(c, what, |_| {
            Err("not supported by this FMU (see its capability flags)".into())
        })
    }
}

/// `fmi2DoStep`.
///
/// # Safety
/// `c` from [`instantiate`].
pub unsafe fn do_step(c: RawComponent, current_communication_point: Real, communication_step_size: Real) -> Status {
    unsafe {
        with_slave(c, "fmi2DoStep", |s| {
            s.do_step(current_communication_point, communication_step_size)
        })
    }
}

/// `fmi2GetStatus` and the typed variants: only `fmi2GetRealStatus` with
/// `fmi2LastSuccessfulTime` and `fmi2GetBooleanStatus` with
/// `fmi2Terminated` answer (steps are synchronous).
///
/// # Safety
/// `c` from [`instantiate`]; `value` valid.
pub unsafe fn get_real_status(c: RawComponent, kind: StatusKind, value: *mut Real) -> Status {
    unsafe {
        with_slave(c, "fmi2GetRealStatus", |s| {
            if kind != fmi2::LAST_SUCCESSFUL_TIME || value.is_null() {
                return Err("only fmi2LastSuccessfulTime is available".into());
            }
            *value = s.time();
            Ok(())
        })
    }
}

/// `fmi2GetBooleanStatus`.
///
/// # Safety
/// `c` from [`instantiate`]; `value` valid.
pub unsafe fn get_boolean_status(c: RawComponent, kind: StatusKind, value: *mut Boolean) -> Status {
    unsafe {
        with_slave(c, "fmi2GetBooleanStatus", |s| {
            if kind != fmi2::TERMINATED || value.is_null() {
                return Err("only fmi2Terminated is available".into());
            }
            *value = Boolean::from(s.terminated());
            Ok(())
        })
    }
}
