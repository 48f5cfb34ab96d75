//! Prescribed load paths `gamma(t)` for the servo constraints `x = gamma(t)`
//! (paper eq. 1c).
//!
//! Every trajectory gives exact time derivatives of any order: the scheme of
//! eqs. (22a-d) needs `gamma`, `gamma'` and `gamma''`, the analytical references
//! need derivatives up to order 4 (Appendix A), and the 3D crane with pulley
//! mass up to order 6 (docs/errata.md).

use nalgebra::SVector;

use crate::double_double::DoubleDouble;

/// A load path with exact time derivatives.
pub trait Trajectory<const A: usize> {
    /// The `k`-th time derivative of `gamma` at `t` (`k = 0` is the position).
    fn derivative(&self, t: f64, k: usize) -> SVector<f64, A>;

    /// `gamma, gamma', ..., gamma^(K-1)` at `t`.
    fn derivatives<const K: usize>(&self, t: f64) -> [SVector<f64, A>; K]
    where
        Self: Sized,
    {
        let mut out = [SVector::zeros(); K];
        self.derivatives_into(t, &mut out);
        out
    }

    /// `gamma^(k)(t)` for `k = 0 .. out.len()` into `out`: one
    /// [`derivative`](Self::derivative) each, unless the path computes them
    /// in one pass (the built-in paths: their polynomials' derivatives side
    /// by side, the same numbers).
    fn derivatives_into(&self, t: f64, out: &mut [SVector<f64, A>]) {
        for (k, gamma) in out.iter_mut().enumerate() {
            *gamma = self.derivative(t, k);
        }
    }

    /// The highest derivative of `gamma` that is continuous for all `t`
    /// (the rest before and after the motion included), if known. The
    /// inputs of a crane depend on the path's derivatives up to
    /// [`Structure::path_order`](crate::Structure::path_order); a path
    /// continuous only to a lower order gives inputs with jumps or impulses.
    fn continuity(&self) -> Option<usize> {
        None
    }

    /// `gamma, gamma', gamma''` to double-double precision at a time given
    /// to that precision ([`DoubleDouble::step_time`]), where the path can
    /// compute them: the built-in paths can. Eqs. (22) then take the load
    /// target free of its rounding to `f64`, whose noise the scheme's
    /// second differences of the robot's coordinates (which the target
    /// fixes) would amplify like `1/dt^2` ([`crate::double_double`]).
    /// `None` (the default): the target in `f64` serves.
    fn target_extended(&self, t: DoubleDouble) -> Option<[SVector<DoubleDouble, A>; 3]> {
        let _ = t;
        None
    }
}

impl<const A: usize, T: Trajectory<A> + ?Sized> Trajectory<A> for &T {
    fn derivative(&self, t: f64, k: usize) -> SVector<f64, A> {
        (**self).derivative(t, k)
    }

    fn derivatives_into(&self, t: f64, out: &mut [SVector<f64, A>]) {
        (**self).derivatives_into(t, out)
    }

    fn target_extended(&self, t: DoubleDouble) -> Option<[SVector<DoubleDouble, A>; 3]> {
        (**self).target_extended(t)
    }

    fn continuity(&self) -> Option<usize> {
        (**self).continuity()
    }
}

/// `k`-th derivative of the polynomial `sum_i c[i] s^i` at `s`.
fn poly_derivative(coefficients: &[f64], s: f64, k: usize) -> f64 {
    let mut value = 0.0;
    for i in (k..coefficients.len()).rev() {
        // d^k/ds^k s^i = i!/(i-k)! s^(i-k)
        value = value * s + coefficients[i] * falling(i, k);
    }
    value
}

/// The polynomial `sum_i c[i] s^i` and its first two derivatives at `s`
/// in double-double, side by side (the falling factorials are exact
/// integers).
fn poly_derivatives_extended(coefficients: &[f64], s: DoubleDouble) -> [DoubleDouble; 3] {
    let mut out = [DoubleDouble::from(0.0); 3];
    for (i, &coefficient) in coefficients.iter().enumerate().rev() {
        for (k, value) in out.iter_mut().enumerate().take(i + 1) {
            *value = *value * s + coefficient * falling(i, k);
        }
    }
    out
}

/// `[gamma0 + (gammaf - gamma0) c, (gammaf - gamma0) c', (gammaf - gamma0)
/// c'']` in double-double, the difference of the points taken exactly.
fn scaled_extended<const A: usize>(
    start: &SVector<f64, A>,
    end: &SVector<f64, A>,
    c: [DoubleDouble; 3],
) -> [SVector<DoubleDouble, A>; 3] {
    let span = |k: usize| DoubleDouble::sum(end[k], -start[k]);
    [
        SVector::from_fn(|k, _| span(k) * c[0] + start[k]),
        SVector::from_fn(|k, _| span(k) * c[1]),
        SVector::from_fn(|k, _| span(k) * c[2]),
    ]
}

/// [`poly_derivative`] of orders `0 .. out.len()` into `out`, the
/// polynomials of the orders side by side (each added in the same order as
/// alone: the same numbers), for at most [`FALLING_SIZE`] orders (the
/// rest are left as they are).
fn poly_derivatives(coefficients: &[f64], s: f64, out: &mut [f64]) {
    let orders = out.len().min(FALLING_SIZE);
    let out = &mut out[..orders];
    out.fill(0.0);
    for (i, &coefficient) in coefficients.iter().enumerate().rev() {
        let falling = FALLING.get(i);
        for (k, value) in out.iter_mut().enumerate().take(i + 1) {
            let factor = falling.map_or_else(|| self::falling(i, k), |row| row[k]);
            *value = *value * s + coefficient * factor;
        }
    }
}

/// How many `i` [`FALLING`] holds.
const FALLING_SIZE: usize = 16;

/// The falling factorials `i!/(i-k)!` for `k <= i < FALLING_SIZE` (0 above
/// the diagonal): integers below 2^53, exact in f64 whatever the order of
/// their factors.
const FALLING: [[f64; FALLING_SIZE]; FALLING_SIZE] = {
    let mut table = [[0.0; FALLING_SIZE]; FALLING_SIZE];
    let mut i = 0;
    while i < FALLING_SIZE {
        let (mut k, mut value) = (0, 1.0);
        while k <= i {
            table[i][k] = value;
            value *= (i - k) as f64;
            k += 1;
        }
        i += 1;
    }
    table
};

/// `i!/(i-k)!` for `k <= i`, from the table where it holds `i`.
fn falling(i: usize, k: usize) -> f64 {
    match FALLING.get(i) {
        Some(row) => row[k],
        None => ((i - k + 1)..=i).map(|j| j as f64).product(),
    }
}

/// Coefficients of the 5-6-7-8-9 polynomial of eq. (44):
/// `c(tau) = 70 tau^9 - 315 tau^8 + 540 tau^7 - 420 tau^6 + 126 tau^5`.
const POLY9: [f64; 10] = [0.0, 0.0, 0.0, 0.0, 0.0, 126.0, -420.0, 540.0, -315.0, 70.0];

/// The rest-to-rest path of eqs. (41)-(45):
/// `gamma(t) = gamma0 + (gammaf - gamma0) c(tau)`, `tau = (t - t0)/(tf - t0)`.
///
/// Derivatives up to order 4 vanish at both ends; outside `[t0, tf]` the
/// load rests at `gamma0` or `gammaf`.
///
/// ```
/// use crane_runtime::trajectory::{Poly9, Trajectory};
/// use crane_runtime::nalgebra::vector;
/// let path = Poly9::new(0.0, 4.0, vector![0.0, -10.0], vector![-3.0, -14.0]).unwrap();
/// assert_eq!(path.derivative(2.0, 0), vector![-1.5, -12.0]); // c(1/2) = 1/2
/// assert_eq!(path.derivative(0.0, 3), vector![0.0, 0.0]);
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct Poly9<const A: usize> {
    t0: f64,
    tf: f64,
    start: SVector<f64, A>,
    end: SVector<f64, A>,
}

/// A trajectory was given inconsistent times or non-finite points.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum TrajectoryError {
    /// `tf <= t0` or a time is not finite.
    #[error("invalid time span: need finite t0 < tf, got t0 = {t0}, tf = {tf}")]
    TimeSpan {
        /// Start time.
        t0: f64,
        /// End time.
        tf: f64,
    },
    /// A ramp longer than half the motion.
    #[error("invalid ramp: need 0 < tau0 <= tau/2, got tau0 = {tau0}, tau = {tau}")]
    Ramp {
        /// Ramp duration.
        tau0: f64,
        /// Total duration.
        tau: f64,
    },
    /// A B-spline's knots, control points or degree do not make one
    /// ([`crate::bspline::BSpline::new`]).
    #[error("invalid B-spline: {reason}")]
    Spline {
        /// What is wrong.
        reason: String,
    },
    /// A start or end point with a NaN or infinite entry.
    #[error("the {which} point has a non-finite entry")]
    NonFinitePoint {
        /// `"start"` or `"end"`.
        which: &'static str,
    },
}

fn check_points<const A: usize>(start: &SVector<f64, A>, end: &SVector<f64, A>) -> Result<(), TrajectoryError> {
    if !start.iter().all(|v| v.is_finite()) {
        return Err(TrajectoryError::NonFinitePoint { which: "start" });
    }
    if !end.iter().all(|v| v.is_finite()) {
        return Err(TrajectoryError::NonFinitePoint { which: "end" });
    }
    Ok(())
}

impl<const A: usize> Poly9<A> {
    /// Rest-to-rest motion from `start` at `t0` to `end` at `tf`.
    pub fn new(t0: f64, tf: f64, start: SVector<f64, A>, end: SVector<f64, A>) -> Result<Self, TrajectoryError> {
        if !(t0.is_finite() && tf.is_finite() && tf > t0) {
            return Err(TrajectoryError::TimeSpan { t0, tf });
        }
        check_points(&start, &end)?;
        Ok(Self { t0, tf, start, end })
    }

    /// Start time `t0`.
    pub fn t0(&self) -> f64 {
        self.t0
    }

    /// End time `tf`.
    pub fn tf(&self) -> f64 {
        self.tf
    }
}

impl<const A: usize> Trajectory<A> for Poly9<A> {
    /// 4: derivatives 1 to 4 vanish at both ends, the 5th jumps there.
    fn continuity(&self) -> Option<usize> {
        Some(4)
    }

    fn derivative(&self, t: f64, k: usize) -> SVector<f64, A> {
        let duration = self.tf - self.t0;
        let tau = ((t - self.t0) / duration).clamp(0.0, 1.0);
        let c = if k == 0 {
            poly_derivative(&POLY9, tau, 0)
        } else if t <= self.t0 || t >= self.tf {
            0.0 // at rest outside the motion (derivatives 1..4 vanish at the ends)
        } else {
            poly_derivative(&POLY9, tau, k) / duration.powi(k as i32)
        };
        scaled(&self.start, &self.end, k, c)
    }

    fn derivatives_into(&self, t: f64, out: &mut [SVector<f64, A>]) {
        let profile = |c: &mut [f64]| {
            let duration = self.tf - self.t0;
            let tau = ((t - self.t0) / duration).clamp(0.0, 1.0);
            poly_derivatives(&POLY9, tau, c);
            let moving = !(t <= self.t0 || t >= self.tf);
            for (k, c) in c.iter_mut().enumerate().skip(1) {
                *c = if moving { *c / duration.powi(k as i32) } else { 0.0 };
            }
        };
        along_profile(&self.start, &self.end, out, profile, |k| self.derivative(t, k));
    }

    fn target_extended(&self, t: DoubleDouble) -> Option<[SVector<DoubleDouble, A>; 3]> {
        let rate = DoubleDouble::from(1.0) / DoubleDouble::sum(self.tf, -self.t0);
        let tau = (t - self.t0) * rate;
        let zero = DoubleDouble::from(0.0);
        let c = if tau.hi <= 0.0 {
            [zero; 3]
        } else if tau.hi >= 1.0 {
            [DoubleDouble::from(1.0), zero, zero]
        } else {
            let [c, c1, c2] = poly_derivatives_extended(&POLY9, tau);
            [c, c1 * rate, c2 * rate * rate]
        };
        Some(scaled_extended(&self.start, &self.end, c))
    }
}

/// `out` along the scalar profile whose derivatives `profile` writes in
/// one pass (`c^(k)` into the `k`-th entry of a slice as long as `out`,
/// never empty), or one `derivative` at a time where `out` is longer than
/// [`poly_derivatives`] takes.
fn along_profile<const A: usize>(
    start: &SVector<f64, A>,
    end: &SVector<f64, A>,
    out: &mut [SVector<f64, A>],
    profile: impl FnOnce(&mut [f64]),
    derivative: impl Fn(usize) -> SVector<f64, A>,
) {
    let mut c = [0.0; FALLING_SIZE];
    let Some(c) = c.get_mut(..out.len()) else {
        for (k, gamma) in out.iter_mut().enumerate() {
            *gamma = derivative(k);
        }
        return;
    };
    if c.is_empty() {
        return;
    }
    profile(c);
    for (k, (gamma, &c)) in out.iter_mut().zip(c.iter()).enumerate() {
        *gamma = scaled(start, end, k, c);
    }
}

/// `gamma0 + (gammaf - gamma0) c` for `k = 0`, `(gammaf - gamma0) c` for a
/// derivative `k > 0` of a path from `start` to `end` along the scalar
/// profile `c`.
fn scaled<const A: usize>(start: &SVector<f64, A>, end: &SVector<f64, A>, k: usize, c: f64) -> SVector<f64, A> {
    if k == 0 {
        start + (end - start) * c
    } else {
        (end - start) * c
    }
}

/// The three phases shared by [`ThreePhase`] and [`SmoothThreePhase`]:
/// `gamma(t) = gamma0 + (gammaf - gamma0) c(t - t0)`, the ramp `h` given by
/// the coefficients of its polynomial.
#[derive(Debug, Clone, PartialEq)]
struct Phases<const A: usize> {
    t0: f64,
    tau: f64,
    tau0: f64,
    start: SVector<f64, A>,
    end: SVector<f64, A>,
    /// Coefficients of `h(s)/tau0`, `s = t/tau0`.
    ramp: &'static [f64],
}

impl<const A: usize> Phases<A> {
    fn new(
        t0: f64,
        tau: f64,
        tau0: f64,
        start: SVector<f64, A>,
        end: SVector<f64, A>,
        ramp: &'static [f64],
    ) -> Result<Self, TrajectoryError> {
        if !(t0.is_finite() && tau.is_finite() && tau > 0.0) {
            return Err(TrajectoryError::TimeSpan { t0, tf: t0 + tau });
        }
        if !(tau0 > 0.0 && tau0 <= 0.5 * tau) {
            return Err(TrajectoryError::Ramp { tau0, tau });
        }
        check_points(&start, &end)?;
        Ok(Self {
            t0,
            tau,
            tau0,
            start,
            end,
            ramp,
        })
    }

    /// `k`-th derivative of `h` at `t` (time since the ramp started).
    fn ramp(&self, t: f64, k: usize) -> f64 {
        self.tau0 * poly_derivative(self.ramp, t / self.tau0, k) / self.tau0.powi(k as i32)
    }

    /// `k`-th derivative of the scalar profile `c` at `t` (time since `t0`).
    fn profile(&self, t: f64, k: usize) -> f64 {
        let (tau, tau0) = (self.tau, self.tau0);
        let cruise = tau - tau0;
        if t <= 0.0 || t >= tau {
            return match k {
                0 if t <= 0.0 => 0.0,
                0 => 1.0,
                _ => 0.0,
            };
        }
        if t < tau0 {
            self.ramp(t, k) / cruise
        } else if t < tau - tau0 {
            match k {
                0 => (t - 0.5 * tau0) / cruise,
                1 => 1.0 / cruise,
                _ => 0.0,
            }
        } else {
            // d^k/dt^k h(tau - t) = (-1)^k h^(k)(tau - t)
            let sign = if k.is_multiple_of(2) { 1.0 } else { -1.0 };
            let value = -sign * self.ramp(tau - t, k) / cruise;
            if k == 0 { 1.0 + value } else { value }
        }
    }

    fn derivative(&self, t: f64, k: usize) -> SVector<f64, A> {
        scaled(&self.start, &self.end, k, self.profile(t - self.t0, k))
    }

    /// The target at `t` in double-double: [`profile`](Self::profile) of
    /// orders 0 to 2 in that arithmetic.
    fn target_extended(&self, t: DoubleDouble) -> [SVector<DoubleDouble, A>; 3] {
        let (tau, tau0) = (self.tau, self.tau0);
        let s = t - self.t0;
        // 1 / (tau - tau0)
        let per_cruise = DoubleDouble::from(1.0) / DoubleDouble::sum(tau, -tau0);
        let zero = DoubleDouble::from(0.0);
        // h^(k)(r) / (tau - tau0) = tau0^(1 - k) p^(k)(r / tau0) / (tau - tau0), k = 0, 1, 2
        let ramp = |r: DoubleDouble| {
            let [p, p1, p2] = poly_derivatives_extended(self.ramp, r / tau0);
            [p * tau0 * per_cruise, p1 * per_cruise, p2 / tau0 * per_cruise]
        };
        let c = if s.hi <= 0.0 {
            [zero; 3]
        } else if s.hi >= tau {
            [DoubleDouble::from(1.0), zero, zero]
        } else if s.hi < tau0 {
            ramp(s)
        } else if s.hi < tau - tau0 {
            [(s - 0.5 * tau0) * per_cruise, per_cruise, zero]
        } else {
            // d^k/dt^k h(tau - t) = (-1)^k h^(k)(tau - t)
            let [h, h1, h2] = ramp(-(s - tau));
            [-h + 1.0, h1, -h2]
        };
        scaled_extended(&self.start, &self.end, c)
    }

    /// [`Trajectory::derivatives_into`]: the phase found once, a ramp's
    /// polynomials side by side.
    fn derivatives_into(&self, t: f64, out: &mut [SVector<f64, A>]) {
        let (s, tau, tau0) = (t - self.t0, self.tau, self.tau0);
        let cruise = tau - tau0;
        // the ramp's derivatives at time r into it (see `ramp`)
        let ramp = |r: f64, h: &mut [f64]| {
            poly_derivatives(self.ramp, r / tau0, h);
            for (k, h) in h.iter_mut().enumerate() {
                *h = tau0 * *h / tau0.powi(k as i32);
            }
        };
        let profile = |h: &mut [f64]| {
            if s <= 0.0 || s >= tau {
                h.fill(0.0);
                h[0] = if s <= 0.0 { 0.0 } else { 1.0 };
            } else if s < tau0 {
                ramp(s, h);
                h.iter_mut().for_each(|h| *h /= cruise);
            } else if s < tau - tau0 {
                h.fill(0.0);
                h[0] = (s - 0.5 * tau0) / cruise;
                if let Some(h1) = h.get_mut(1) {
                    *h1 = 1.0 / cruise;
                }
            } else {
                ramp(tau - s, h);
                for (k, h) in h.iter_mut().enumerate() {
                    let sign = if k.is_multiple_of(2) { 1.0 } else { -1.0 };
                    let value = -sign * *h / cruise;
                    *h = if k == 0 { 1.0 + value } else { value };
                }
            }
        };
        along_profile(&self.start, &self.end, out, profile, |k| self.derivative(t, k));
    }
}

/// Coefficients of `h(s)/tau0 = 7 s^5 - 14 s^6 + 10 s^7 - 5/2 s^8` (docs/errata.md, eq. 86).
const RAMP: [f64; 9] = [0.0, 0.0, 0.0, 0.0, 0.0, 7.0, -14.0, 10.0, -2.5];

/// The three-phase path of eqs. (82), (85), (86) as corrected in docs/errata.md:
/// accelerate during `tau0`, move at constant speed, decelerate during `tau0`.
///
/// `gamma(t) = gamma0 + (gammaf - gamma0) c(t - t0)` with
/// `c_I = h(t)/(tau - tau0)`, `c_II = (t - tau0/2)/(tau - tau0)`,
/// `c_III = 1 - h(tau - t)/(tau - tau0)`,
/// `h(t) = tau0 (7 s^5 - 14 s^6 + 10 s^7 - 5/2 s^8)`, `s = t/tau0`.
/// Four times continuously differentiable (the 5th derivative jumps at the
/// phase switches).
///
/// ```
/// use crane_runtime::trajectory::{ThreePhase, Trajectory};
/// use crane_runtime::nalgebra::vector;
/// let path = ThreePhase::new(0.0, 20.0, 5.0, vector![0.0], vector![1.0]).unwrap();
/// assert!((path.derivative(10.0, 0)[0] - 0.5).abs() < 1e-15);
/// assert!((path.derivative(10.0, 1)[0] - 1.0 / 15.0).abs() < 1e-15);
/// ```
pub type ThreePhase<const A: usize> = Phased<A, false>;

/// Coefficients of the smooth ramp `h(s)/tau0 = 66 s^7 - 495/2 s^8 + 385 s^9
/// - 308 s^10 + 126 s^11 - 21 s^12` of [`SmoothThreePhase`].
///
/// Derivation: with `p(s) = h(tau0 s)/tau0` the ramp needs `p^(k)(0) = 0` for
/// `k = 0..6`, so `p = sum_{i=7}^{13} a_i s^i`, and at `s = 1` it must meet the
/// cruise line `c_II` (times `tau - tau0`), `t - tau0/2`: `p(1) = 1/2`,
/// `p'(1) = 1`, `p^(k)(1) = 0` for `k = 2..6`. These 7 linear equations in
/// `a_7..a_13` (solved in exact rational arithmetic) give
/// `a = [66, -495/2, 385, -308, 126, -21, 0]`: degree 12 suffices, `a_13 = 0`.
/// (The 7th derivative jumps at the switches: `p^(7)(0) = 66 * 7!`.)
const SMOOTH_RAMP: [f64; 13] = [
    0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 66.0, -247.5, 385.0, -308.0, 126.0, -21.0,
];

/// A smoother three-phase path: like [`ThreePhase`] (accelerate during
/// `tau0`, cruise at constant speed, decelerate during `tau0`), but with
/// ramps that make the profile six times continuously differentiable at the
/// phase switches `t0`, `t0 + tau0`, `t0 + tau - tau0`, `t0 + tau`.
///
/// `gamma(t) = gamma0 + (gammaf - gamma0) c(t - t0)` with
/// `c_I = h(t)/(tau - tau0)`, `c_II = (t - tau0/2)/(tau - tau0)`,
/// `c_III = 1 - h(tau - t)/(tau - tau0)` and
/// `h(t) = tau0 (66 s^7 - 495/2 s^8 + 385 s^9 - 308 s^10 + 126 s^11 - 21 s^12)`,
/// `s = t/tau0` (the lowest-degree polynomial with `h^(k)(0) = 0`, `k = 0..6`,
/// meeting the cruise line with derivatives up to order 6 at `s = 1`).
///
/// The 3D crane with pulley mass (paper sect. 6.2) needs the load path's
/// derivatives up to order 6 for its slewing torque (docs/errata.md): on the paper's
/// C4 profile [`ThreePhase`] that torque has impulses at the switches, on this
/// one it is bounded. Same constructor as [`ThreePhase`]; the ramps are
/// steeper in the middle: for the same `tau0` the peak of `h''` is
/// `2.707/tau0` against `2.1875/tau0` (1.24 times higher, at `s = 1/2`).
///
/// ```
/// use crane_runtime::trajectory::{SmoothThreePhase, Trajectory};
/// use crane_runtime::nalgebra::vector;
/// let path = SmoothThreePhase::new(0.0, 20.0, 5.0, vector![0.0], vector![1.0]).unwrap();
/// assert!((path.derivative(10.0, 0)[0] - 0.5).abs() < 1e-15);
/// assert!((path.derivative(10.0, 1)[0] - 1.0 / 15.0).abs() < 1e-15);
/// // the 6th derivative is continuous at the end of the acceleration phase
/// let (left, right) = (path.derivative(5.0 - 1e-9, 6)[0], path.derivative(5.0 + 1e-9, 6)[0]);
/// assert!((left - right).abs() < 1e-6);
/// assert_eq!(path.derivative(20.0, 0)[0], 1.0);
/// ```
pub type SmoothThreePhase<const A: usize> = Phased<A, true>;

/// A three-phase move (ramp, constant speed, ramp) with the ramp of
/// [`ThreePhase`] (`SMOOTH = false`, four times continuously
/// differentiable) or of [`SmoothThreePhase`] (`SMOOTH = true`, six times).
#[derive(Debug, Clone, PartialEq)]
pub struct Phased<const A: usize, const SMOOTH: bool>(Phases<A>);

impl<const A: usize, const SMOOTH: bool> Phased<A, SMOOTH> {
    /// Motion from `start` at `t0` to `end` at `t0 + tau` with ramps of length `tau0` (`0 < tau0 <= tau/2`).
    pub fn new(
        t0: f64,
        tau: f64,
        tau0: f64,
        start: SVector<f64, A>,
        end: SVector<f64, A>,
    ) -> Result<Self, TrajectoryError> {
        Phases::new(t0, tau, tau0, start, end, if SMOOTH { &SMOOTH_RAMP } else { &RAMP }).map(Self)
    }
}

impl<const A: usize, const SMOOTH: bool> Trajectory<A> for Phased<A, SMOOTH> {
    fn derivative(&self, t: f64, k: usize) -> SVector<f64, A> {
        self.0.derivative(t, k)
    }

    fn derivatives_into(&self, t: f64, out: &mut [SVector<f64, A>]) {
        self.0.derivatives_into(t, out)
    }

    fn target_extended(&self, t: DoubleDouble) -> Option<[SVector<DoubleDouble, A>; 3]> {
        Some(self.0.target_extended(t))
    }

    /// 4 for the ramps of [`ThreePhase`], [`SMOOTH_THREE_PHASE_CONTINUITY`]
    /// for those of [`SmoothThreePhase`].
    fn continuity(&self) -> Option<usize> {
        Some(if SMOOTH { SMOOTH_THREE_PHASE_CONTINUITY } else { 4 })
    }
}

/// How many derivatives of a [`SmoothThreePhase`] path are continuous: the
/// smoothest of the built-in paths.
pub const SMOOTH_THREE_PHASE_CONTINUITY: usize = 6;

/// A user-supplied path: a closure `(t, k) -> gamma^(k)(t)`.
///
/// ```
/// use crane_runtime::trajectory::{FromFn, Trajectory};
/// use crane_runtime::nalgebra::{vector, SVector};
/// // a load lowered at constant acceleration 0.1 m/s^2
/// let path = FromFn(|t: f64, k: usize| -> SVector<f64, 1> {
///     match k { 0 => vector![-10.0 - 0.05 * t * t], 1 => vector![-0.1 * t],
///               2 => vector![-0.1], _ => vector![0.0] }
/// });
/// assert_eq!(path.derivative(1.0, 1), vector![-0.1]);
/// ```
#[derive(Debug, Clone, Copy)]
pub struct FromFn<F>(pub F);

impl<const A: usize, F: Fn(f64, usize) -> SVector<f64, A>> Trajectory<A> for FromFn<F> {
    fn derivative(&self, t: f64, k: usize) -> SVector<f64, A> {
        (self.0)(t, k)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::vector;

    /// The built-in paths' double-double targets round to their `f64`
    /// targets (to 1e-10 of the move: the `f64` polynomials of the
    /// derivatives cancel, measured up to 1.2e-12 m/s^2 off where the
    /// acceleration passes zero), in every phase; and their positions
    /// at the step times `n dt` have the second differences of Taylor's
    /// expansion, `gamma'' + dt^2 gamma^(4)/12 + dt^4 gamma^(6)/360` times
    /// `dt^2`, to `O(dt^6)` (away from the phase switches, where
    /// `gamma^(5)` jumps): at dt = 0.001 s to 1e-11 m/s^2 (the `f64`
    /// derivatives it is compared with are off by up to 1.2e-12), where positions
    /// rounded to `f64` would leave noise of about 1e-16 |gamma| / dt^2 =
    /// 1e-9.
    #[test]
    fn extended_targets_are_the_targets_without_their_rounding() {
        fn check(path: &impl Trajectory<2>, tf: f64, switches: &[f64]) {
            let dt = 0.001;
            let steps = (tf / dt).round() as u64;
            let at = |n: u64| path.target_extended(DoubleDouble::step_time(0.0, n, dt)).unwrap();
            for n in 1..steps {
                let t = DoubleDouble::step_time(0.0, n, dt);
                let [x, v, a] = at(n);
                for (k, extended) in [x, v, a].iter().enumerate() {
                    let rounded = path.derivative(t.hi, k);
                    for i in 0..2 {
                        assert!(
                            (extended[i].hi - rounded[i]).abs() <= 1e-10 * (1.0 + rounded[i].abs()),
                            "t = {t}, order {k}: {} against {}",
                            extended[i],
                            rounded[i]
                        );
                    }
                }
                if switches.iter().any(|s| (t.hi - s).abs() < 2.0 * dt) {
                    continue;
                }
                let (before, after) = (at(n - 1)[0], at(n + 1)[0]);
                let expected = path.derivative(t.hi, 2)
                    + path.derivative(t.hi, 4) * (dt * dt / 12.0)
                    + path.derivative(t.hi, 6) * (dt.powi(4) / 360.0);
                for i in 0..2 {
                    let second = ((after[i] + before[i]) - x[i] * 2.0) / (dt * dt);
                    assert!(
                        (second.hi - expected[i]).abs() <= 1e-11,
                        "t = {t}: {second} against {}",
                        expected[i]
                    );
                }
            }
        }
        let (start, end) = (vector![30.0, 0.0], vector![0.0, 30.0]);
        check(
            &Poly9::new(0.0, 4.0, vector![0.0, -10.0], vector![-3.0, -14.0]).unwrap(),
            4.0,
            &[],
        );
        let switches = [5.0, 15.0];
        check(&ThreePhase::new(0.0, 20.0, 5.0, start, end).unwrap(), 20.0, &switches);
        check(
            &SmoothThreePhase::new(0.0, 20.0, 5.0, start, end).unwrap(),
            20.0,
            &switches,
        );
    }

    /// The built-in paths' derivatives in one pass are their derivatives
    /// one at a time, bit for bit, in every phase of the move, and past
    /// the orders the one pass takes.
    #[test]
    fn derivatives_in_one_pass_are_those_one_at_a_time() {
        fn check(path: &impl Trajectory<2>, times: &[f64]) {
            for &t in times {
                for orders in [0, 1, 3, 7, FALLING_SIZE, FALLING_SIZE + 2] {
                    let mut out = vec![SVector::<f64, 2>::repeat(f64::NAN); orders];
                    path.derivatives_into(t, &mut out);
                    for (k, gamma) in out.iter().enumerate() {
                        // bit for bit, or both not a number (whose sign
                        // bit the order of the operands sets)
                        let one = path.derivative(t, k);
                        let same = |(a, b): (&f64, &f64)| a.to_bits() == b.to_bits() || (a.is_nan() && b.is_nan());
                        assert!(
                            gamma.iter().zip(one.iter()).all(same),
                            "t = {t}, k = {k}: {gamma} {one}"
                        );
                    }
                }
            }
        }
        let (start, end) = (vector![0.5, -10.0], vector![-3.0, -14.0]);
        let times = [-1.0, 0.0, 0.3, 2.5, 5.0, 7.7, 12.0, 17.5, 19.9, 20.0, 25.0, f64::NAN];
        check(&Poly9::new(0.0, 20.0, start, end).unwrap(), &times);
        check(&ThreePhase::new(0.0, 20.0, 5.0, start, end).unwrap(), &times);
        check(&SmoothThreePhase::new(0.0, 20.0, 5.0, start, end).unwrap(), &times);
    }

    /// The table's falling factorials are the products they stand for.
    #[test]
    fn falling_factorials_are_the_products() {
        for i in 0..FALLING_SIZE + 3 {
            for k in 0..=i {
                let product: f64 = ((i - k + 1)..=i).map(|j| j as f64).product();
                assert_eq!(falling(i, k), product, "{i}, {k}");
            }
        }
    }

    /// Central difference of derivative `k - 1`; error O(h^2) ~ 1e-8 relative
    /// for h = 1e-4 on these polynomials, plus round-off eps/h ~ 1e-12.
    fn fd<T: Trajectory<1>>(path: &T, t: f64, k: usize) -> f64 {
        let h = 1e-4;
        (path.derivative(t + h, k - 1)[0] - path.derivative(t - h, k - 1)[0]) / (2.0 * h)
    }

    #[test]
    fn poly9_derivatives_match_finite_differences() {
        let path = Poly9::new(0.5, 4.5, vector![1.0], vector![3.0]).unwrap();
        for &t in &[0.7, 1.3, 2.5, 3.9] {
            for k in 1..=6 {
                let exact = path.derivative(t, k)[0];
                let approx = fd(&path, t, k);
                assert!((exact - approx).abs() <= 1e-6 * (1.0 + exact.abs()), "k={k} t={t}");
            }
        }
    }

    #[test]
    fn poly9_is_rest_to_rest() {
        let path = Poly9::new(0.0, 4.0, vector![0.0], vector![-3.0]).unwrap();
        assert_eq!(path.derivative(0.0, 0)[0], 0.0);
        assert_eq!(path.derivative(4.0, 0)[0], -3.0);
        // c^(k)(0) = c^(k)(1) = 0 for k = 1..4 evaluated on the polynomial itself
        for k in 1..=4 {
            assert_eq!(poly_derivative(&POLY9, 0.0, k), 0.0);
            assert!(poly_derivative(&POLY9, 1.0, k).abs() < 1e-9, "k={k}");
        }
        assert_eq!(path.derivative(5.0, 0)[0], -3.0);
    }

    #[test]
    fn three_phase_is_four_times_continuously_differentiable() {
        let path = ThreePhase::new(0.0, 20.0, 5.0, vector![0.0], vector![1.0]).unwrap();
        for &switch in &[0.0, 5.0, 15.0, 20.0] {
            for k in 0..=4 {
                let left = path.derivative(switch - 1e-9, k)[0];
                let right = path.derivative(switch + 1e-9, k)[0];
                // jumps would be O(1); continuity leaves O(1e-9 * |c^(k+1)|)
                assert!((left - right).abs() < 1e-7, "k={k} at t={switch}: {left} vs {right}");
            }
        }
        for &t in &[1.0, 4.0, 7.0, 16.0, 19.5] {
            for k in 1..=5 {
                let exact = path.derivative(t, k)[0];
                assert!(
                    (exact - fd(&path, t, k)).abs() <= 1e-6 * (1.0 + exact.abs()),
                    "k={k} t={t}"
                );
            }
        }
        assert_eq!(path.derivative(20.0, 0)[0], 1.0);
    }

    #[test]
    fn smooth_ramp_meets_its_conditions() {
        // p^(k)(0) = 0 for k = 0..6; p(1) = 1/2, p'(1) = 1, p^(k)(1) = 0 for k = 2..6
        for k in 0..=6 {
            assert_eq!(poly_derivative(&SMOOTH_RAMP, 0.0, k), 0.0, "k={k}");
            let expected = match k {
                0 => 0.5,
                1 => 1.0,
                _ => 0.0,
            };
            let at_one = poly_derivative(&SMOOTH_RAMP, 1.0, k);
            // the terms reach 66 * 12!/5! ~ 2.6e8 for k = 6: round-off ~ 1e-7
            assert!((at_one - expected).abs() < 1e-6, "k={k}: {at_one}");
        }
        // the 7th derivative jumps (so the profile is exactly C6)
        assert!(poly_derivative(&SMOOTH_RAMP, 0.0, 7).abs() > 1e5);
    }

    #[test]
    fn smooth_three_phase_is_six_times_continuously_differentiable() {
        let path = SmoothThreePhase::new(0.0, 20.0, 5.0, vector![0.0], vector![1.0]).unwrap();
        let paper = ThreePhase::new(0.0, 20.0, 5.0, vector![0.0], vector![1.0]).unwrap();
        for &switch in &[0.0, 5.0, 15.0, 20.0] {
            for k in 0..=6 {
                let left = path.derivative(switch - 1e-9, k)[0];
                let right = path.derivative(switch + 1e-9, k)[0];
                // jumps would be O(1e-3..1) (cf. the paper profile below); continuity leaves
                // O(1e-9 |c^(k+1)|) plus round-off in the ramp polynomial
                assert!((left - right).abs() < 1e-7, "k={k} at t={switch}: {left} vs {right}");
            }
            // the paper's C4 profile jumps in the 5th derivative there
            let jump5 = paper.derivative(switch + 1e-9, 5)[0] - paper.derivative(switch - 1e-9, 5)[0];
            assert!(jump5.abs() > 1e-3, "t={switch}: {jump5}");
        }
        for &t in &[1.0, 2.5, 4.0, 7.0, 16.0, 18.0, 19.5] {
            for k in 1..=8 {
                let exact = path.derivative(t, k)[0];
                let approx = fd(&path, t, k);
                assert!(
                    (exact - approx).abs() <= 1e-6 * (1.0 + exact.abs()),
                    "k={k} t={t}: {exact} vs {approx}"
                );
            }
        }
        assert_eq!(path.derivative(0.0, 0)[0], 0.0);
        assert_eq!(path.derivative(20.0, 0)[0], 1.0);
        assert_eq!(path.derivative(25.0, 1)[0], 0.0);
        // monotone: the speed c' stays >= 0 on the ramps
        for i in 0..=1000 {
            assert!(path.derivative(20.0 * i as f64 / 1000.0, 1)[0] >= 0.0);
        }
        assert!(SmoothThreePhase::new(0.0, 10.0, 6.0, vector![0.0], vector![1.0]).is_err());
    }

    #[test]
    fn bad_inputs_are_errors() {
        assert!(Poly9::new(1.0, 1.0, vector![0.0], vector![1.0]).is_err());
        assert!(Poly9::new(0.0, 1.0, vector![f64::NAN], vector![1.0]).is_err());
        assert!(ThreePhase::new(0.0, 10.0, 6.0, vector![0.0], vector![1.0]).is_err());
    }
}
