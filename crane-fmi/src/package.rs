//! The FMU archive: `modelDescription.xml`, the shared library as
//! `binaries/linux64/<modelIdentifier>.so` and, for a packaged run, the
//! run as `resources/start.toml` ([`Start`]), zipped (the `zip` crate).
//! Written to a temporary file next to the target and renamed, so a failed
//! packaging leaves no partial FMU.

use std::fs::File;
use std::io::Write;
use std::path::{Path, PathBuf};

use crane_models::Crane;

use crate::description::{model_description, model_identifier};
use crate::start::{RESOURCE, Start};

/// Why an FMU could not be written.
#[derive(Debug, thiserror::Error)]
pub enum PackageError {
    /// The crane's variables clash.
    #[error(transparent)]
    Variables(#[from] crate::variables::TableError),
    /// Reading the library or writing the archive.
    #[error("{context}: {source}")]
    Io {
        /// What was being done.
        context: String,
        /// The error.
        source: std::io::Error,
    },
    /// The library is not an FMU's shared library.
    #[error("{path} is not an FMU library: {reason}")]
    NotALibrary {
        /// The file given.
        path: PathBuf,
        /// What it lacks.
        reason: &'static str,
    },
    /// The destination exists and is no regular file (a device, a FIFO,
    /// a symbolic link, a folder): it is not replaced.
    #[error("{path} exists and is {kind}, not a regular file: give the path of an .fmu file to write")]
    NotAFile {
        /// The destination given.
        path: PathBuf,
        /// What it is.
        kind: &'static str,
    },
    /// The zip writer.
    #[error("writing {path}: {source}")]
    Zip {
        /// The archive.
        path: PathBuf,
        /// The error.
        source: zip::result::ZipError,
    },
}

fn io(context: impl Into<String>) -> impl FnOnce(std::io::Error) -> PackageError {
    let context = context.into();
    move |source| PackageError::Io { context, source }
}

/// Write the FMU of crane `C` starting from `start` (its default run,
/// [`Start::default_for`], or a packaged one, [`Start::packaged`]) to
/// `out`, with the shared library `library` (a `cdylib` that calls
/// [`export_fmu!`](crate::export_fmu) on `C`).
pub fn package<C: Crane<N, M, A>, const N: usize, const M: usize, const A: usize>(
    library: &Path,
    out: &Path,
    start: &Start<A>,
) -> Result<(), PackageError> {
    let bytes = archive::<C, N, M, A>(library, start)?;
    write_file(&bytes, out)
}

/// The FMU of crane `C` starting from `start`, with the shared library
/// `library`, as the bytes of its archive (for a caller that writes files
/// its own way).
pub fn archive<C: Crane<N, M, A>, const N: usize, const M: usize, const A: usize>(
    library: &Path,
    start: &Start<A>,
) -> Result<Vec<u8>, PackageError> {
    let (xml, _) = model_description::<C, N, M, A>(start)?;
    let binary = std::fs::read(library).map_err(io(format!("reading the FMU library {}", library.display())))?;
    check_library(&binary).map_err(|reason| PackageError::NotALibrary {
        path: library.to_path_buf(),
        reason,
    })?;
    let resource = start.resource.as_deref().map(|text| (RESOURCE, text.as_bytes()));
    zip_archive(&xml, &model_identifier(C::NAME), &binary, resource)
}

/// Why `binary` cannot be an FMU's shared library for linux64, if it cannot:
/// an ELF file that names the FMI 2.0 entry points (their symbol names are
/// in its dynamic symbol table).
fn check_library(binary: &[u8]) -> Result<(), &'static str> {
    if !binary.starts_with(b"\x7fELF") {
        return Err(if binary.is_empty() {
            "the file is empty"
        } else {
            "not an ELF shared library"
        });
    }
    let names = |symbol: &[u8]| binary.windows(symbol.len()).any(|w| w == symbol);
    if !(names(b"fmi2Instantiate") && names(b"fmi2DoStep")) {
        return Err("it does not export the FMI 2.0 functions (fmi2Instantiate, fmi2DoStep)");
    }
    Ok(())
}

/// Zip `xml`, `binary` and a resource `(name, contents)` in memory.
fn zip_archive(
    xml: &str,
    identifier: &str,
    binary: &[u8],
    resource: Option<(&str, &[u8])>,
) -> Result<Vec<u8>, PackageError> {
    let zip_error = |source| PackageError::Zip {
        path: PathBuf::from(format!("{identifier}.fmu")),
        source,
    };
    let mut zip = zip::ZipWriter::new(std::io::Cursor::new(Vec::new()));
    let options = zip::write::SimpleFileOptions::default().compression_method(zip::CompressionMethod::Deflated);
    zip.start_file("modelDescription.xml", options).map_err(zip_error)?;
    zip.write_all(xml.as_bytes())
        .map_err(io("writing modelDescription.xml"))?;
    let so = options.unix_permissions(0o755);
    zip.start_file(format!("binaries/linux64/{identifier}.so"), so)
        .map_err(zip_error)?;
    zip.write_all(binary).map_err(io("writing the library"))?;
    if let Some((name, contents)) = resource {
        zip.start_file(format!("resources/{name}"), options)
            .map_err(zip_error)?;
        zip.write_all(contents)
            .map_err(io(format!("writing resources/{name}")))?;
    }
    Ok(zip.finish().map_err(zip_error)?.into_inner())
}

/// Write `bytes` to `out` through a temporary file beside it, renamed when
/// whole.
fn write_file(bytes: &[u8], out: &Path) -> Result<(), PackageError> {
    if let Some(parent) = out.parent().filter(|p| !p.as_os_str().is_empty()) {
        std::fs::create_dir_all(parent).map_err(io(format!("creating {}", parent.display())))?;
    }
    if let Some(kind) = crane_models::files::not_a_regular_file(out) {
        return Err(PackageError::NotAFile {
            path: out.to_path_buf(),
            kind,
        });
    }
    // a name of this process's own beside the destination: two packagers
    // writing the same FMU at once each rename a whole archive (the last
    // one wins), never one archive written by both
    static SERIAL: std::sync::atomic::AtomicUsize = std::sync::atomic::AtomicUsize::new(0);
    let serial = SERIAL.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
    let partial = out.with_extension(format!("fmu.{}-{serial}.partial", std::process::id()));
    let result = (|| {
        let mut file = File::create(&partial).map_err(io(format!("creating {}", partial.display())))?;
        file.write_all(bytes)
            .map_err(io(format!("writing {}", partial.display())))?;
        std::fs::rename(&partial, out).map_err(io(format!("renaming to {}", out.display())))
    })();
    if result.is_err() {
        let _ = std::fs::remove_file(&partial);
    }
    result
}
