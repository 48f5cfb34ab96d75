//! Load paths as clamped B-splines ([`BSpline`]): any shape through control
//! points, with exact time derivatives of every order (the derivative of a
//! B-spline of degree `p` is a B-spline of degree `p - 1` whose control
//! points are the differences of the original's), evaluated by de Boor's
//! recursion.
//!
//! ```
//! use crane_runtime::bspline::BSpline;
//! use crane_runtime::{Trajectory, nalgebra::vector};
//! // a cubic Bezier arc from (0, -5) over (1, -3), (3, -3) to (4, -5) in 2 s
//! let path = BSpline::new(
//!     3,
//!     vec![0.0, 0.0, 0.0, 0.0, 2.0, 2.0, 2.0, 2.0],
//!     vec![vector![0.0, -5.0], vector![1.0, -3.0], vector![3.0, -3.0], vector![4.0, -5.0]],
//! )?;
//! assert_eq!(path.derivative(1.0, 0), vector![2.0, -3.5]);
//! // the velocity at the start: 3 (P1 - P0) / 2 s
//! assert_eq!(path.derivative(0.0, 1), vector![1.5, 3.0]);
//! # Ok::<(), crane_runtime::trajectory::TrajectoryError>(())
//! ```

use std::ops::{Add, Div, Mul, Sub};

use nalgebra::SVector;

use crate::double_double::DoubleDouble;
use crate::trajectory::{Trajectory, TrajectoryError};

/// A clamped B-spline `gamma(t) = sum_i N_(i,p)(t) P_i` of degree `p` on the
/// knots `t_0 <= ... <= t_(n+p)` (the first and the last `p + 1` equal:
/// the curve starts at `P_0` and ends at `P_(n-1)`), held at its end points
/// outside `[t_p, t_n]` (where its derivatives are 0).
#[derive(Debug, Clone, PartialEq)]
pub struct BSpline<const A: usize> {
    degree: usize,
    knots: Vec<f64>,
    /// The control points of the curve and of each derivative, `k = 0 ..=
    /// p`: those of derivative `k` (degree `p - k`, knots `knots[k ..
    /// len - k]`) are `(p - k + 1) (Q_(i+1) - Q_i) / (t_(i+p+1) - t_(i+k))`
    /// of derivative `k - 1`'s.
    control: Vec<Vec<SVector<f64, A>>>,
}

impl<const A: usize> BSpline<A> {
    /// The B-spline of `degree` (at least 1) on `knots` through the
    /// `control` points (`knots.len() == control.len() + degree + 1`): the
    /// knots finite and non-decreasing, the first and the last `degree + 1`
    /// equal, the span they clamp not empty, no interior knot repeated more
    /// than `degree` times, the points finite.
    pub fn new(degree: usize, knots: Vec<f64>, control: Vec<SVector<f64, A>>) -> Result<Self, TrajectoryError> {
        let invalid = |reason: String| Err(TrajectoryError::Spline { reason });
        if degree == 0 || degree > MAX_DEGREE {
            return invalid(format!(
                "the degree must be at least 1 and at most {MAX_DEGREE}, got {degree}"
            ));
        }
        if control.len() < degree + 1 {
            return invalid(format!(
                "a spline of degree {degree} needs at least {} control points, got {}",
                degree + 1,
                control.len()
            ));
        }
        if knots.len() != control.len() + degree + 1 {
            return invalid(format!(
                "{} control points of degree {degree} need {} knots, got {}",
                control.len(),
                control.len() + degree + 1,
                knots.len()
            ));
        }
        if let Some(k) = knots.iter().position(|t| !t.is_finite()) {
            return invalid(format!("knot {k} is not finite"));
        }
        if let Some(k) = knots.windows(2).position(|w| w[1] < w[0]) {
            return invalid(format!(
                "the knots decrease at knot {}: {} after {}",
                k + 1,
                knots[k + 1],
                knots[k]
            ));
        }
        let (first, last) = (knots[0], knots[knots.len() - 1]);
        let clamped = |ends: &[f64], at: f64| ends.iter().all(|&t| t == at);
        if !clamped(&knots[..=degree], first) || !clamped(&knots[knots.len() - degree - 1..], last) {
            return invalid(format!(
                "the first and the last {} knots must be equal (clamped)",
                degree + 1
            ));
        }
        if last <= first {
            return invalid(format!("the knots span no time: {first} to {last}"));
        }
        let interior = &knots[degree + 1..knots.len() - degree - 1];
        if let Some(w) = interior.windows(degree + 1).find(|w| w[0] == w[degree]) {
            return invalid(format!(
                "the interior knot {} is repeated more than the degree, {degree}, times (the curve would break \
                 there)",
                w[0]
            ));
        }
        if control.iter().any(|p| !p.iter().all(|v| v.is_finite())) {
            return invalid("a control point has a non-finite entry".into());
        }
        let mut all = vec![control];
        for k in 1..=degree {
            let before = &all[k - 1];
            let scale = (degree - k + 1) as f64;
            // (a basis function of zero width, at a repeated knot, adds nothing)
            let next = (0..before.len() - 1)
                .map(|i| match knots[i + degree + 1] - knots[i + k] {
                    width if width > 0.0 => (before[i + 1] - before[i]) * (scale / width),
                    _ => SVector::zeros(),
                })
                .collect();
            all.push(next);
        }
        Ok(Self {
            degree,
            knots,
            control: all,
        })
    }

    /// The spline through `waypoints` at `times` (increasing, at least two),
    /// at rest at both ends to order `rest` (its derivatives `1 ..= rest`
    /// vanish there, so the held ends join it with `rest` continuous
    /// derivatives), continuous to order `rest` everywhere: between two
    /// waypoints a polynomial of degree `2 rest + 1` (a Hermite segment),
    /// each interior waypoint a knot of multiplicity `rest + 1`.
    ///
    /// At an interior waypoint each coordinate's velocity is the slope of
    /// the chord through its neighbours (Catmull-Rom), or zero where the
    /// coordinate turns there or holds still on one side (so a lift, a
    /// traverse and a lowering do not overshoot their corners), and its
    /// derivatives `2 ..= rest` are zero. A spline continuous to order `2
    /// rest` at the waypoints (the one of least `int |gamma^(rest+1)|^2`)
    /// would swing far past them on such a path. Through two waypoints it
    /// is the polynomial of degree `2 rest + 1` from rest to rest (with
    /// `rest = 4` the built-in poly9 move).
    pub fn through(times: &[f64], waypoints: &[SVector<f64, A>], rest: usize) -> Result<Self, TrajectoryError> {
        let invalid = |reason: String| Err(TrajectoryError::Spline { reason });
        let degree = 2 * rest + 1;
        if times.len() != waypoints.len() || times.len() < 2 {
            return invalid(format!(
                "a path through waypoints needs at least two, each with its time; got {} waypoints and {} times",
                waypoints.len(),
                times.len()
            ));
        }
        if let Some(k) = times
            .windows(2)
            .position(|w| !(w[1] > w[0]) || !w[0].is_finite() || !w[1].is_finite())
        {
            return invalid(format!(
                "the waypoints' times must be finite and increasing: {} then {}",
                times[k],
                times[k + 1]
            ));
        }
        if let Some(k) = waypoints.iter().position(|p| !p.iter().all(|v| v.is_finite())) {
            return invalid(format!("waypoint {k} has a non-finite entry"));
        }
        if degree > MAX_DEGREE {
            return invalid(format!(
                "at rest to order {rest} the spline has degree {degree}, above the highest, {MAX_DEGREE}"
            ));
        }
        let m = times.len();
        let (t0, t1) = (times[0], times[m - 1]);
        let mut knots = vec![t0; degree + 1];
        for &t in &times[1..m - 1] {
            knots.extend(std::iter::repeat_n(t, rest + 1));
        }
        knots.extend(std::iter::repeat_n(t1, degree + 1));
        let n = m * (rest + 1);
        // the value of each basis function's derivative `k` at `t`: the
        // spline of the unit control vector
        let basis = |t: f64, k: usize| -> Result<Vec<f64>, TrajectoryError> {
            (0..n)
                .map(|j| {
                    let unit = (0..n)
                        .map(|i| SVector::<f64, 1>::from([f64::from(u8::from(i == j))]))
                        .collect();
                    Ok(BSpline::new(degree, knots.clone(), unit)?.evaluate(t, k)[0])
                })
                .collect()
        };
        let velocity = |i: usize| -> SVector<f64, A> {
            if i == 0 || i == m - 1 {
                return SVector::zeros();
            }
            let before = (waypoints[i] - waypoints[i - 1]) / (times[i] - times[i - 1]);
            let after = (waypoints[i + 1] - waypoints[i]) / (times[i + 1] - times[i]);
            let chord = (waypoints[i + 1] - waypoints[i - 1]) / (times[i + 1] - times[i - 1]);
            SVector::from_fn(|c, _| if before[c] * after[c] > 0.0 { chord[c] } else { 0.0 })
        };
        let mut rows = Vec::with_capacity(n);
        let mut rhs = Vec::with_capacity(n);
        for (i, (&t, point)) in times.iter().zip(waypoints).enumerate() {
            rows.push(basis(t, 0)?);
            rhs.push(*point);
            for k in 1..=rest {
                rows.push(basis(t, k)?);
                rhs.push(if k == 1 { velocity(i) } else { SVector::zeros() });
            }
        }
        let matrix = nalgebra::DMatrix::from_fn(n, n, |i, j| rows[i][j]);
        let lu = matrix.lu();
        let mut control = vec![SVector::zeros(); n];
        for c in 0..A {
            let column = nalgebra::DVector::from_fn(n, |i, _| rhs[i][c]);
            let Some(solved) = lu.solve(&column) else {
                return invalid("the interpolation conditions are singular (waypoints too close in time)".into());
            };
            for (point, value) in control.iter_mut().zip(solved.iter()) {
                point[c] = *value;
            }
        }
        // a clamped spline starts at its first control point and ends at
        // its last: the first and the last waypoint, exactly
        (control[0], control[n - 1]) = (waypoints[0], waypoints[m - 1]);
        BSpline::new(degree, knots, control)
    }

    /// The degree `p`.
    pub fn degree(&self) -> usize {
        self.degree
    }

    /// The knots `t_0 ..= t_(n+p)`.
    pub fn knots(&self) -> &[f64] {
        &self.knots
    }

    /// The control points `P_0 ..= P_(n-1)`.
    pub fn control_points(&self) -> &[SVector<f64, A>] {
        &self.control[0]
    }

    /// The span of the motion, `[t_p, t_n]`.
    pub fn span(&self) -> (f64, f64) {
        (self.knots[0], self.knots[self.knots.len() - 1])
    }

    /// Derivative `k` at `t` inside the span: de Boor's recursion on that
    /// derivative's control points.
    fn evaluate(&self, t: f64, k: usize) -> SVector<f64, A> {
        let p = self.degree - k;
        let knots = &self.knots[k..self.knots.len() - k];
        let control = &self.control[k];
        // the span [knots[s], knots[s + 1]) holding t (the last one closed)
        let n = control.len();
        let s = if t >= knots[n] {
            n - 1
        } else {
            (p..n).rev().find(|&s| knots[s] <= t).unwrap_or(p)
        };
        let mut d: [SVector<f64, A>; MAX_DEGREE + 1] = [SVector::zeros(); MAX_DEGREE + 1];
        for (j, point) in d.iter_mut().enumerate().take(p + 1) {
            *point = control[s + j - p];
        }
        de_boor(knots, p, s, &mut d, t)
    }
}

/// A number de Boor's recursion runs in: `f64`, or [`DoubleDouble`] for
/// the load target of eqs. (22).
trait Scalar:
    nalgebra::Scalar
    + Copy
    + Add<Output = Self>
    + Sub<Output = Self>
    + Sub<f64, Output = Self>
    + Mul<Output = Self>
    + Div<Output = Self>
{
    /// `x` in this type.
    fn of(x: f64) -> Self;
    /// `a - b` as this type holds it (rounded in `f64`, exact in
    /// double-double).
    fn difference(a: f64, b: f64) -> Self;
    /// Whether it is above zero.
    fn positive(self) -> bool;
}

impl Scalar for f64 {
    fn of(x: f64) -> Self {
        x
    }
    fn difference(a: f64, b: f64) -> Self {
        a - b
    }
    fn positive(self) -> bool {
        self > 0.0
    }
}

impl Scalar for DoubleDouble {
    fn of(x: f64) -> Self {
        DoubleDouble::from(x)
    }
    fn difference(a: f64, b: f64) -> Self {
        DoubleDouble::sum(a, -b)
    }
    fn positive(self) -> bool {
        self.hi > 0.0
    }
}

/// De Boor's recursion of degree `p` on `knots` at `t` in the span
/// `[knots[s], knots[s + 1])`, whose `p + 1` control points `d` holds on
/// entry: the curve's point (`d` is overwritten).
fn de_boor<S: Scalar, const A: usize>(
    knots: &[f64],
    p: usize,
    s: usize,
    d: &mut [SVector<S, A>; MAX_DEGREE + 1],
    t: S,
) -> SVector<S, A> {
    for r in 1..=p {
        for j in (r..=p).rev() {
            let i = s + j - p;
            let denominator = S::difference(knots[i + p + 1 - r], knots[i]);
            let alpha = if denominator.positive() {
                (t - knots[i]) / denominator
            } else {
                S::of(0.0)
            };
            let one_minus = S::of(1.0) - alpha;
            let (lower, upper) = (d[j - 1], d[j]);
            d[j] = SVector::from_fn(|c, _| lower[c] * one_minus + upper[c] * alpha);
        }
    }
    d[p]
}

/// The highest degree a [`BSpline`] evaluates with its fixed workspace:
/// `2 p + 1` for the highest path order `p`
/// ([`MAX_PATH_ORDER`](crate::dummy_derivative::MAX_PATH_ORDER)), the
/// degree of a path through waypoints at rest to that order at both ends
/// ([`BSpline::through`]), whose inputs are then continuous.
pub const MAX_DEGREE: usize = 2 * crate::dummy_derivative::MAX_PATH_ORDER + 1;

impl<const A: usize> Trajectory<A> for BSpline<A> {
    /// The derivative of the spline inside its span, its ends included (the
    /// spline's own one-sided value where a derivative jumps there); outside
    /// it the end point held (derivatives 0); 0 above the degree.
    fn derivative(&self, t: f64, k: usize) -> SVector<f64, A> {
        let (t0, t1) = self.span();
        match k {
            _ if k > self.degree => SVector::zeros(),
            0 if t <= t0 => self.control[0][0],
            0 if t >= t1 => self.control[0][self.control[0].len() - 1],
            _ if t < t0 || t > t1 => SVector::zeros(),
            _ => self.evaluate(t, k),
        }
    }

    /// De Boor's recursion in double-double on the control points of the
    /// span holding `t` and their differences (those of derivatives 1
    /// and 2, formed in double-double too): the spline these `f64` knots
    /// and points define, to double-double precision, so that eqs. (22)
    /// do not differentiate its rounding to `f64`.
    fn target_extended(&self, t: DoubleDouble) -> Option<[SVector<DoubleDouble, A>; 3]> {
        let zero = SVector::from_element(DoubleDouble::from(0.0));
        let (t0, t1) = self.span();
        let points = &self.control[0];
        let held = |point: &SVector<f64, A>| Some([point.map(DoubleDouble::from), zero, zero]);
        if t.hi <= t0 {
            return held(&points[0]);
        }
        if t.hi >= t1 {
            return held(&points[points.len() - 1]);
        }
        let degree = self.degree;
        let n = points.len();
        // the span [knots[s], knots[s + 1]) holding t
        let s = (degree..n).rev().find(|&s| self.knots[s] <= t.hi).unwrap_or(degree);
        // the window of control points of derivatives 0, 1, 2 there:
        // level k holds points s - p .. s - k of derivative k
        let mut window = [[zero; MAX_DEGREE + 1]; 3];
        for (j, point) in window[0].iter_mut().enumerate().take(degree + 1) {
            *point = points[s - degree + j].map(DoubleDouble::from);
        }
        let levels = degree.min(2);
        for k in 1..=levels {
            let scale = DoubleDouble::from((degree - k + 1) as f64);
            for j in 0..=degree - k {
                let i = s - degree + j;
                let width = DoubleDouble::sum(self.knots[i + degree + 1], -self.knots[i + k]);
                let (before, after) = (window[k - 1][j], window[k - 1][j + 1]);
                window[k][j] = if width.hi > 0.0 {
                    SVector::from_fn(|c, _| (after[c] - before[c]) * scale / width)
                } else {
                    zero
                };
            }
        }
        let mut out = [zero; 3];
        for (k, value) in out.iter_mut().enumerate().take(levels + 1) {
            // de Boor on derivative k: degree p - k on the knots without
            // the first and the last k
            let p = degree - k;
            let mut d = window[k];
            *value = de_boor(&self.knots[k..self.knots.len() - k], p, s - k, &mut d, t);
        }
        Some(out)
    }

    /// Where the curve starts and ends at rest to order `r` (its
    /// derivatives 1 ..= r vanish at both ends, as where the first and the
    /// last `r + 1` control points are equal), the held ends join it with
    /// `r` continuous derivatives; inside, a knot of multiplicity `m` leaves
    /// `p - m`. The smaller of the two.
    fn continuity(&self) -> Option<usize> {
        let (t0, t1) = self.span();
        let at_rest = (1..=self.degree)
            .take_while(|&k| {
                let scale = self.control[k]
                    .iter()
                    .map(|p| p.amax())
                    .fold(0.0, f64::max)
                    .max(f64::MIN_POSITIVE);
                [t0, t1].iter().all(|&t| self.evaluate(t, k).amax() <= 1e-12 * scale)
            })
            .count();
        let interior = &self.knots[self.degree + 1..self.knots.len() - self.degree - 1];
        let multiplicity = interior.chunk_by(|a, b| a == b).map(<[f64]>::len).max().unwrap_or(0);
        Some(at_rest.min(self.degree - multiplicity.max(1)))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::vector;

    /// A cubic Bezier segment (no interior knots) is the Bernstein
    /// polynomial of its control points: in monomial form `a0 + a1 s + a2
    /// s^2 + a3 s^3` of `s = (t - t0) / T` with `a1 = 3 (P1 - P0)`, `a2 =
    /// 3 (P0 - 2 P1 + P2)`, `a3 = 3 (P1 - P2) + P3 - P0`; the spline's
    /// derivatives of every order equal the polynomial's to round-off.
    #[test]
    fn a_bezier_segment_is_its_bernstein_polynomial() {
        let (t0, period) = (1.0, 2.5);
        let p = [
            vector![0.3, -5.0],
            vector![1.1, -2.0],
            vector![2.9, -3.5],
            vector![4.0, -1.0],
        ];
        let spline = BSpline::new(
            3,
            vec![t0, t0, t0, t0, t0 + period, t0 + period, t0 + period, t0 + period],
            p.to_vec(),
        )
        .unwrap();
        let a = [
            p[0],
            (p[1] - p[0]) * 3.0,
            (p[0] - p[1] * 2.0 + p[2]) * 3.0,
            (p[1] - p[2]) * 3.0 + p[3] - p[0],
        ];
        for step in 0..=20 {
            let t = t0 + period * step as f64 / 20.0;
            let s = (t - t0) / period;
            for k in 0..=4 {
                // d^k/dt^k of sum a_j s^j = sum j!/(j-k)! a_j s^(j-k) / T^k
                let mut expected = SVector::<f64, 2>::zeros();
                for (j, aj) in a.iter().enumerate().skip(k) {
                    let falling: f64 = ((j - k + 1)..=j).map(|x| x as f64).product();
                    expected += aj * (falling * s.powi((j - k) as i32) / period.powi(k as i32));
                }
                let got = spline.derivative(t, k);
                assert!(
                    (got - expected).amax() <= 1e-12 * (1.0 + expected.amax()),
                    "t = {t}, k = {k}: {got} {expected}"
                );
            }
        }
    }

    /// On a spline of degree 5 with interior knots, each derivative is the
    /// central difference of the one below to its truncation error (`h^2 /
    /// 6` times the third derivative of that one: below 1e-6 here at h =
    /// 1e-4), inside the knot spans.
    #[test]
    fn each_derivative_is_the_rate_of_the_one_below() {
        let knots = vec![
            0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.7, 1.3, 1.9, 3.0, 3.0, 3.0, 3.0, 3.0, 3.0,
        ];
        let control: Vec<SVector<f64, 1>> = (0..9).map(|i| vector![((i * 7) % 5) as f64 - 2.0]).collect();
        let spline = BSpline::new(5, knots, control).unwrap();
        let h = 1e-4;
        for t in [0.3, 0.95, 1.5, 2.4, 2.9] {
            for k in 0..5 {
                let difference = (spline.derivative(t + h, k) - spline.derivative(t - h, k)) / (2.0 * h);
                let exact = spline.derivative(t, k + 1);
                assert!(
                    (difference - exact).amax() <= 1e-6 * (1.0 + exact.amax()),
                    "t = {t}, k = {k}"
                );
            }
        }
    }

    /// At a simple interior knot a spline of degree `p` keeps `p - 1`
    /// continuous derivatives (left and right limits agree to round-off)
    /// and its derivative `p` jumps; a doubled knot leaves `p - 2`. The
    /// continuity reported is that, where the ends are at rest.
    #[test]
    fn interior_knots_leave_the_degree_less_their_multiplicity_continuous() {
        let rest = |n: usize| -> Vec<SVector<f64, 1>> {
            let mut points = vec![vector![0.0]; 4];
            points.extend((0..n).map(|i| vector![1.0 + i as f64 * 0.5]));
            points.extend(vec![vector![5.0]; 4]);
            points
        };
        // degree 3, the ends at rest to order 3 (four equal points), one
        // simple knot at 1.0 among the interior ones
        let knots = vec![0.0, 0.0, 0.0, 0.0, 0.4, 0.7, 1.0, 1.3, 1.6, 2.0, 2.0, 2.0, 2.0];
        let spline = BSpline::new(3, knots, rest(1)).unwrap();
        let jump = |k: usize| (spline.derivative(1.0 + 1e-9, k) - spline.derivative(1.0 - 1e-9, k)).amax();
        assert!(jump(2) < 1e-6, "{}", jump(2));
        assert!(jump(3) > 1e-3, "{}", jump(3));
        assert_eq!(spline.continuity(), Some(2));
        let doubled = vec![0.0, 0.0, 0.0, 0.0, 0.4, 1.0, 1.0, 1.3, 1.6, 2.0, 2.0, 2.0, 2.0];
        let spline = BSpline::new(3, doubled, rest(1)).unwrap();
        assert_eq!(spline.continuity(), Some(1));
    }

    /// Through two waypoints at rest to order 4 the spline is poly9, the
    /// built-in move (the unique polynomial of degree 9 from rest to rest):
    /// every derivative equal to round-off.
    #[test]
    fn through_two_waypoints_at_rest_to_order_four_is_poly9() {
        use crate::trajectory::Poly9;
        let (start, end) = (vector![0.0, -5.0], vector![4.0, -3.0]);
        let spline = BSpline::through(&[0.5, 5.5], &[start, end], 4).unwrap();
        let poly9 = Poly9::new(0.5, 5.5, start, end).unwrap();
        assert_eq!(spline.degree(), 9);
        for step in 0..=50 {
            let t = 0.5 + 5.0 * step as f64 / 50.0;
            // (at the ends poly9 gives the rest's derivatives, the spline
            // its own: they differ from the 5th on, which jumps there)
            let top = if step == 0 || step == 50 { 4 } else { 9 };
            for k in 0..=top {
                let (got, expected) = (spline.derivative(t, k), poly9.derivative(t, k));
                assert!(
                    (got - expected).amax() <= 1e-10 * (1.0 + expected.amax()),
                    "t = {t}, k = {k}"
                );
            }
        }
        assert_eq!(spline.continuity(), Some(4));
    }

    /// Through waypoints: at each time its waypoint, at both ends at rest
    /// to the order asked, continuous to order `rest` at the interior
    /// waypoints and no further (the derivative `rest + 1` jumps there),
    /// where a coordinate that turns is at rest and one that goes on has
    /// the velocity of the chord through the neighbours.
    #[test]
    fn through_waypoints_meets_them_at_rest_at_both_ends() {
        let times = [0.0, 1.5, 2.0, 4.0];
        let points = [
            vector![0.0, -5.0],
            vector![1.0, -2.0],
            vector![2.5, -2.0],
            vector![4.0, -5.0],
        ];
        let spline = BSpline::through(&times, &points, 3).unwrap();
        for (&t, point) in times.iter().zip(&points) {
            assert!((spline.derivative(t, 0) - point).amax() < 1e-12, "t = {t}");
        }
        for k in 1..=3 {
            for t in [0.0, 4.0] {
                assert!(spline.derivative(t, k).amax() < 1e-9, "t = {t}, k = {k}");
            }
        }
        assert_eq!(spline.continuity(), Some(3));
        let jump = |k: usize| (spline.derivative(1.5 + 1e-9, k) - spline.derivative(1.5 - 1e-9, k)).amax();
        // (derivative k changes by about 1e-9 times derivative k + 1 across
        // the 2e-9 s; the 4th is of order 1e3 here)
        assert!(jump(3) < 1e-4 && jump(4) > 1.0, "{} {}", jump(3), jump(4));
        // x goes on at 1.5 s at the chord's slope (2.5 - 0) / (2 - 0), and at
        // 2 s at (4 - 1) / (4 - 1.5); z turns at both (rises, holds, drops):
        // at rest
        assert!((spline.derivative(1.5, 1) - vector![1.25, 0.0]).amax() < 1e-9);
        assert!((spline.derivative(2.0, 1) - vector![1.2, 0.0]).amax() < 1e-9);
        // z never rises above the traverse's height, nor drops below the ends'
        for step in 0..=400 {
            let z = spline.derivative(4.0 * step as f64 / 400.0, 0)[1];
            assert!((-5.0 - 1e-12..=-2.0 + 1e-12).contains(&z), "z = {z}");
        }
        let refused = |times: &[f64], points: &[SVector<f64, 2>]| BSpline::through(times, points, 2).unwrap_err();
        assert!(refused(&[0.0], &points[..1]).to_string().contains("at least two"));
        assert!(
            refused(&[0.0, 2.0, 1.0], &points[..3])
                .to_string()
                .contains("increasing")
        );
    }

    /// In double-double the spline is the one its `f64` knots and points
    /// define, to about 1e-30 of its size: it agrees with the `f64`
    /// evaluation to the latter's rounding (1e-14 relative) in value and
    /// the first two derivatives, inside, at a knot, and held at the ends.
    #[test]
    fn the_double_double_target_is_the_spline_to_its_precision() {
        let times = [0.0, 1.5, 2.0, 4.0];
        let points = [
            vector![0.0, -5.0],
            vector![1.0, -2.0],
            vector![2.5, -2.0],
            vector![4.0, -5.0],
        ];
        let spline = BSpline::through(&times, &points, 4).unwrap();
        for t in [-1.0, 0.0, 0.3, 1.5, 1.7, 2.0, 3.99, 4.0, 5.0] {
            let extended = spline.target_extended(DoubleDouble::from(t)).unwrap();
            for k in 0..3 {
                let (got, expected) = (extended[k].map(DoubleDouble::to_f64), spline.derivative(t, k));
                let scale = 1.0 + spline.derivative(t, k).amax();
                assert!(
                    (got - expected).amax() <= 1e-13 * scale,
                    "t = {t}, k = {k}: {got} {expected}"
                );
            }
        }
        // between two step times 1e-17 s apart the double-double target
        // moves by the velocity times 1e-17; f64 cannot tell the times apart
        let t = DoubleDouble::new(1.7, 1e-17);
        let moved = spline.target_extended(t).unwrap()[0] - spline.target_extended(DoubleDouble::from(1.7)).unwrap()[0];
        let velocity = spline.derivative(1.7, 1);
        for c in 0..2 {
            let error = (moved[c].to_f64() - velocity[c] * 1e-17).abs();
            assert!(
                error <= 1e-3 * velocity[c].abs() * 1e-17 + 1e-30,
                "{c}: {error:e}, velocity {}",
                velocity[c]
            );
        }
    }

    #[test]
    fn bad_splines_are_refused_with_the_reason() {
        let points = |n: usize| vec![vector![0.0]; n];
        let reason = |degree, knots: Vec<f64>, n| match BSpline::<1>::new(degree, knots, points(n)) {
            Err(TrajectoryError::Spline { reason }) => reason,
            other => panic!("{other:?}"),
        };
        assert!(reason(0, vec![0.0, 1.0], 1).contains("at least 1"));
        assert!(reason(22, vec![0.0; 46], 23).contains("at most 21"));
        assert!(reason(3, vec![0.0; 7], 3).contains("at least 4 control points"));
        assert!(reason(1, vec![0.0, 0.0, 1.0], 2).contains("need 4 knots"));
        assert!(reason(1, vec![0.0, 0.0, 2.0, 1.0, 1.0], 3).contains("decrease"));
        assert!(reason(2, vec![0.0, 1.0, 1.0, 2.0, 2.0, 2.0], 3).contains("clamped"));
        assert!(reason(1, vec![1.0, 1.0, 1.0, 1.0], 2).contains("span no time"));
        assert!(reason(1, vec![0.0, 0.0, 0.5, 0.5, 1.0, 1.0], 4).contains("repeated more than the degree"));
        assert!(reason(1, vec![0.0, 0.0, f64::NAN, 1.0, 1.0], 3).contains("not finite"));
    }
}
