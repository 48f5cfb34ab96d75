//! Time-discretisation schemes: how the rates at `t_{n+1}` follow from the
//! new value and the history.
//!
//! The problems (servo constraints in redundant coordinates, eqs. 22; in
//! minimal coordinates, eqs. 24) discretise second-order kinematics
//! `y' = v`, `v' = a` of some of their unknowns (`p`, or `mu1`). Every
//! scheme here is a constant-step linear multistep formula in which the new
//! rate is an affine function of the new value,
//! ```text
//! dt y'_{n+1} = c (y_{n+1} - ybar),   ybar = -sum_{j=1..k} alpha_j y_{n+1-j}
//! ```
//! applied to both `y' = v` and `v' = a` (so `a` is affine in `y_{n+1}` too,
//! with slope `(c/dt)^2`). A problem sees only that [`Formula`] and a
//! [`History`]; it never names a scheme, so a new scheme is a new variant
//! here and touches no problem.
//!
//! BDF-k in normalised form, `sum_j alpha_j y_{n+1-j} = beta dt y'_{n+1}`
//! (`alpha_0 = 1`, `c = 1/beta`):
//!
//! | k | alpha_1 .. alpha_k | beta |
//! |---|---|---|
//! | 1 | -1 | 1 |
//! | 2 | -4/3, 1/3 | 2/3 |
//! | 3 | -18/11, 9/11, -2/11 | 6/11 |
//! | 4 | -48/25, 36/25, -16/25, 3/25 | 12/25 |
//! | 5 | -300/137, 300/137, -200/137, 75/137, -12/137 | 60/137 |
//!
//! BDF-1 is backward Euler, the paper's scheme (eqs. 22a, 24a). BDF-k with
//! `k < 7` converges with order `k` in all variables of an index-3
//! Hessenberg DAE once it is started consistently (Brenan, Campbell and
//! Petzold, *Numerical Solution of Initial-Value Problems in DAEs*, ch. 3).
//!
//! ```
//! use crane_runtime::scheme::Scheme;
//! let bdf3: Scheme = "bdf3".parse().unwrap();
//! assert_eq!(bdf3.order(), 3);
//! // the formula differentiates a polynomial of degree k exactly:
//! // y = t^3 at t = -2, -1, 0 (history) and 1 (new), dt = 1
//! let f = bdf3.formula();
//! let past = [0.0, -1.0, -8.0]; // y_n, y_{n-1}, y_{n-2}
//! let ybar: f64 = -(0..3).map(|j| f.alpha[j] * past[j]).sum::<f64>();
//! assert!((f.c * (1.0 - ybar) - 3.0).abs() < 1e-12); // y'(1) = 3
//! ```

use std::fmt;
use std::str::FromStr;

use nalgebra::SVector;

/// Largest history length of a scheme here (BDF-5).
pub const MAX_STEPS: usize = 5;

/// A time-discretisation scheme of the steppers.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub enum Scheme {
    /// Backward Euler (BDF-1), the paper's scheme: first order.
    #[default]
    BackwardEuler,
    /// BDF of order 2.
    Bdf2,
    /// BDF of order 3.
    Bdf3,
    /// BDF of order 4.
    Bdf4,
    /// BDF of order 5.
    Bdf5,
}

/// The coefficients of a scheme: `dt y'_{n+1} = c (y_{n+1} + sum_j alpha_j y_{n+1-j})`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Formula {
    /// Number of past values the formula uses.
    pub steps: usize,
    /// `c = 1/beta`: `d y'_{n+1} / d y_{n+1} = c/dt`.
    pub c: f64,
    /// `alpha_1 .. alpha_k` (the first `steps` entries; the rest are 0).
    pub alpha: [f64; MAX_STEPS],
}

impl Scheme {
    /// All schemes, in order.
    pub const ALL: [Scheme; 5] = [
        Scheme::BackwardEuler,
        Scheme::Bdf2,
        Scheme::Bdf3,
        Scheme::Bdf4,
        Scheme::Bdf5,
    ];

    /// BDF of order `k` (1 = backward Euler), if `1 <= k <= 5`.
    pub fn bdf(k: usize) -> Option<Scheme> {
        Self::ALL.get(k.checked_sub(1)?).copied()
    }

    /// Order of convergence (and number of past steps).
    pub fn order(self) -> usize {
        match self {
            Scheme::BackwardEuler => 1,
            Scheme::Bdf2 => 2,
            Scheme::Bdf3 => 3,
            Scheme::Bdf4 => 4,
            Scheme::Bdf5 => 5,
        }
    }

    /// The name used on the command line, in scenario files and in results:
    /// `backward-euler`, `bdf2` .. `bdf5`.
    pub fn name(self) -> &'static str {
        match self {
            Scheme::BackwardEuler => "backward-euler",
            Scheme::Bdf2 => "bdf2",
            Scheme::Bdf3 => "bdf3",
            Scheme::Bdf4 => "bdf4",
            Scheme::Bdf5 => "bdf5",
        }
    }

    /// The scheme's formula.
    pub fn formula(self) -> Formula {
        bdf_formula(self.order())
    }
}

/// BDF-k coefficients (table in the module docs).
fn bdf_formula(k: usize) -> Formula {
    let (beta, alpha): (f64, &[f64]) = match k {
        1 => (1.0, &[-1.0]),
        2 => (2.0 / 3.0, &[-4.0 / 3.0, 1.0 / 3.0]),
        3 => (6.0 / 11.0, &[-18.0 / 11.0, 9.0 / 11.0, -2.0 / 11.0]),
        4 => (12.0 / 25.0, &[-48.0 / 25.0, 36.0 / 25.0, -16.0 / 25.0, 3.0 / 25.0]),
        _ => (
            60.0 / 137.0,
            &[
                -300.0 / 137.0,
                300.0 / 137.0,
                -200.0 / 137.0,
                75.0 / 137.0,
                -12.0 / 137.0,
            ],
        ),
    };
    let mut padded = [0.0; MAX_STEPS];
    padded[..alpha.len()].copy_from_slice(alpha);
    Formula {
        steps: alpha.len(),
        c: 1.0 / beta,
        alpha: padded,
    }
}

impl fmt::Display for Scheme {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// A scheme name that is none of `backward-euler`, `bdf1` .. `bdf5`.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("unknown scheme `{0}`; expected backward-euler, bdf1, bdf2, bdf3, bdf4 or bdf5")]
pub struct UnknownScheme(pub String);

impl FromStr for Scheme {
    type Err = UnknownScheme;
    /// `backward-euler` (or `bdf1`), `bdf2` .. `bdf5`.
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        match s {
            "backward-euler" | "bdf1" => Ok(Scheme::BackwardEuler),
            "bdf2" => Ok(Scheme::Bdf2),
            "bdf3" => Ok(Scheme::Bdf3),
            "bdf4" => Ok(Scheme::Bdf4),
            "bdf5" => Ok(Scheme::Bdf5),
            other => Err(UnknownScheme(other.to_string())),
        }
    }
}

/// Past values `y_n, y_{n-1}, ...` and rates `y'_n, y'_{n-1}, ...` of the
/// discretised unknowns, newest first; fixed size, so pushing a step does
/// not allocate.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct History<const K: usize> {
    values: [SVector<f64, K>; MAX_STEPS],
    rates: [SVector<f64, K>; MAX_STEPS],
    /// How many entries are valid (oldest ones may be missing early on).
    known: usize,
}

/// The affine maps a scheme imposes at one step, per component `i`:
/// `v_i = (c/dt) (y_i - ybar_i)`, `a_i = (c/dt) (v_i - vbar_i)`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StepFormula<const K: usize> {
    /// `c/dt`: the slope of `v` in `y` (and of `a` in `v`).
    pub rate: f64,
    /// `ybar` from the past values.
    pub value_offset: SVector<f64, K>,
    /// `vbar` from the past rates.
    pub rate_offset: SVector<f64, K>,
}

impl<const K: usize> StepFormula<K> {
    /// `v_i` and `dt^2 a_i` for a new value `y` of component `i` (generic in
    /// the scalar, so that dual numbers pass through).
    pub fn kinematics<T>(&self, i: usize, y: T, dt: f64) -> (T, T)
    where
        T: Copy + std::ops::Sub<f64, Output = T> + std::ops::Mul<f64, Output = T>,
    {
        let v = (y - self.value_offset[i]) * self.rate;
        // dt^2 a = dt^2 rate (v - vbar) = (c dt) (v - vbar) ... written so
        // that backward Euler reads y - y_n - dt v_n exactly
        let c_dt = self.rate * dt;
        let accel_dt2 = (y - self.value_offset[i]) * (c_dt * c_dt) - self.rate_offset[i] * (c_dt * dt);
        (v, accel_dt2)
    }
}

impl<const K: usize> History<K> {
    /// A history at rest: every past value `y0`, every past rate zero (the
    /// exact past of a crane that rests before `t0`).
    pub fn at_rest(y0: SVector<f64, K>) -> Self {
        Self {
            values: [y0; MAX_STEPS],
            rates: [SVector::zeros(); MAX_STEPS],
            known: MAX_STEPS,
        }
    }

    /// A history that knows only the start `(y0, v0)`; the first steps then
    /// use lower orders (see [`History::formula`]).
    pub fn start(y0: SVector<f64, K>, v0: SVector<f64, K>) -> Self {
        Self {
            values: [y0; MAX_STEPS],
            rates: [v0; MAX_STEPS],
            known: 1,
        }
    }

    /// A history from past values and rates, newest (`t0`) first.
    pub fn from_past(values: &[SVector<f64, K>], rates: &[SVector<f64, K>]) -> Self {
        let known = values.len().min(rates.len()).clamp(1, MAX_STEPS);
        let mut history = Self::start(values[0], rates[0]);
        history.values[..known].copy_from_slice(&values[..known]);
        history.rates[..known].copy_from_slice(&rates[..known]);
        history.known = known;
        history
    }

    /// Record an accepted step: `y_{n+1}, y'_{n+1}` become the newest entry.
    pub fn push(&mut self, y: SVector<f64, K>, v: SVector<f64, K>) {
        self.values.rotate_right(1);
        self.rates.rotate_right(1);
        self.values[0] = y;
        self.rates[0] = v;
        self.known = (self.known + 1).min(MAX_STEPS);
    }

    /// The newest value `y_n`.
    pub fn value(&self) -> &SVector<f64, K> {
        &self.values[0]
    }

    /// The newest rate `y'_n`.
    pub fn rate(&self) -> &SVector<f64, K> {
        &self.rates[0]
    }

    /// Order actually available for `scheme`: its own, or lower while the
    /// history is shorter than the scheme needs (a start of which only the
    /// present is known).
    pub fn order(&self, scheme: Scheme) -> usize {
        scheme.order().min(self.known)
    }

    /// The scheme's affine maps for the step after the newest entry, with
    /// time step `dt`.
    pub fn formula(&self, scheme: Scheme, dt: f64) -> StepFormula<K> {
        let formula = bdf_formula(self.order(scheme));
        let mut value_offset = SVector::zeros();
        let mut rate_offset = SVector::zeros();
        for j in 0..formula.steps {
            value_offset -= self.values[j] * formula.alpha[j];
            rate_offset -= self.rates[j] * formula.alpha[j];
        }
        StepFormula {
            rate: formula.c / dt,
            value_offset,
            rate_offset,
        }
    }

    /// Predictor for the next value: the polynomial through the last
    /// `order + 1` values (at most the five held) (or `y_n + dt y'_n` while only the start is known),
    /// extrapolated one step.
    pub fn predict(&self, scheme: Scheme, dt: f64) -> SVector<f64, K> {
        let order = self.order(scheme);
        if self.known < 2 {
            return self.values[0] + self.rates[0] * dt;
        }
        // extrapolation through `points` equally spaced values:
        // y_{n+1} = sum_j (-1)^j C(points, j+1) y_{n-j}
        let points = (order + 1).min(self.known);
        let mut prediction = SVector::zeros();
        let mut binomial = 1.0;
        for j in 0..points {
            binomial = binomial * (points - j) as f64 / (j + 1) as f64;
            let sign = if j % 2 == 0 { 1.0 } else { -1.0 };
            prediction += self.values[j] * (sign * binomial);
        }
        prediction
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::vector;

    /// BDF-k is exact for polynomials of degree k (and its consistency
    /// conditions hold): `sum alpha = -1`, `sum j alpha_j = -beta`.
    #[test]
    fn bdf_k_differentiates_degree_k_polynomials_exactly() {
        for scheme in Scheme::ALL {
            let k = scheme.order();
            let f = scheme.formula();
            assert_eq!(f.steps, k);
            for degree in 0..=k {
                let y = |t: f64| t.powi(degree as i32);
                let dy = |t: f64| {
                    if degree == 0 {
                        0.0
                    } else {
                        degree as f64 * t.powi(degree as i32 - 1)
                    }
                };
                let dt = 0.5;
                let t_new = 1.0;
                let past: Vec<_> = (1..=k).map(|j| vector![y(t_new - j as f64 * dt)]).collect();
                let history = History::<1>::from_past(&past, &past);
                assert_eq!(history.order(scheme), k);
                let step = history.formula(scheme, dt);
                let (v, _) = step.kinematics(0, y(t_new), dt);
                assert!(
                    (v - dy(t_new)).abs() < 1e-12,
                    "{scheme} degree {degree}: {v} vs {}",
                    dy(t_new)
                );
            }
        }
    }

    /// Backward Euler's affine maps are eq. (22a) and the difference quotient of v.
    #[test]
    fn backward_euler_is_eq_22a() {
        let history = History::<1>::start(vector![2.0], vector![3.0]);
        let step = history.formula(Scheme::BackwardEuler, 0.1);
        let (v, a_dt2) = step.kinematics(0, 2.5, 0.1);
        assert!((v - (2.5 - 2.0) / 0.1).abs() < 1e-12);
        assert!((a_dt2 - (2.5 - 2.0 - 0.1 * 3.0)).abs() < 1e-12);
    }

    /// The predictor of order k extrapolates polynomials of degree k exactly
    /// (degree 4 for BDF-5: the history holds five values).
    #[test]
    fn predictor_extrapolates_polynomials() {
        for scheme in Scheme::ALL {
            let k = scheme.order().min(MAX_STEPS - 1);
            let y = |t: f64| (0..=k).map(|i| t.powi(i as i32) / (i + 1) as f64).sum::<f64>();
            let past: Vec<_> = (0..MAX_STEPS).map(|j| vector![y(-(j as f64))]).collect();
            let history = History::<1>::from_past(&past, &past);
            let p = history.predict(scheme, 1.0)[0];
            assert!((p - y(1.0)).abs() < 1e-9, "{scheme}: {p} vs {}", y(1.0));
        }
    }

    #[test]
    fn names_round_trip() {
        for scheme in Scheme::ALL {
            assert_eq!(scheme.name().parse::<Scheme>(), Ok(scheme));
            assert_eq!(Scheme::bdf(scheme.order()), Some(scheme));
        }
        assert_eq!("bdf1".parse::<Scheme>(), Ok(Scheme::BackwardEuler));
        assert!("bdf6".parse::<Scheme>().is_err());
        assert_eq!(Scheme::bdf(0), None);
        assert_eq!(Scheme::bdf(6), None);
    }
}
