//! Derived outputs: the 3D cranes report the slewing angle `phi` as a column
//! of results.csv.

use std::process::Command;

#[test]
fn navy_3d_reports_the_slewing_angle() {
    let out = tempfile::tempdir().unwrap();
    let status = Command::new(env!("CARGO_BIN_EXE_crane"))
        .args(["run", "navy-3d", "--dt", "0.1", "--quiet", "--out"])
        .arg(out.path())
        .status()
        .unwrap();
    assert!(status.success());
    let csv = std::fs::read_to_string(out.path().join("results.csv")).unwrap();
    let header: Vec<&str> = csv.lines().next().unwrap().split(',').collect();
    assert_eq!(header.last(), Some(&"phi"));
    let last: Vec<f64> = csv
        .lines()
        .last()
        .unwrap()
        .split(',')
        .map(|v| v.parse().unwrap())
        .collect();
    // at rest at the end the boom points at the load (2, 5): phi = atan2(5, 2),
    // exact up to round-off (the massless pulley fixes the geometry algebraically)
    let phi = *last.last().unwrap();
    assert!((phi - 5f64.atan2(2.0)).abs() < 1e-9, "phi = {phi}");
    // the first value: the boom along the x axis at the start (eq. 87)
    let first: Vec<f64> = csv
        .lines()
        .nth(1)
        .unwrap()
        .split(',')
        .map(|v| v.parse().unwrap())
        .collect();
    assert!(first.last().unwrap().abs() < 1e-12);
}
