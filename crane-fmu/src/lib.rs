//! The FMI 2.0 co-simulation library of every built-in crane: one shared
//! library, `libcrane_fmu.so`, that `crane fmu MODEL` puts into each FMU as
//! `binaries/linux64/<model>.so`; the GUID in the FMU's description picks
//! the crane when the host instantiates it.

crane_fmi::export_fmu!(entries = crane_fmi::built_in);
