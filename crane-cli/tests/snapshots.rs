//! `crane run` writes `snapshots.svg` (the crane at 7 instants, like the
//! paper's Figs. 10, 19, 23, 26) for a planar and a 3D crane.

use std::process::Command;

/// Run `crane run MODEL --dt DT` into a temporary directory; return the text
/// of its `snapshots.svg`.
fn snapshots(model: &str, dt: &str) -> String {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out");
    let result = Command::new(env!("CARGO_BIN_EXE_crane"))
        .args(["run", model, "--dt", dt, "--quiet", "--out"])
        .arg(&out)
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .output()
        .expect("run crane");
    assert!(
        result.status.success(),
        "crane run {model} failed: {}",
        String::from_utf8_lossy(&result.stderr)
    );
    let path = out.join("snapshots.svg");
    let size = std::fs::metadata(&path)
        .unwrap_or_else(|e| panic!("{}: {e}", path.display()))
        .len();
    assert!(size > 1024, "{} has only {size} bytes", path.display());
    std::fs::read_to_string(&path).unwrap()
}

/// Whether `svg` has a text element reading exactly `text`.
fn has_text(svg: &str, text: &str) -> bool {
    svg.contains(&format!(">{text}<")) || svg.contains(&format!(">\n{text}\n<"))
}

/// The checks common to every model: an SVG with 7 instants labelled
/// `t = ... s` in the legend, the pulley and the load drawn at each (three
/// circles per instant: the pulley's fill and ring, the load), the legend.
fn check(svg: &str, tf: f64) {
    assert!(svg.contains("<svg"), "not an SVG");
    // the legend's labels (the title's "dt = ..." is not one of them)
    let labels: Vec<&str> = svg
        .match_indices(">t = ")
        .chain(svg.match_indices("\nt = "))
        .map(|(i, _)| svg[i + 1..].split(['<', '\n']).next().unwrap())
        .collect();
    assert_eq!(labels.len(), 7, "snapshot labels: {labels:?}");
    assert_eq!(labels[0], "t = 0.00 s", "{labels:?}");
    assert_eq!(labels[6], format!("t = {tf:.2} s"), "{labels:?}");
    assert!(svg.matches("<circle").count() >= 7 * 3, "too few pulley/load dots");
    assert!(svg.contains("[m]"), "no axis unit");
    for needle in [
        "load C",
        "main pulley B",
        "path of the load",
        "trajectory of the pulley",
    ] {
        assert!(has_text(svg, needle), "lacks {needle:?}");
    }
}

#[test]
fn planar_crane_snapshots() {
    let svg = snapshots("navy-planar", "0.1");
    check(&svg, 4.0);
    // the winch A and the boom tip P are labelled
    assert!(has_text(&svg, "A") && has_text(&svg, "P"), "fixed points not labelled");
    assert!(has_text(&svg, "x [m]") && has_text(&svg, "z [m]"), "axis labels");
    assert!(svg.contains("equal scales"));
}

#[test]
fn crane_3d_snapshots() {
    let svg = snapshots("navy-3d-pulley", "0.1");
    check(&svg, 20.0);
    assert!(svg.contains("cabinet projection"));
    assert!(has_text(&svg, "O"), "boom foot not labelled");
}
