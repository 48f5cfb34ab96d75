//! SVG plots of a run (plotters, with the DejaVu Sans font embedded so that
//! no system font library is needed).

use std::sync::Once;

use crane_runtime::{Solution, State};
use plotters::element::DashedPathElement;
use plotters::prelude::*;

use crate::CliError;

static FONT: Once = Once::new();

/// Register the embedded DejaVu Sans as `sans-serif` (once).
pub(crate) fn register_font() {
    FONT.call_once(|| {
        // the embedded font is valid TrueType; registration only fails on invalid data
        let _ = plotters::style::register_font("sans-serif", FontStyle::Normal, dejavu::sans::regular());
    });
}

/// One curve.
struct Series {
    name: String,
    points: Vec<(f64, f64)>,
    color: RGBColor,
    dashed: bool,
}

const PALETTE: [RGBColor; 8] = [
    RGBColor(31, 119, 180),
    RGBColor(255, 127, 14),
    RGBColor(44, 160, 44),
    RGBColor(214, 39, 40),
    RGBColor(148, 103, 189),
    RGBColor(140, 86, 75),
    RGBColor(227, 119, 194),
    RGBColor(127, 127, 127),
];

fn draw(title: &str, y_label: &str, series: &[Series]) -> Result<String, CliError> {
    register_font();
    let failed = |e: String| CliError::Output {
        what: format!("plot '{title}'"),
        message: e,
    };
    let (mut x_min, mut x_max, mut y_min, mut y_max) =
        (f64::INFINITY, f64::NEG_INFINITY, f64::INFINITY, f64::NEG_INFINITY);
    for s in series {
        for &(x, y) in &s.points {
            if x.is_finite() && y.is_finite() {
                x_min = x_min.min(x);
                x_max = x_max.max(x);
                y_min = y_min.min(y);
                y_max = y_max.max(y);
            }
        }
    }
    if !(x_min < x_max) {
        return Err(failed("no finite data to plot".into()));
    }
    if !(y_max - y_min).is_finite() {
        return Err(failed(format!(
            "values from {y_min:e} to {y_max:e} span more than a plot can"
        )));
    }
    let pad = ((y_max - y_min) * 0.05).max(1e-9 * y_max.abs().max(1.0));
    let (y_min, y_max) = (y_min - pad, y_max + pad);
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, (1000, 560)).into_drawing_area();
        root.fill(&WHITE).map_err(|e| failed(e.to_string()))?;
        // plot on the left, legend in its own column on the right so it never hides data
        let (plot_area, legend_area) = root.split_horizontally(820);
        let mut chart = ChartBuilder::on(&plot_area)
            .caption(title, ("sans-serif", 22))
            .margin(12)
            .x_label_area_size(45)
            .y_label_area_size(80)
            .build_cartesian_2d(x_min..x_max, y_min..y_max)
            .map_err(|e| failed(e.to_string()))?;
        chart
            .configure_mesh()
            .x_desc("t [s]")
            .y_desc(y_label)
            .label_style(("sans-serif", 15))
            .draw()
            .map_err(|e| failed(e.to_string()))?;
        for s in series {
            let style = ShapeStyle::from(&s.color).stroke_width(if s.dashed { 1 } else { 2 });
            if s.dashed {
                chart
                    .draw_series(DashedLineSeries::new(s.points.iter().copied(), 6, 4, style))
                    .map_err(|e| failed(e.to_string()))?;
            } else {
                chart
                    .draw_series(LineSeries::new(s.points.iter().copied(), style))
                    .map_err(|e| failed(e.to_string()))?;
            }
        }
        let mut y = 60;
        for s in series.iter().filter(|s| !s.name.is_empty()) {
            let style = ShapeStyle::from(&s.color).stroke_width(if s.dashed { 1 } else { 2 });
            let sample = vec![(8, y), (38, y)];
            if s.dashed {
                legend_area
                    .draw(&DashedPathElement::new(sample, 6, 4, style))
                    .map_err(|e| failed(e.to_string()))?;
            } else {
                legend_area
                    .draw(&PathElement::new(sample, style))
                    .map_err(|e| failed(e.to_string()))?;
            }
            legend_area
                .draw(&Text::new(s.name.clone(), (46, y - 8), ("sans-serif", 15)))
                .map_err(|e| failed(e.to_string()))?;
            y += 22;
        }
        root.present().map_err(|e| failed(e.to_string()))?;
    }
    Ok(svg)
}

/// Most points a curve is drawn with: a plot 820 pixels wide shows no more,
/// and a run of 2e6 steps would otherwise write SVGs of 100 MB each.
pub const MAX_POINTS: usize = 2000;

/// The points `point(0..len)` of a curve, thinned to at most [`MAX_POINTS`]:
/// each bucket of consecutive points keeps its lowest and highest value (in
/// time order), so peaks and spikes stay visible.
fn thinned(len: usize, point: impl Fn(usize) -> (f64, f64)) -> Vec<(f64, f64)> {
    if len <= MAX_POINTS {
        return (0..len).map(point).collect();
    }
    let bucket = len.div_ceil(MAX_POINTS / 2);
    let mut out = Vec::with_capacity(MAX_POINTS + 2);
    for start in (0..len).step_by(bucket) {
        let end = (start + bucket).min(len);
        let (mut lo, mut hi) = (start, start);
        for i in start..end {
            let v = point(i).1;
            if v < point(lo).1 {
                lo = i;
            }
            if v > point(hi).1 {
                hi = i;
            }
        }
        let (a, b) = if lo <= hi { (lo, hi) } else { (hi, lo) };
        out.push(point(a));
        if b != a {
            out.push(point(b));
        }
    }
    out
}

/// Numerical curves (solid, one colour per column) and, where there is a
/// reference, the reference curves as thin black dashes on top of them (one
/// legend entry), as in the paper's figures (NUM vs REF).
fn curves<const N: usize, const M: usize, const A: usize>(
    solution: &Solution<N, M, A>,
    references: Option<&[State<N, M, A>]>,
    columns: &[(String, usize)],
    value: impl Fn(&State<N, M, A>, usize) -> f64,
) -> Vec<Series> {
    let mut out: Vec<Series> = columns
        .iter()
        .enumerate()
        .map(|(c, (name, k))| Series {
            name: name.clone(),
            points: thinned(solution.states.len(), |i| {
                let s = &solution.states[i];
                (s.t, value(s, *k))
            }),
            color: PALETTE[c % PALETTE.len()],
            dashed: false,
        })
        .collect();
    if let Some(refs) = references {
        for (c, (_, k)) in columns.iter().enumerate() {
            out.push(Series {
                name: if c == 0 {
                    "analytical reference".into()
                } else {
                    String::new()
                },
                points: thinned(refs.len(), |i| (refs[i].t, value(&refs[i], *k))),
                color: BLACK,
                dashed: true,
            });
        }
    }
    out
}

/// Named curves over time (each thinned to at most [`MAX_POINTS`] points).
pub fn curves_over_time(title: &str, y_label: &str, curves: &[(&str, Vec<(f64, f64)>)]) -> Result<String, CliError> {
    curves_with_levels(title, y_label, curves, &[])
}

/// Named curves over time with horizontal dashed lines at the `levels`
/// (e.g. `+-150` for a torque limit), in the colour of their curve; a level
/// beyond 100 times every curve's largest value is left out.
pub fn curves_with_levels(
    title: &str,
    y_label: &str,
    curves: &[(&str, Vec<(f64, f64)>)],
    levels: &[(usize, f64)],
) -> Result<String, CliError> {
    let mut series: Vec<Series> = curves
        .iter()
        .enumerate()
        .map(|(c, (name, points))| Series {
            name: name.to_string(),
            points: thinned(points.len(), |i| points[i]),
            color: PALETTE[c % PALETTE.len()],
            dashed: false,
        })
        .collect();
    let span = curves
        .iter()
        .flat_map(|(_, p)| p.first().zip(p.last()))
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), (f, l)| {
            (a.min(f.0), b.max(l.0))
        });
    // a level far beyond every curve (a limit of 1e308) would flatten them
    // to a line at zero, and its axis span overflow: it is left out
    let largest = curves
        .iter()
        .flat_map(|(_, p)| p.iter().map(|&(_, y)| y.abs()))
        .fold(0.0, f64::max);
    for &(c, level) in levels
        .iter()
        .filter(|&&(_, level)| level.abs() <= 100.0 * largest.max(1.0))
    {
        series.push(Series {
            name: format!("{} {level}", curves.get(c).map_or("limit", |c| c.0)),
            points: vec![(span.0, level), (span.1, level)],
            color: PALETTE[c % PALETTE.len()],
            dashed: true,
        });
    }
    draw(title, y_label, &series)
}

/// A heat map of `values[iy][ix]` over the grid `xs` x `ys` (cells without a
/// value, failed points, in grey; cells `marked` with a cross: infeasible),
/// with a colour bar.
#[allow(clippy::too_many_arguments)]
pub fn heat_map(
    title: &str,
    x_label: &str,
    y_label: &str,
    xs: &[f64],
    ys: &[f64],
    values: &[Vec<Option<f64>>],
    marked: &[Vec<bool>],
    value_label: &str,
) -> Result<String, CliError> {
    register_font();
    let failed = |e: String| CliError::Output {
        what: format!("plot '{title}'"),
        message: e,
    };
    let finite: Vec<f64> = values
        .iter()
        .flatten()
        .flatten()
        .copied()
        .filter(|v| v.is_finite())
        .collect();
    let (lo, hi) = finite
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &v| (a.min(v), b.max(v)));
    if xs.len() < 2 || ys.len() < 2 || finite.is_empty() {
        return Err(failed("a heat map needs at least 2 x 2 points with values".into()));
    }
    let (lo, hi) = if hi > lo { (lo, hi) } else { (lo - 0.5, hi + 0.5) };
    let half = |v: &[f64], i: usize| {
        if i + 1 < v.len() {
            0.5 * (v[i + 1] - v[i])
        } else {
            0.5 * (v[i] - v[i - 1])
        }
    };
    let colour = |v: f64| {
        // blue (low) .. yellow .. red (high)
        let t = ((v - lo) / (hi - lo)).clamp(0.0, 1.0);
        let (r, g, b) = if t < 0.5 {
            (2.0 * t, 2.0 * t, 1.0 - 2.0 * t)
        } else {
            (1.0, 2.0 - 2.0 * t, 0.0)
        };
        RGBColor((255.0 * r) as u8, (200.0 * g) as u8, (255.0 * b) as u8)
    };
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, (1000, 640)).into_drawing_area();
        root.fill(&WHITE).map_err(|e| failed(e.to_string()))?;
        let (plot_area, bar_area) = root.split_horizontally(860);
        let x_range = (xs[0] - half(xs, 0))..(xs[xs.len() - 1] + half(xs, xs.len() - 1));
        let y_range = (ys[0] - half(ys, 0))..(ys[ys.len() - 1] + half(ys, ys.len() - 1));
        let mut chart = ChartBuilder::on(&plot_area)
            .caption(title, ("sans-serif", 22))
            .margin(12)
            .x_label_area_size(45)
            .y_label_area_size(80)
            .build_cartesian_2d(x_range, y_range)
            .map_err(|e| failed(e.to_string()))?;
        chart
            .configure_mesh()
            .disable_mesh()
            .x_desc(x_label)
            .y_desc(y_label)
            .label_style(("sans-serif", 15))
            .draw()
            .map_err(|e| failed(e.to_string()))?;
        for (iy, row) in values.iter().enumerate() {
            for (ix, value) in row.iter().enumerate() {
                let (x, y) = (xs[ix], ys[iy]);
                let (hx, hy) = (half(xs, ix), half(ys, iy));
                let fill = value.filter(|v| v.is_finite()).map_or(RGBColor(190, 190, 190), colour);
                chart
                    .draw_series(std::iter::once(Rectangle::new(
                        [(x - hx, y - hy), (x + hx, y + hy)],
                        fill.filled(),
                    )))
                    .map_err(|e| failed(e.to_string()))?;
                if marked.get(iy).and_then(|row| row.get(ix)).copied().unwrap_or(false) {
                    let cross = ShapeStyle::from(&BLACK).stroke_width(1);
                    let (dx, dy) = (0.35 * hx, 0.35 * hy);
                    for (a, b) in [
                        ((x - dx, y - dy), (x + dx, y + dy)),
                        ((x - dx, y + dy), (x + dx, y - dy)),
                    ] {
                        chart
                            .draw_series(std::iter::once(PathElement::new(vec![a, b], cross)))
                            .map_err(|e| failed(e.to_string()))?;
                    }
                }
            }
        }
        let steps = 50;
        for k in 0..steps {
            let v = lo + (hi - lo) * k as f64 / (steps - 1) as f64;
            let y0 = 560 - (k * 480 / steps);
            bar_area
                .draw(&Rectangle::new(
                    [(20, y0 - 480 / steps - 1), (50, y0)],
                    colour(v).filled(),
                ))
                .map_err(|e| failed(e.to_string()))?;
        }
        for (text, y) in [
            (format!("{hi:.4}"), 70),
            (format!("{lo:.4}"), 572),
            (value_label.to_string(), 30),
        ] {
            bar_area
                .draw(&Text::new(text, (8, y), ("sans-serif", 14)))
                .map_err(|e| failed(e.to_string()))?;
        }
        bar_area
            .draw(&Text::new("grey: failed".to_string(), (8, 596), ("sans-serif", 14)))
            .map_err(|e| failed(e.to_string()))?;
        bar_area
            .draw(&Text::new("x: infeasible".to_string(), (8, 614), ("sans-serif", 14)))
            .map_err(|e| failed(e.to_string()))?;
        root.present().map_err(|e| failed(e.to_string()))?;
    }
    Ok(svg)
}

/// Grey dashed vertical lines at the start and end of the load's move
/// (`moving`), across the range of `series`, one legend entry: where a run
/// by stable inversion acts before the move (pre-actuation) and after it
/// (post-actuation).
fn mark_move(mut series: Vec<Series>, moving: Option<(f64, f64)>) -> Vec<Series> {
    let Some((start, end)) = moving else {
        return series;
    };
    let (low, high) = series
        .iter()
        .flat_map(|s| s.points.iter().map(|&(_, y)| y))
        .filter(|y| y.is_finite())
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), y| (a.min(y), b.max(y)));
    if !(low <= high) {
        return series;
    }
    for (k, t) in [start, end].into_iter().enumerate() {
        series.push(Series {
            name: if k == 0 {
                "the load moves (before: pre-, after: post-actuation)".into()
            } else {
                String::new()
            },
            points: vec![(t, low), (t, high)],
            color: RGBColor(128, 128, 128),
            dashed: true,
        });
    }
    series
}

/// All plots of a run as `(file name, SVG text)`; `method` (the
/// formulation and scheme) goes into the titles; `moving`, the times the
/// load starts and stops moving where the run extends beyond them (stable
/// inversion), is marked on each.
pub fn all<const N: usize, const M: usize, const A: usize>(
    solution: &Solution<N, M, A>,
    references: Option<&[State<N, M, A>]>,
    method: &str,
    moving: Option<(f64, f64)>,
) -> Result<Vec<(String, String)>, CliError> {
    let info = solution.info;
    let title = |what: &str| format!("{} - {what} ({method}, dt = {} s)", info.name, solution.dt);
    let inputs: Vec<(String, usize)> = info
        .inputs
        .iter()
        .enumerate()
        .map(|(k, n)| (n.to_string(), k))
        .collect();
    let coords: Vec<(String, usize)> = info
        .coordinates
        .iter()
        .enumerate()
        .map(|(k, n)| (n.to_string(), k))
        .collect();
    let lambdas: Vec<(String, usize)> = (0..M).map(|i| (format!("lambda{}", i + 1), i)).collect();
    let mut plots = vec![
        (
            "inputs.svg".to_string(),
            draw(
                &title("inputs u"),
                "u [N m]",
                &mark_move(curves(solution, references, &inputs, |s, k| s.u[k]), moving),
            )?,
        ),
        (
            "coordinates.svg".to_string(),
            draw(
                &title("coordinates q"),
                "q [m]",
                &mark_move(curves(solution, references, &coords, |s, k| s.q[k]), moving),
            )?,
        ),
        (
            "multipliers.svg".to_string(),
            draw(
                &title("multipliers lambda"),
                "lambda [N/m]",
                &mark_move(curves(solution, references, &lambdas, |s, k| s.lambda[k]), moving),
            )?,
        ),
    ];
    if !info.ropes.is_empty() {
        let series: Vec<Series> = info
            .ropes
            .iter()
            .enumerate()
            .map(|(r, rope)| Series {
                name: rope.tension.to_string(),
                points: thinned(solution.states.len(), |i| {
                    (solution.states[i].t, solution.tensions_at(i)[r])
                }),
                color: PALETTE[r % PALETTE.len()],
                dashed: false,
            })
            .collect();
        plots.push((
            "tensions.svg".to_string(),
            draw(&title("rope tensions"), "N [N]", &mark_move(series, moving))?,
        ));
    }
    Ok(plots)
}

/// Log-log plot of a convergence study: the relative error `e_u` over `dt`
/// (points joined by a line) with a dashed guide of slope `order`, like the
/// paper's Figs. 7 and 16. The guide goes through the finest step whose
/// error is at least 1e-7, 100 times the round-off floor of the index-3
/// schemes (about 1e-9 at the smallest steps), so that it shows the
/// scheme's slope rather than the floor; without such a step, through the
/// coarsest. No guide for `order = None` (a formulation that discretises
/// nothing). An error of exactly 0 is drawn at 1e-17, below round-off.
pub fn convergence(title: &str, rows: &[(f64, f64)], order: Option<usize>) -> Result<String, CliError> {
    register_font();
    let failed = |e: String| CliError::Output {
        what: format!("plot '{title}'"),
        message: e,
    };
    let finite: Vec<(f64, f64)> = rows
        .iter()
        .copied()
        .filter(|&(d, e)| d > 0.0 && e >= 0.0 && e.is_finite())
        .map(|(d, e)| (d, e.max(1e-17)))
        .collect();
    let Some(&coarsest) = finite.first() else {
        return Err(failed("no positive finite errors to plot".into()));
    };
    let (dt_anchor, e_anchor) = finite
        .iter()
        .rev()
        .find(|&&(_, e)| e >= 1e-7)
        .copied()
        .unwrap_or(coarsest);
    let guide: Vec<(f64, f64)> = match order {
        Some(order) => finite
            .iter()
            .map(|&(d, _)| (d, e_anchor * (d / dt_anchor).powi(order as i32)))
            .collect(),
        None => Vec::new(),
    };
    let (x_min, x_max) = finite
        .iter()
        .fold((f64::INFINITY, 0.0f64), |(lo, hi), &(d, _)| (lo.min(d), hi.max(d)));
    let (y_min, y_max) = finite
        .iter()
        .chain(&guide)
        .fold((f64::INFINITY, 0.0f64), |(lo, hi), &(_, e)| (lo.min(e), hi.max(e)));
    // half a decade of room on each side of the data
    let (x_min, x_max, y_min, y_max) = (x_min / 1.5, x_max * 1.5, y_min / 2.0, y_max * 2.0);
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, (1000, 560)).into_drawing_area();
        root.fill(&WHITE).map_err(|e| failed(e.to_string()))?;
        let (plot_area, legend_area) = root.split_horizontally(820);
        let mut chart = ChartBuilder::on(&plot_area)
            .caption(title, ("sans-serif", 20))
            .margin(12)
            .x_label_area_size(45)
            .y_label_area_size(90)
            .build_cartesian_2d((x_min..x_max).log_scale(), (y_min..y_max).log_scale())
            .map_err(|e| failed(e.to_string()))?;
        chart
            .configure_mesh()
            .x_desc("time step dt [s]")
            .y_desc("relative error e_u [-]")
            .x_label_formatter(&|v| format!("{v}"))
            .y_label_formatter(&|v| format!("{v:.0e}"))
            .label_style(("sans-serif", 15))
            .draw()
            .map_err(|e| failed(e.to_string()))?;
        let color = PALETTE[0];
        chart
            .draw_series(LineSeries::new(
                finite.iter().copied(),
                ShapeStyle::from(&color).stroke_width(2),
            ))
            .map_err(|e| failed(e.to_string()))?;
        chart
            .draw_series(
                finite
                    .iter()
                    .map(|&p| Circle::new(p, 5, ShapeStyle::from(&color).filled())),
            )
            .map_err(|e| failed(e.to_string()))?;
        chart
            .draw_series(DashedLineSeries::new(
                guide.iter().copied(),
                6,
                4,
                ShapeStyle::from(&BLACK).stroke_width(1),
            ))
            .map_err(|e| failed(e.to_string()))?;
        let guide_name = order.map(|order| format!("order {order} (slope {order})"));
        let mut entries: Vec<(&str, RGBColor, bool)> = vec![("e_u at t = 1.5 s", color, false)];
        if let Some(name) = &guide_name {
            entries.push((name.as_str(), BLACK, true));
        }
        let mut y = 60;
        for (name, c, dashed) in entries {
            let style = ShapeStyle::from(&c).stroke_width(if dashed { 1 } else { 2 });
            let sample = vec![(8, y), (38, y)];
            if dashed {
                legend_area
                    .draw(&DashedPathElement::new(sample, 6, 4, style))
                    .map_err(|e| failed(e.to_string()))?;
            } else {
                legend_area
                    .draw(&PathElement::new(sample, style))
                    .map_err(|e| failed(e.to_string()))?;
                legend_area
                    .draw(&Circle::new((23, y), 5, style.filled()))
                    .map_err(|e| failed(e.to_string()))?;
            }
            legend_area
                .draw(&Text::new(name, (46, y - 8), ("sans-serif", 15)))
                .map_err(|e| failed(e.to_string()))?;
            y += 22;
        }
        root.present().map_err(|e| failed(e.to_string()))?;
    }
    Ok(svg)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A spike of one sample in 2e5 survives the thinning, and the points
    /// stay in time order.
    #[test]
    fn thinning_keeps_peaks_in_order() {
        let len = 200_000;
        let value = |i: usize| {
            if i == 123_457 {
                50.0
            } else if i == 7 {
                -3.0
            } else {
                (i as f64 * 1e-4).sin()
            }
        };
        let points = thinned(len, |i| (i as f64, value(i)));
        assert!(points.len() <= MAX_POINTS + 2, "{}", points.len());
        assert!(points.windows(2).all(|w| w[0].0 < w[1].0));
        assert!(points.contains(&(123_457.0, 50.0)));
        assert!(points.contains(&(7.0, -3.0)));
        let short = thinned(10, |i| (i as f64, value(i)));
        assert_eq!(short.len(), 10);
    }
}
