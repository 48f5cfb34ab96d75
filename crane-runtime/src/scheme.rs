//! Time-discretisation schemes: how the rates at `t_{n+1}` follow from the
//! new value and the history.
//!
//! The problems (servo constraints in redundant coordinates, eqs. 22; in
//! minimal coordinates, eqs. 24; the forward dynamics) discretise
//! second-order kinematics `y' = v`, `v' = a` of some of their unknowns
//! (`p`, `q` or `mu1`). Every scheme here is a constant-step linear
//! multistep formula in which the new rate is an affine function of the new
//! value,
//! ```text
//! dt y'_{n+1} = c (y_{n+1} - ybar),   ybar = -sum_{j=1..k} alpha_j y_{n+1-j}
//! ```
//! applied to both `y' = v` and `v' = a` (so `a` is affine in `y_{n+1}` too,
//! with slope `(c/dt)^2`). A [`Method`] says which `c` and `alpha` a step
//! uses; a [`History`] is the method at work (its past values, rates, the
//! predictor and the start-up rule) and hands a problem the affine maps of
//! one step and their slopes ([`StepFormula`], [`Slopes`]). A problem never
//! names a scheme, so a new scheme is one `impl Method` and touches no
//! problem.
//!
//! BDF-k in normalised form, `sum_j alpha_j y_{n+1-j} = beta dt y'_{n+1}`
//! (`alpha_0 = 1`, `c = 1/beta`), the built-in [`Scheme`]s:
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
//! use crane_runtime::scheme::{History, Method, Scheme};
//! use crane_runtime::nalgebra::vector;
//! let bdf3: Scheme = "bdf3".parse().unwrap();
//! assert_eq!(bdf3.order(), 3);
//! // the formula differentiates a polynomial of degree k exactly:
//! // y = t^3 at t = -2, -1, 0 (history) and 1 (new), dt = 1
//! let past = [vector![0.0], vector![-1.0], vector![-8.0]]; // y_n, y_{n-1}, y_{n-2}
//! let history = History::from_past(bdf3, &past, &past).unwrap();
//! let (rate, _) = history.formula(1.0).kinematics(0, 1.0);
//! assert!((rate - 3.0).abs() < 1e-12); // y'(1) = 3
//! ```

use std::fmt;
use std::str::FromStr;

use nalgebra::SVector;

use crate::double_double::DoubleDouble;

/// Largest history length of a scheme here (BDF-5).
pub const MAX_STEPS: usize = 5;

/// The coefficients of one step: `dt y'_{n+1} = c (y_{n+1} + sum_j alpha_j y_{n+1-j})`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Formula {
    /// Number of past values the formula uses (at most [`MAX_STEPS`]).
    pub steps: usize,
    /// `c = 1/beta`: `d y'_{n+1} / d y_{n+1} = c/dt`.
    pub c: f64,
    /// `alpha_1 .. alpha_k` (the first `steps` entries; the rest are 0).
    pub alpha: [f64; MAX_STEPS],
}

impl Formula {
    /// The formula with `c` and the past coefficients `alpha`: at most
    /// [`MAX_STEPS`] of them, which the compiler checks (a sixth
    /// coefficient is a compile error, not a coefficient dropped):
    ///
    /// ```compile_fail
    /// let six = crane_runtime::scheme::Formula::new(1.0, &[0.1; 6]);
    /// ```
    pub fn new<const K: usize>(c: f64, alpha: &[f64; K]) -> Self {
        const { assert!(K <= MAX_STEPS, "a formula uses at most MAX_STEPS = 5 past values") };
        let mut padded = [0.0; MAX_STEPS];
        padded[..K].copy_from_slice(alpha);
        Self {
            steps: K,
            c,
            alpha: padded,
        }
    }
}

/// A constant-step linear multistep method for `y' = v`, `v' = a`: the
/// formula of each step and how many past values its predictor uses.
///
/// The built-in methods are the [`Scheme`]s; a method of one's own needs
/// only these few lines and runs on every problem. Here is the second-order
/// numerical differentiation formula of Klopfenstein and Shampine (NDF-2,
/// the default of MATLAB's `ode15s`): BDF-2 plus `-kappa gamma_2 nabla^3
/// y_{n+1}` with `kappa = -1/9`, `gamma_2 = 3/2`, which puts a third past
/// value into the formula,
/// `5/3 y_{n+1} - 5/2 y_n + y_{n-1} - 1/6 y_{n-2} = dt y'_{n+1}`:
///
/// ```
/// use crane_runtime::scheme::{Formula, Method};
///
/// #[derive(Debug, Clone, Copy)]
/// struct Ndf2;
///
/// impl Method for Ndf2 {
///     fn name(&self) -> &'static str { "ndf2" }
///     fn order(&self) -> usize { 2 }
///     fn formula(&self, known: usize) -> Formula {
///         match known {
///             1 => Formula::new(1.0, &[-1.0]),                      // backward Euler
///             2 => Formula::new(1.5, &[-4.0 / 3.0, 1.0 / 3.0]),     // BDF-2
///             _ => Formula::new(5.0 / 3.0, &[-1.5, 0.6, -0.1]),     // NDF-2
///         }
///     }
/// }
/// let f = Ndf2.formula(3);
/// // consistency: constants and linear functions are differentiated exactly
/// assert!((1.0 + f.alpha.iter().sum::<f64>()).abs() < 1e-15);
/// let t = [1.0, 0.0, -1.0, -2.0]; // y = t at t_{n+1}, t_n, t_{n-1}, t_{n-2}, dt = 1
/// let slope = f.c * (t[0] + (0..3).map(|j| f.alpha[j] * t[j + 1]).sum::<f64>());
/// assert!((slope - 1.0).abs() < 1e-15);
/// ```
pub trait Method: Copy + fmt::Debug + Send + Sync + 'static {
    /// The name in results and plot titles.
    fn name(&self) -> &'static str;

    /// The order of convergence once the history is long enough.
    fn order(&self) -> usize;

    /// The formula of a step after which `known` (`1..=MAX_STEPS`) past
    /// values are in the history: the method's own once it has enough, a
    /// lower-order one before (the start-up of a moving start).
    fn formula(&self, known: usize) -> Formula;

    /// Past values the predictor extrapolates through, of `known`: the
    /// polynomial of degree `order` (at most what is known).
    fn predictor_points(&self, known: usize) -> usize {
        (self.order() + 1).min(known)
    }
}

/// The built-in schemes: BDF of orders 1 (backward Euler) to 5.
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

impl Scheme {
    /// All schemes, in order: the one list the command line, scenario files
    /// and the FMU's `scheme` variable are made from.
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

    /// The integer code of the FMU's `scheme` variable: the order.
    pub fn code(self) -> i32 {
        self.order() as i32
    }

    /// The scheme of an FMU `scheme` code, if it is one.
    pub fn from_code(code: i32) -> Option<Scheme> {
        Self::ALL.into_iter().find(|s| s.code() == code)
    }

    /// What it is, in a few words.
    pub fn description(self) -> &'static str {
        match self {
            Scheme::BackwardEuler => "backward Euler, the paper's (order 1)",
            Scheme::Bdf2 => "BDF-2 (order 2)",
            Scheme::Bdf3 => "BDF-3 (order 3)",
            Scheme::Bdf4 => "BDF-4 (order 4)",
            Scheme::Bdf5 => "BDF-5 (order 5)",
        }
    }

    /// The choices as one line of help, e.g. for a command-line flag:
    /// "backward-euler (backward Euler, the paper's (order 1)), bdf2 (BDF-2 (order 2)), ...".
    pub fn help() -> String {
        Self::ALL
            .iter()
            .map(|s| format!("{} ({})", s.name(), s.description()))
            .collect::<Vec<_>>()
            .join(", ")
    }

    /// The names, "backward-euler (also bdf1), bdf2, bdf3, bdf4 or bdf5".
    pub fn names() -> String {
        let names: Vec<String> = Self::ALL
            .iter()
            .map(|s| {
                if *s == Scheme::BackwardEuler {
                    format!("{s} (also bdf1)")
                } else {
                    s.to_string()
                }
            })
            .collect();
        let (last, rest) = names
            .split_last()
            .map_or((String::new(), &[][..]), |(l, r)| (l.clone(), r));
        format!("{} or {last}", rest.join(", "))
    }

    /// The choices by FMU code, e.g. "1 backward Euler, the paper's (order 1), 2 BDF-2 (order 2), ...".
    pub fn code_help() -> String {
        Self::ALL
            .iter()
            .map(|s| format!("{} {}", s.code(), s.description()))
            .collect::<Vec<_>>()
            .join(", ")
    }

    /// The scheme's formula with a full history.
    pub fn formula(self) -> Formula {
        bdf_formula(self.order())
    }
}

impl Method for Scheme {
    fn name(&self) -> &'static str {
        Scheme::name(*self)
    }

    fn order(&self) -> usize {
        Scheme::order(*self)
    }

    /// BDF-k, or BDF-`known` while fewer than `k` past values are known.
    fn formula(&self, known: usize) -> Formula {
        bdf_formula(Scheme::order(*self).min(known))
    }
}

/// BDF-k coefficients (table in the module docs): `c = 1/beta` and alpha.
fn bdf_formula(k: usize) -> Formula {
    match k {
        1 => Formula::new(1.0, &[-1.0]),
        2 => Formula::new(1.0 / (2.0 / 3.0), &[-4.0 / 3.0, 1.0 / 3.0]),
        3 => Formula::new(1.0 / (6.0 / 11.0), &[-18.0 / 11.0, 9.0 / 11.0, -2.0 / 11.0]),
        4 => Formula::new(
            1.0 / (12.0 / 25.0),
            &[-48.0 / 25.0, 36.0 / 25.0, -16.0 / 25.0, 3.0 / 25.0],
        ),
        _ => Formula::new(
            1.0 / (60.0 / 137.0),
            &[
                -300.0 / 137.0,
                300.0 / 137.0,
                -200.0 / 137.0,
                75.0 / 137.0,
                -12.0 / 137.0,
            ],
        ),
    }
}

impl fmt::Display for Scheme {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// The other name of backward Euler: BDF-1.
const BACKWARD_EULER_ALIAS: &str = "bdf1";

/// A scheme name that is none of `backward-euler`, `bdf1` .. `bdf5`.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("unknown scheme `{0}`; expected {names}", names = Scheme::names())]
pub struct UnknownScheme(pub String);

impl FromStr for Scheme {
    type Err = UnknownScheme;
    /// `backward-euler` (or `bdf1`), `bdf2` .. `bdf5`.
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        if s == BACKWARD_EULER_ALIAS {
            return Ok(Scheme::BackwardEuler);
        }
        Self::ALL
            .into_iter()
            .find(|scheme| scheme.name() == s)
            .ok_or_else(|| UnknownScheme(s.to_string()))
    }
}

/// A method at work: past values `y_n, y_{n-1}, ...` and rates
/// `y'_n, y'_{n-1}, ...` of the discretised unknowns, newest first, the
/// predictor and the start-up rule; fixed size, so pushing a step does not
/// allocate.
#[derive(Debug, Clone, Copy)]
pub struct History<const K: usize, S: Method = Scheme> {
    method: S,
    /// Past values and rates, a ring: the newest at `newest`, each older
    /// one after it, wrapping around.
    values: [SVector<f64, K>; MAX_STEPS],
    rates: [SVector<f64, K>; MAX_STEPS],
    /// What rounding to `f64` took from each past value and rate, where a
    /// problem keeps it ([`History::push_extended`]; zero otherwise).
    values_lo: [SVector<f64, K>; MAX_STEPS],
    rates_lo: [SVector<f64, K>; MAX_STEPS],
    newest: usize,
    /// How many entries are valid (oldest ones may be missing early on).
    known: usize,
}

/// The affine maps a scheme imposes at one step, per component `i`:
/// `v_i = (c/dt) (y_i - ybar_i)`, `a_i = (c/dt) (v_i - vbar_i)`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StepFormula<const K: usize> {
    /// `c/dt`: the slope of `v` in `y` (and of `a` in `v`).
    pub rate: f64,
    /// The time step.
    pub dt: f64,
    /// `ybar` from the past values.
    pub value_offset: SVector<f64, K>,
    /// `vbar` from the past rates.
    pub rate_offset: SVector<f64, K>,
    /// The same beyond double precision, for a problem that solves for
    /// corrections to the prediction ([`Predictor::Correction`](crate::problem::Predictor::Correction)).
    pub extended: Option<Extended<K>>,
}

/// A step's affine maps, its prediction and its time in double-double
/// ([`History::extended_formula`]): a problem that holds its discretised
/// coordinates as the prediction plus a correction, both to that
/// precision, takes `v` and `a` from them free of the noise that rounding
/// the coordinates to `f64` would leave in their second differences.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Extended<const K: usize> {
    /// `ybar`.
    pub value_offset: SVector<DoubleDouble, K>,
    /// `vbar`.
    pub rate_offset: SVector<DoubleDouble, K>,
    /// The predictor's extrapolation of `y_{n+1}`.
    pub prediction: SVector<DoubleDouble, K>,
    /// The step's time `t0 + (n + 1) dt`, where the step's drive is the
    /// problem's own (its path's target there, which the problem may then
    /// take to this precision); `None` for a drive given from outside.
    pub target_time: Option<DoubleDouble>,
}

/// The slopes of one step's affine maps in the new value `y`, as the
/// iteration matrices use them (rows scaled by `dt^2`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Slopes {
    /// `dv/dy = c/dt`.
    pub velocity: f64,
    /// `d(dt^2 v)/dy = c dt`.
    pub velocity_dt2: f64,
    /// `d(dt^2 a)/dy = c^2`.
    pub acceleration_dt2: f64,
}

impl<const K: usize> StepFormula<K> {
    /// `v_i` and `dt^2 a_i` for a new value `y` of component `i` (generic in
    /// the scalar, so that dual numbers pass through).
    pub fn kinematics<T>(&self, i: usize, y: T) -> (T, T)
    where
        T: Copy + std::ops::Sub<f64, Output = T> + std::ops::Mul<f64, Output = T>,
    {
        let dt = self.dt;
        let v = (y - self.value_offset[i]) * self.rate;
        // dt^2 a = dt^2 rate (v - vbar) = (c dt) (v - vbar) ... written so
        // that backward Euler reads y - y_n - dt v_n exactly
        let c_dt = self.rate * dt;
        let accel_dt2 = (y - self.value_offset[i]) * (c_dt * c_dt) - self.rate_offset[i] * (c_dt * dt);
        (v, accel_dt2)
    }

    /// No step prepared yet: every map NaN (a problem's state between its
    /// construction and the first [`Problem::prepare`](crate::problem::Problem::prepare)).
    pub fn unprepared() -> Self {
        Self {
            rate: f64::NAN,
            dt: f64::NAN,
            value_offset: SVector::zeros(),
            rate_offset: SVector::zeros(),
            extended: None,
        }
    }

    /// The slopes of `v`, `dt^2 v` and `dt^2 a` in `y` (the same products
    /// as [`kinematics`](Self::kinematics)).
    pub fn slopes(&self) -> Slopes {
        let c_dt = self.rate * self.dt;
        Slopes {
            velocity: self.rate,
            velocity_dt2: c_dt * self.dt,
            acceleration_dt2: c_dt * c_dt,
        }
    }
}

impl<const K: usize, S: Method> History<K, S> {
    /// The start-up rule, for the discretised unknowns `y0` (`q` or `mu`)
    /// with rates `v0`:
    ///
    /// - At rest (`at_rest`, see [`init::at_rest`](crate::init::at_rest)):
    ///   the crane rested before `t0`, so every past value is `y0` and every
    ///   past rate zero. This history is exact, and a BDF-k run from it
    ///   keeps order k from the first step.
    /// - Otherwise only the present is known, and the method starts itself:
    ///   the j-th step uses the formula for j known values
    ///   ([`Method::formula`]; BDF-j) until the history holds k steps (an
    ///   order ramp). The lower-order first steps leave an error in the
    ///   inputs near `t0` (backward Euler's first step from a moving start
    ///   is off by O(1) in the accelerations, so in `u`); for a crane whose
    ///   coordinates the servo and holonomic constraints fix (all built-in
    ///   models) it is gone after 2k steps, and order k holds at every time
    ///   from there on (measured in the tests on a start in the middle of a
    ///   move).
    pub fn new(method: S, y0: SVector<f64, K>, v0: SVector<f64, K>, at_rest: bool) -> Self {
        if at_rest {
            Self::at_rest(method, y0)
        } else {
            Self::start(method, y0, v0)
        }
    }

    /// A history at rest: every past value `y0`, every past rate zero.
    pub fn at_rest(method: S, y0: SVector<f64, K>) -> Self {
        Self {
            method,
            values: [y0; MAX_STEPS],
            rates: [SVector::zeros(); MAX_STEPS],
            values_lo: [SVector::zeros(); MAX_STEPS],
            rates_lo: [SVector::zeros(); MAX_STEPS],
            newest: 0,
            known: MAX_STEPS,
        }
    }

    /// A history that knows only the start `(y0, v0)`.
    pub fn start(method: S, y0: SVector<f64, K>, v0: SVector<f64, K>) -> Self {
        Self {
            method,
            values: [y0; MAX_STEPS],
            rates: [v0; MAX_STEPS],
            values_lo: [SVector::zeros(); MAX_STEPS],
            rates_lo: [SVector::zeros(); MAX_STEPS],
            newest: 0,
            known: 1,
        }
    }

    /// A history from past values and rates, newest (`t0`) first: as many
    /// as both give, up to [`MAX_STEPS`]; `None` without at least one of
    /// each.
    pub fn from_past(method: S, values: &[SVector<f64, K>], rates: &[SVector<f64, K>]) -> Option<Self> {
        let known = values.len().min(rates.len()).min(MAX_STEPS);
        let (&first_value, &first_rate) = (values.first()?, rates.first()?);
        let mut history = Self::start(method, first_value, first_rate);
        history.values[..known].copy_from_slice(&values[..known]);
        history.rates[..known].copy_from_slice(&rates[..known]);
        history.known = known;
        Some(history)
    }

    /// The method.
    pub fn method(&self) -> &S {
        &self.method
    }

    /// Record an accepted step: `y_{n+1}, y'_{n+1}` become the newest entry.
    pub fn push(&mut self, y: SVector<f64, K>, v: SVector<f64, K>) {
        self.push_extended(y, SVector::zeros(), v, SVector::zeros());
    }

    /// Record an accepted step to double-double precision: `y + y_lo` and
    /// `v + v_lo`.
    pub fn push_extended(
        &mut self,
        y: SVector<f64, K>,
        y_lo: SVector<f64, K>,
        v: SVector<f64, K>,
        v_lo: SVector<f64, K>,
    ) {
        self.newest = self.newest.checked_sub(1).unwrap_or(MAX_STEPS - 1);
        self.values[self.newest] = y;
        self.rates[self.newest] = v;
        self.values_lo[self.newest] = y_lo;
        self.rates_lo[self.newest] = v_lo;
        self.known = (self.known + 1).min(MAX_STEPS);
    }

    /// The past values and rates in double-double, newest first.
    fn past_extended(&self) -> impl Iterator<Item = (SVector<DoubleDouble, K>, SVector<DoubleDouble, K>)> + '_ {
        let join =
            |hi: &SVector<f64, K>, lo: &SVector<f64, K>| SVector::from_fn(|i, _| DoubleDouble::new(hi[i], lo[i]));
        let values = newest_first(&self.values, self.newest).zip(newest_first(&self.values_lo, self.newest));
        let rates = newest_first(&self.rates, self.newest).zip(newest_first(&self.rates_lo, self.newest));
        values
            .zip(rates)
            .map(move |((y, y_lo), (v, v_lo))| (join(y, y_lo), join(v, v_lo)))
    }

    /// The past values and rates, newest first.
    fn past(&self) -> impl Iterator<Item = (&SVector<f64, K>, &SVector<f64, K>)> {
        let (values, rates) = (
            newest_first(&self.values, self.newest),
            newest_first(&self.rates, self.newest),
        );
        values.zip(rates)
    }

    /// The newest value `y_n`.
    pub fn value(&self) -> &SVector<f64, K> {
        &self.values[self.newest]
    }

    /// The newest rate `y'_n`.
    pub fn rate(&self) -> &SVector<f64, K> {
        &self.rates[self.newest]
    }

    /// Order of the next step: the method's, or lower while the history is
    /// shorter than the method needs.
    pub fn order(&self) -> usize {
        self.method.order().min(self.known)
    }

    /// The method's affine maps for the step after the newest entry, with
    /// time step `dt`.
    pub fn formula(&self, dt: f64) -> StepFormula<K> {
        let formula = self.method.formula(self.known);
        let mut value_offset = SVector::zeros();
        let mut rate_offset = SVector::zeros();
        for (j, (value, rate)) in self.past().take(formula.steps).enumerate() {
            value_offset -= value * formula.alpha[j];
            rate_offset -= rate * formula.alpha[j];
        }
        StepFormula {
            rate: formula.c / dt,
            dt,
            value_offset,
            rate_offset,
            extended: None,
        }
    }

    /// [`formula`](Self::formula) with its [`Extended`] part: the offsets
    /// and the prediction ([`predict`](Self::predict) with `extra` points)
    /// summed in double-double from the past held to that precision, for
    /// the step at `target_time` ([`Extended::target_time`]).
    pub fn extended_formula(&self, dt: f64, extra: usize, target_time: Option<DoubleDouble>) -> StepFormula<K> {
        let mut step = self.formula(dt);
        let formula = self.method.formula(self.known);
        // ybar = -sum_j alpha_j y_{n-j} summed by parts, y_n + sum_{j >= 1}
        // B_j (y_{n-j+1} - y_{n-j}) with the tails B_j = sum_{i >= j}
        // alpha_i: the coefficients' sum -1 is then exact, not that of
        // their roundings (off by ~1e-16, which would bias v by 1e-16 y/dt
        // and a by 1e-16 v/dt)
        let mut tails = [0.0; MAX_STEPS];
        for j in (1..formula.steps).rev() {
            tails[j] = formula.alpha[j] + tails.get(j + 1).copied().unwrap_or(0.0);
        }
        let mut past = self.past_extended().take(formula.steps);
        let (mut value_offset, mut rate_offset) = past.next().unwrap_or((SVector::zeros(), SVector::zeros()));
        let (mut newer_value, mut newer_rate) = (value_offset, rate_offset);
        for (j, (value, rate)) in past.enumerate().map(|(j, past)| (j + 1, past)) {
            for i in 0..K {
                value_offset[i] += (newer_value[i] - value[i]) * tails[j];
                rate_offset[i] += (newer_rate[i] - rate[i]) * tails[j];
            }
            (newer_value, newer_rate) = (value, rate);
        }
        let mut prediction = SVector::<DoubleDouble, K>::zeros();
        let mut past = self.past_extended();
        if self.known < 2 {
            if let Some((value, rate)) = past.next() {
                prediction = SVector::from_fn(|i, _| value[i] + rate[i] * dt);
            }
        } else {
            let weights = extrapolation_weights(self.prediction_points(extra));
            for ((value, _), weight) in past.zip(&weights[..self.prediction_points(extra)]) {
                for i in 0..K {
                    prediction[i] += value[i] * *weight;
                }
            }
        }
        step.extended = Some(Extended {
            value_offset,
            rate_offset,
            prediction,
            target_time,
        });
        step
    }

    /// The points the predictor extrapolates through with `extra` more.
    fn prediction_points(&self, extra: usize) -> usize {
        (self.method.predictor_points(self.known) + extra)
            .min(self.known)
            .min(MAX_STEPS)
    }

    /// Predictor for the next value: the polynomial through the last
    /// [`Method::predictor_points`] values and `extra` more (at most the
    /// known ones and [`MAX_STEPS`]), extrapolated one step (or
    /// `y_n + dt y'_n` while only the start is known). One extra point
    /// leaves an error `O(dt^(k + 2))` instead of `O(dt^(k + 1))`.
    pub fn predict(&self, dt: f64, extra: usize) -> SVector<f64, K> {
        if self.known < 2 {
            return self.value() + self.rate() * dt;
        }
        let points = self.prediction_points(extra);
        let weights = extrapolation_weights(points);
        let mut prediction = SVector::zeros();
        for ((value, _), weight) in self.past().zip(&weights[..points]) {
            prediction += value * *weight;
        }
        prediction
    }
}

/// Equal histories have the same method and the same known past, newest
/// first, wherever their rings start.
impl<const K: usize, S: Method + PartialEq> PartialEq for History<K, S> {
    fn eq(&self, other: &Self) -> bool {
        self.method == other.method
            && self.known == other.known
            && self.past().take(self.known).eq(other.past().take(other.known))
    }
}

/// The entries of a ring whose newest is at `newest`, newest first.
pub(crate) fn newest_first<T>(ring: &[T], newest: usize) -> impl Iterator<Item = &T> {
    let (wrapped, from_newest) = ring.split_at(newest.min(ring.len()));
    from_newest.iter().chain(wrapped)
}

/// The most past values an extrapolation goes through
/// ([`Predictor::Extrapolation`](crate::problem::Predictor::Extrapolation)).
pub const MAX_EXTRAPOLATION: usize = 8;

/// The weights of the extrapolation one step ahead through `points`
/// (`1..=MAX_EXTRAPOLATION`) equally spaced values, newest first:
/// `y_{n+1} = sum_j w_j y_{n-j}`, `w_j = (-1)^j C(points, j + 1)` (the
/// polynomial of degree `points - 1`; one point: the last value).
pub(crate) fn extrapolation_weights(points: usize) -> [f64; MAX_EXTRAPOLATION] {
    EXTRAPOLATION_WEIGHTS[points.min(MAX_EXTRAPOLATION)]
}

/// [`extrapolation_weights`] of `0 ..= MAX_EXTRAPOLATION` points, made at
/// compile time (a predictor asks for them at every step).
const EXTRAPOLATION_WEIGHTS: [[f64; MAX_EXTRAPOLATION]; MAX_EXTRAPOLATION + 1] = {
    let mut table = [[0.0; MAX_EXTRAPOLATION]; MAX_EXTRAPOLATION + 1];
    let mut points = 0;
    while points <= MAX_EXTRAPOLATION {
        let mut binomial = 1.0;
        let mut j = 0;
        while j < points {
            binomial = binomial * (points - j) as f64 / (j + 1) as f64;
            table[points][j] = if j % 2 == 0 { binomial } else { -binomial };
            j += 1;
        }
        points += 1;
    }
    table
};

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::vector;

    /// A history needs a past: none from empty slices, and no panic.
    #[test]
    fn a_history_without_a_past_is_none() {
        let empty: [SVector<f64, 1>; 0] = [];
        assert!(History::from_past(Scheme::Bdf3, &empty, &empty).is_none());
        assert!(History::from_past(Scheme::Bdf3, &[SVector::<f64, 1>::zeros()], &empty).is_none());
        let one = [SVector::<f64, 1>::zeros()];
        assert!(History::from_past(Scheme::Bdf3, &one, &one).is_some());
    }

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
                let history = History::<1>::from_past(scheme, &past, &past).expect("a past");
                assert_eq!(history.order(), k);
                let step = history.formula(dt);
                let (v, _) = step.kinematics(0, y(t_new));
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
        let history = History::<1>::start(Scheme::BackwardEuler, vector![2.0], vector![3.0]);
        let step = history.formula(0.1);
        let (v, a_dt2) = step.kinematics(0, 2.5);
        assert!((v - (2.5 - 2.0) / 0.1).abs() < 1e-12);
        assert!((a_dt2 - (2.5 - 2.0 - 0.1 * 3.0)).abs() < 1e-12);
    }

    /// The slopes are the derivatives of the affine maps (exact: the maps
    /// are affine, so a difference over any step is the slope to round-off).
    #[test]
    fn slopes_are_the_derivatives_of_the_maps() {
        for scheme in Scheme::ALL {
            let past: Vec<_> = (0..MAX_STEPS).map(|j| vector![1.0 + 0.3 * j as f64]).collect();
            let rates: Vec<_> = (0..MAX_STEPS).map(|j| vector![0.5 - 0.2 * j as f64]).collect();
            let dt = 0.05;
            let step = History::<1>::from_past(scheme, &past, &rates)
                .expect("a past")
                .formula(dt);
            let slopes = step.slopes();
            let (v0, a0) = step.kinematics(0, 2.0);
            let (v1, a1) = step.kinematics(0, 3.0);
            assert!((v1 - v0 - slopes.velocity).abs() < 1e-9 * slopes.velocity, "{scheme}");
            assert!(
                (a1 - a0 - slopes.acceleration_dt2).abs() < 1e-12 * slopes.acceleration_dt2,
                "{scheme}"
            );
            assert!(((v1 - v0) * dt * dt - slopes.velocity_dt2).abs() < 1e-12, "{scheme}");
        }
    }

    /// The predictor of order k extrapolates polynomials of degree k exactly
    /// (degree 4 for BDF-5: the history holds five values).
    #[test]
    fn predictor_extrapolates_polynomials() {
        for scheme in Scheme::ALL {
            let k = scheme.order().min(MAX_STEPS - 1);
            let y = |t: f64| (0..=k).map(|i| t.powi(i as i32) / (i + 1) as f64).sum::<f64>();
            let past: Vec<_> = (0..MAX_STEPS).map(|j| vector![y(-(j as f64))]).collect();
            let history = History::<1>::from_past(scheme, &past, &past).expect("a past");
            let p = history.predict(1.0, 0)[0];
            assert!((p - y(1.0)).abs() < 1e-9, "{scheme}: {p} vs {}", y(1.0));
            // one extra point: exact for one degree more (up to the five values held)
            let k = (scheme.order() + 1).min(MAX_STEPS - 1);
            let y = |t: f64| (0..=k).map(|i| t.powi(i as i32) / (i + 1) as f64).sum::<f64>();
            let past: Vec<_> = (0..MAX_STEPS).map(|j| vector![y(-(j as f64))]).collect();
            let history = History::<1>::from_past(scheme, &past, &past).expect("a past");
            let p = history.predict(1.0, 1)[0];
            assert!((p - y(1.0)).abs() < 1e-9, "{scheme} + 1: {p} vs {}", y(1.0));
        }
    }

    /// The weights are the ones written out: last value, linear,
    /// quadratic, cubic.
    /// Histories of the same past are equal wherever their rings start;
    /// another past is not.
    #[test]
    fn histories_compare_by_their_past() {
        let values: Vec<SVector<f64, 1>> = (0..7).map(|j| vector![j as f64]).collect();
        let mut pushed = History::start(Scheme::Bdf3, values[6], values[6]);
        for value in values[..6].iter().rev() {
            pushed.push(*value, *value);
        }
        let given = History::from_past(Scheme::Bdf3, &values[..5], &values[..5]).unwrap();
        assert_eq!(pushed, given);
        pushed.push(vector![-1.0], vector![-1.0]);
        assert_ne!(pushed, given);
    }

    #[test]
    fn extrapolation_weights_are_the_binomial_ones() {
        assert_eq!(extrapolation_weights(1)[..5], [1.0, 0.0, 0.0, 0.0, 0.0]);
        assert_eq!(extrapolation_weights(2)[..5], [2.0, -1.0, 0.0, 0.0, 0.0]);
        assert_eq!(extrapolation_weights(3)[..5], [3.0, -3.0, 1.0, 0.0, 0.0]);
        assert_eq!(extrapolation_weights(4)[..5], [4.0, -6.0, 4.0, -1.0, 0.0]);
        assert_eq!(
            extrapolation_weights(8),
            [8.0, -28.0, 56.0, -70.0, 56.0, -28.0, 8.0, -1.0]
        );
    }

    #[test]
    fn names_and_codes_round_trip() {
        for scheme in Scheme::ALL {
            assert_eq!(scheme.name().parse::<Scheme>(), Ok(scheme));
            assert_eq!(Scheme::bdf(scheme.order()), Some(scheme));
            assert_eq!(Scheme::from_code(scheme.code()), Some(scheme));
            assert!(Scheme::help().contains(scheme.name()));
            assert!(Scheme::code_help().contains(&format!("{} {}", scheme.code(), scheme.description())));
        }
        assert_eq!("bdf1".parse::<Scheme>(), Ok(Scheme::BackwardEuler));
        assert!("bdf6".parse::<Scheme>().is_err());
        assert_eq!(Scheme::bdf(0), None);
        assert_eq!(Scheme::bdf(6), None);
        assert_eq!(Scheme::from_code(0), None);
        assert_eq!(Scheme::from_code(6), None);
    }
}
