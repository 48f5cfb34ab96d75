//! `snapshots.svg`: the crane drawn at a few instants of a run, with the
//! load's path and the pulley's trajectory, like the paper's Figs. 10, 19, 23
//! and 26.
//!
//! Each built-in model has a small geometric description (its `drawing`, in
//! crane-models): its fixed points (winches, boom foot and tip) from the
//! parameters, and for a state `q` the boom, the ropes (straight lines
//! between winch points, the main pulley B and the load C), B and C. The planar cranes are drawn in the
//! (x, z) plane, the 3D cranes in a cabinet projection of (x, y, z) (y drawn
//! at 45 degrees, shortened by half); both with equal scales on both axes.

use crane_runtime::{ModelInfo, Solution};
use plotters::coord::Shift;
use plotters::coord::types::RangedCoordf64;
use plotters::element::{DashedPathElement, Drawable, PointCollection};
use plotters::prelude::*;

use crate::CliError;
use crate::plot::register_font;

/// Number of instants drawn, evenly spaced from `t0` to `tf`.
pub const SNAPSHOTS: usize = 7;

/// The built-in models' drawings live with the models
/// (`Crane::drawing` in crane-models).
use crane_models::drawing::{Drawing as Geometry, P3, Pose};

/// Cabinet projection for the 3D cranes: y at 45 degrees, shortened by half.
const OBLIQUE: f64 = 0.5 * std::f64::consts::FRAC_1_SQRT_2;

fn project(spatial: bool, p: P3) -> (f64, f64) {
    if spatial {
        (p[0] + OBLIQUE * p[1], p[2] + OBLIQUE * p[1])
    } else {
        (p[0], p[2])
    }
}

/// Colour of snapshot `i` of `n`: light blue (early) to near black (late).
fn shade(i: usize, n: usize) -> RGBColor {
    let f = if n > 1 { i as f64 / (n - 1) as f64 } else { 1.0 };
    let mix = |a: f64, b: f64| (a + (b - a) * f).round() as u8;
    RGBColor(mix(150.0, 10.0), mix(190.0, 20.0), mix(235.0, 70.0))
}

const LOAD_PATH: RGBColor = RGBColor(214, 39, 40);
const PULLEY_PATH: RGBColor = RGBColor(44, 160, 44);
const BOOM: RGBColor = RGBColor(110, 110, 110);

/// Indices of `count` states evenly spaced in time over the run.
fn instants(times: &[f64], count: usize) -> Vec<usize> {
    let (Some(&t0), Some(&tf)) = (times.first(), times.last()) else {
        return Vec::new();
    };
    let mut out: Vec<usize> = (0..count)
        .map(|j| {
            let t = t0 + (tf - t0) * j as f64 / (count - 1).max(1) as f64;
            // the state closest to t
            let i = times.partition_point(|&s| s < t).min(times.len() - 1);
            if i > 0 && (times[i - 1] - t).abs() <= (times[i] - t).abs() {
                i - 1
            } else {
                i
            }
        })
        .collect();
    out.dedup();
    out
}

/// `snapshots.svg` of a run drawn with `drawing`; `None` for a model
/// without one.
pub fn svg<const N: usize, const M: usize, const A: usize>(
    drawing: Option<Geometry>,
    solution: &Solution<N, M, A>,
) -> Result<Option<String>, CliError> {
    let info = &solution.info;
    let Some(geometry) = drawing else {
        return Ok(None);
    };
    let times: Vec<f64> = solution.states.iter().map(|s| s.t).collect();
    let picked = instants(&times, SNAPSHOTS);
    if picked.is_empty() {
        return Ok(None);
    }
    let poses: Vec<(f64, Pose)> = picked
        .iter()
        .map(|&i| (times[i], (geometry.pose)(solution.states[i].q.as_slice())))
        .collect();
    // the trajectories, at most ~800 points each
    let stride = (solution.states.len() / 800).max(1);
    let along: Vec<Pose> = solution
        .states
        .iter()
        .enumerate()
        .filter(|(i, _)| i % stride == 0 || *i + 1 == solution.states.len())
        .map(|(_, s)| (geometry.pose)(s.q.as_slice()))
        .collect();
    draw(info, solution.dt, &geometry, &poses, &along).map(Some)
}

/// The chart of the snapshots: data coordinates in metres.
type Chart<'a, 'b> = ChartContext<'a, SVGBackend<'b>, Cartesian2d<RangedCoordf64, RangedCoordf64>>;

/// The legend column.
type Area<'a> = DrawingArea<SVGBackend<'a>, Shift>;

/// What `snapshots.svg` failed at, as the command's error.
fn failed(e: impl ToString) -> CliError {
    CliError::Output {
        what: "snapshots.svg".into(),
        message: e.to_string(),
    }
}

/// The data window and the plot size: everything drawn inside, padded,
/// with equal scales on both axes (a fixed plot width, the height from the
/// data's aspect ratio within limits, the other range widened to fill).
struct View {
    x: (f64, f64),
    z: (f64, f64),
    px_per_m: f64,
    plot_w: u32,
    plot_h: u32,
}

impl View {
    /// The view of `points` (projected), or an error if none is finite.
    fn of(points: Vec<(f64, f64)>) -> Result<Self, CliError> {
        let points: Vec<(f64, f64)> = points
            .into_iter()
            .filter(|(x, z)| x.is_finite() && z.is_finite())
            .collect();
        if points.is_empty() {
            return Err(failed("no finite positions to draw"));
        }
        let (mut x0, mut x1, mut z0, mut z1) = points.iter().fold(
            (f64::INFINITY, f64::NEG_INFINITY, f64::INFINITY, f64::NEG_INFINITY),
            |(a, b, c, d), &(x, z)| (a.min(x), b.max(x), c.min(z), d.max(z)),
        );
        let pad = 0.06 * (x1 - x0).max(z1 - z0).max(1.0);
        (x0, x1, z0, z1) = (x0 - pad, x1 + pad, z0 - pad, z1 + pad);
        const PLOT_W: f64 = 700.0;
        let (min_h, max_h) = (380.0, 820.0);
        let mut px_per_m = PLOT_W / (x1 - x0);
        let mut plot_h = (z1 - z0) * px_per_m;
        if plot_h > max_h {
            plot_h = max_h;
            px_per_m = max_h / (z1 - z0);
            let widen = (PLOT_W / px_per_m - (x1 - x0)) / 2.0;
            (x0, x1) = (x0 - widen, x1 + widen);
        } else if plot_h < min_h {
            plot_h = min_h;
            let widen = (min_h / px_per_m - (z1 - z0)) / 2.0;
            (z0, z1) = (z0 - widen, z1 + widen);
        }
        Ok(Self {
            x: (x0, x1),
            z: (z0, z1),
            px_per_m,
            plot_w: PLOT_W.round() as u32,
            plot_h: plot_h.round() as u32,
        })
    }
}

const MARGIN: u32 = 15;
const Y_LABELS: u32 = 70;
const X_LABELS: u32 = 50;
const CAPTION: u32 = 40;
const LEGEND_W: u32 = 300;

/// Draw one series on the chart.
fn series<'b, E, S>(chart: &mut Chart<'_, 'b>, elements: S) -> Result<(), CliError>
where
    S: IntoIterator<Item = E>,
    for<'e> &'e E: PointCollection<'e, (f64, f64)>,
    E: Drawable<SVGBackend<'b>>,
{
    chart.draw_series(elements).map(|_| ()).map_err(failed)
}

fn draw(
    info: &ModelInfo,
    dt: f64,
    geometry: &Geometry,
    poses: &[(f64, Pose)],
    along: &[Pose],
) -> Result<String, CliError> {
    register_font();
    let spatial = geometry.spatial;
    let pr = |p: P3| project(spatial, p);
    // the extent of everything drawn
    let mut points: Vec<(f64, f64)> = Vec::new();
    for (_, pose) in poses {
        points.extend(pose.boom.iter().map(|&p| pr(p)));
        points.extend(pose.ropes.iter().flatten().map(|&p| pr(p)));
    }
    for pose in along {
        points.push(pr(pose.load));
        points.push(pr(pose.pulley));
    }
    points.extend(geometry.fixed.iter().map(|&(_, p)| pr(p)));
    let view = View::of(points)?;
    let left_w = view.plot_w + Y_LABELS + 2 * MARGIN;
    let height = view.plot_h + X_LABELS + 2 * MARGIN + CAPTION;
    let title = format!("{} - snapshots at {} instants (dt = {dt} s)", info.name, poses.len());
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, (left_w + LEGEND_W, height)).into_drawing_area();
        root.fill(&WHITE).map_err(failed)?;
        let root = root.titled(&title, ("sans-serif", 22)).map_err(failed)?;
        let (plot_area, legend_area) = root.split_horizontally(left_w);
        let mut chart = ChartBuilder::on(&plot_area)
            .margin(MARGIN)
            .x_label_area_size(X_LABELS)
            .y_label_area_size(Y_LABELS)
            .build_cartesian_2d(view.x.0..view.x.1, view.z.0..view.z.1)
            .map_err(failed)?;
        let (x_desc, z_desc) = if spatial {
            ("x + y/(2√2) [m]   (cabinet projection)", "z + y/(2√2) [m]")
        } else {
            ("x [m]", "z [m]")
        };
        chart
            .configure_mesh()
            .x_desc(x_desc)
            .y_desc(z_desc)
            .label_style(("sans-serif", 15))
            .light_line_style(RGBColor(240, 240, 240))
            .max_light_lines(4)
            .draw()
            .map_err(failed)?;
        draw_trajectories(&mut chart, along, &pr)?;
        draw_poses(&mut chart, poses, spatial, &pr)?;
        draw_fixed_points(&mut chart, geometry, view.px_per_m, &pr)?;
        draw_legend(&legend_area, geometry, poses)?;
        root.present().map_err(failed)?;
    }
    Ok(svg)
}

/// The load's path (solid) and the pulley's trajectory (dashed), thin,
/// under everything else.
fn draw_trajectories(chart: &mut Chart, along: &[Pose], pr: &impl Fn(P3) -> (f64, f64)) -> Result<(), CliError> {
    let load_path: Vec<(f64, f64)> = along.iter().map(|p| pr(p.load)).collect();
    let pulley_path: Vec<(f64, f64)> = along.iter().map(|p| pr(p.pulley)).collect();
    series(
        chart,
        LineSeries::new(load_path, ShapeStyle::from(&LOAD_PATH).stroke_width(1)),
    )?;
    series(
        chart,
        DashedLineSeries::new(pulley_path, 5, 3, ShapeStyle::from(&PULLEY_PATH).stroke_width(1)),
    )
}

/// The crane at each instant, early (light) to late (dark) so the late
/// ones are on top: boom, ropes, pulley, load.
fn draw_poses(
    chart: &mut Chart,
    poses: &[(f64, Pose)],
    spatial: bool,
    pr: &impl Fn(P3) -> (f64, f64),
) -> Result<(), CliError> {
    let n = poses.len();
    for (i, (_, pose)) in poses.iter().enumerate() {
        let color = shade(i, n);
        let boom_color = if spatial { color } else { BOOM };
        series(
            chart,
            std::iter::once(PathElement::new(
                pose.boom.iter().map(|&p| pr(p)).collect::<Vec<_>>(),
                ShapeStyle::from(&boom_color).stroke_width(5),
            )),
        )?;
        series(
            chart,
            pose.ropes
                .iter()
                .map(|r| PathElement::new(vec![pr(r[0]), pr(r[1])], ShapeStyle::from(&color).stroke_width(1))),
        )?;
        series(
            chart,
            [
                Circle::new(pr(pose.pulley), 4, ShapeStyle::from(&WHITE).filled()),
                Circle::new(pr(pose.pulley), 4, ShapeStyle::from(&color).stroke_width(2)),
                Circle::new(pr(pose.load), 6, ShapeStyle::from(&color).filled()),
            ],
        )?;
    }
    Ok(())
}

/// The fixed points (winches, boom foot and tip), labelled.
fn draw_fixed_points(
    chart: &mut Chart,
    geometry: &Geometry,
    px_per_m: f64,
    pr: &impl Fn(P3) -> (f64, f64),
) -> Result<(), CliError> {
    for &(label, p) in &geometry.fixed {
        let (x, z) = pr(p);
        let corners = [
            (x - 3.0 / px_per_m, z - 3.0 / px_per_m),
            (x + 3.0 / px_per_m, z + 3.0 / px_per_m),
        ];
        series(chart, [Rectangle::new(corners, ShapeStyle::from(&BLACK).filled())])?;
        let at = (
            x + 6.0 / px_per_m,
            z + if geometry.spatial { -4.0 } else { 22.0 } / px_per_m,
        );
        series(
            chart,
            std::iter::once(Text::new(label.to_string(), at, ("sans-serif", 16))),
        )?;
    }
    Ok(())
}

/// The legend column: what is drawn, then the instants, then the
/// projection's axes (3D) or a note on the scales (planar).
fn draw_legend(area: &Area, geometry: &Geometry, poses: &[(f64, Pose)]) -> Result<(), CliError> {
    let spatial = geometry.spatial;
    let n = poses.len();
    let text = |s: &str, y: i32, size: u32| {
        area.draw(&Text::new(s.to_string(), (10, y), ("sans-serif", size)))
            .map_err(failed)
    };
    let line = |y: i32, style: ShapeStyle, dashed: bool| {
        let sample = vec![(10, y + 8), (40, y + 8)];
        if dashed {
            area.draw(&DashedPathElement::new(sample, 5, 3, style))
        } else {
            area.draw(&PathElement::new(sample, style))
        }
        .map_err(failed)
    };
    let entry = |y: i32, s: &str| {
        area.draw(&Text::new(s.to_string(), (48, y), ("sans-serif", 14)))
            .map_err(failed)
    };
    let dark = shade(n - 1, n);
    let mut y = 20;
    line(
        y,
        ShapeStyle::from(&if spatial { dark } else { BOOM }).stroke_width(5),
        false,
    )?;
    entry(y, "boom")?;
    y += 22;
    line(y, ShapeStyle::from(&dark).stroke_width(1), false)?;
    entry(y, geometry.ropes)?;
    y += 22;
    area.draw(&Circle::new((25, y + 8), 4, ShapeStyle::from(&dark).stroke_width(2)))
        .map_err(failed)?;
    entry(y, "main pulley B")?;
    y += 22;
    area.draw(&Circle::new((25, y + 8), 6, ShapeStyle::from(&dark).filled()))
        .map_err(failed)?;
    entry(y, "load C")?;
    y += 22;
    line(y, ShapeStyle::from(&LOAD_PATH).stroke_width(1), false)?;
    entry(y, "path of the load")?;
    y += 22;
    line(y, ShapeStyle::from(&PULLEY_PATH).stroke_width(1), true)?;
    entry(y, "trajectory of the pulley")?;
    y += 22;
    area.draw(&Rectangle::new(
        [(22, y + 5), (28, y + 11)],
        ShapeStyle::from(&BLACK).filled(),
    ))
    .map_err(failed)?;
    entry(y, if spatial { "boom foot O" } else { "winches and boom tip" })?;
    y += 34;
    text("snapshots (light to dark):", y, 15)?;
    y += 24;
    for (i, (t, _)) in poses.iter().enumerate() {
        line(y, ShapeStyle::from(&shade(i, n)).stroke_width(4), false)?;
        entry(y, &format!("t = {t:.2} s"))?;
        y += 20;
    }
    y += 14;
    if spatial {
        text("cabinet projection: y drawn at", y, 13)?;
        text("45 degrees, shortened by 1/2:", y + 16, 13)?;
        // axis triad
        let (ox, oy) = (40, y + 110);
        let grey = ShapeStyle::from(&RGBColor(90, 90, 90)).stroke_width(2);
        for (label, (dx, dy)) in [("x", (60, 0)), ("y", (30, -30)), ("z", (0, -60))] {
            area.draw(&PathElement::new(vec![(ox, oy), (ox + dx, oy + dy)], grey))
                .map_err(failed)?;
            area.draw(&Text::new(label, (ox + dx + 4, oy + dy - 8), ("sans-serif", 15)))
                .map_err(failed)?;
        }
    } else {
        text("equal scales on x and z", y, 13)?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn instants_are_evenly_spaced_and_distinct() {
        let times: Vec<f64> = (0..=40).map(|i| i as f64 * 0.1).collect();
        let picked = instants(&times, 7);
        assert_eq!(picked.len(), 7);
        assert_eq!(picked.first(), Some(&0));
        assert_eq!(picked.last(), Some(&40));
        // few states: no duplicates
        assert_eq!(instants(&[0.0, 1.0, 2.0], 7), vec![0, 1, 2]);
    }

    #[test]
    fn planar_geometry_matches_the_constraints() {
        use crane_models::Crane;
        let model = crane_models::navy_planar::NavyPlanar::default();
        let g = crane_models::navy_planar::Description::drawing(&model).unwrap();
        // eq. (46): pulley at (0, -5), load at (0, -10)
        let q = [8.660254037844386, 10.0, 5.0, 0.0, -5.0, 0.0, -10.0];
        let pose = (g.pose)(&q);
        let len = |r: &[P3; 2]| ((r[0][0] - r[1][0]).powi(2) + (r[0][2] - r[1][2]).powi(2)).sqrt();
        assert!((len(&pose.ropes[0]) - q[0]).abs() < 1e-9, "L1");
        assert!((len(&pose.ropes[1]) - q[2]).abs() < 1e-9, "L0");
        assert!((len(&pose.ropes[2]) - (q[1] - q[2])).abs() < 1e-9, "L2 - L0");
    }
}
