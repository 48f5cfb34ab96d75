//! Write `planar-gantry.fmu` (and the API's run of the same move, for the
//! check) into the directory given: `cargo run --release --bin planar-gantry-package -- DIR`
//! after `cargo build --release` built the library next to this binary.

use std::io::Write;

use crane::prelude::*;
use planar_gantry_fmu::{Gantry, PlanarGantry};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let dir = std::path::PathBuf::from(std::env::args().nth(1).unwrap_or_else(|| ".".into()));
    let library = std::env::current_exe()?.with_file_name("libplanar_gantry_fmu.so");
    let fmu = dir.join("planar-gantry.fmu");
    crane::fmi::package::package::<PlanarGantry, 4, 1, 2>(&library, &fmu)?;
    println!("wrote {}", fmu.display());

    // the same move through the API: the FMU must reproduce it
    let crane = Gantry::default();
    let path = Poly9::new(0.0, 5.0, SVector::from([0.0, -5.0]), SVector::from([4.0, -3.0]))?;
    let start = init::check_start(&crane, &path, 0.0, &[0.0, 5.0], None)?;
    let run = simulate(&crane, &path, &start, &Options::new(0.01, 5.0)?)?;
    let mut csv = std::fs::File::create(dir.join("planar-gantry-api.csv"))?;
    writeln!(csv, "t,u1,u2,s,L,x,z")?;
    for s in &run.states {
        writeln!(csv, "{:?},{:?},{:?},{:?},{:?},{:?},{:?}", s.t, s.u[0], s.u[1], s.q[0], s.q[1], s.q[2], s.q[3])?;
    }
    println!("wrote {}", dir.join("planar-gantry-api.csv").display());
    Ok(())
}
