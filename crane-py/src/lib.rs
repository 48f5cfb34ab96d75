//! The Python package `crane`: the built-in cranes as a Python module
//! (see `crane::python` for what it offers).
//!
//! ```python
//! import crane
//! r = crane.run("navy-planar", dt=0.01, scheme="bdf4")
//! r.u.shape                   # (401, 2): one row per step, one column per input
//! r.summary["peak_torque"]    # the dict of summary.json
//! r.warnings                  # what the audit found, one string each
//! ```

crane::python::export_module!(registry = crane::models::registry::BuiltIn, name = "crane");
