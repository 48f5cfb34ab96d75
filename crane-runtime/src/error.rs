//! Typed errors of the runtime: every failure a user can cause or meet.

/// Everything that can go wrong setting up or integrating a crane's inverse dynamics.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum Error {
    /// Newton's method did not meet its tolerance within the iteration limit.
    #[error(
        "Newton's method did not converge at t = {} s after {iterations} iterations \
         (residual {residual:.3e}); try a smaller dt or check that the path is reachable",
        Seconds::of(.t)
    )]
    NewtonNotConverged {
        /// Time of the step that failed.
        t: f64,
        /// Iterations taken.
        iterations: usize,
        /// Infinity norm of the (dt^2-scaled) residual at the last iterate.
        residual: f64,
    },
    /// The iteration matrix was singular and the minimum-norm fallback failed too.
    #[error("singular iteration matrix at t = {} s (LU pivot ratio {pivot_ratio:.1e})", Seconds::of(.t))]
    SingularIterationMatrix {
        /// Time of the step that failed.
        t: f64,
        /// Smallest-to-largest LU pivot ratio.
        pivot_ratio: f64,
    },
    /// A quantity became NaN or infinite during a step.
    #[error("non-finite {quantity} at t = {} s", Seconds::of(.t))]
    NonFinite {
        /// What became non-finite.
        quantity: &'static str,
        /// Time of the step.
        t: f64,
    },
    /// A coordinate of the start is so large that the constraints (squares
    /// of lengths) cannot be evaluated in f64.
    #[error("the start's coordinate `{coordinate}` = {value:e} is beyond 1e100: its square would overflow")]
    StartOutOfRange {
        /// The coordinate's name.
        coordinate: &'static str,
        /// Its value.
        value: f64,
    },
    /// The load path takes a coordinate so far that the constraints (squares
    /// of lengths) cannot be evaluated in f64.
    #[error(
        "the load path's `{coordinate}` = {value:e} at t = {} s is beyond 1e100: its square would overflow; check the \
         path's `start` and `end`",
        Seconds::of(.t)
    )]
    PathOutOfRange {
        /// The load coordinate's name.
        coordinate: &'static str,
        /// Its value on the path.
        value: f64,
        /// When.
        t: f64,
    },
    /// The time step is not a finite positive number.
    #[error("invalid time step dt = {dt:?}: it must be finite and at least 1e-6 s")]
    InvalidTimeStep {
        /// The rejected value.
        dt: f64,
    },
    /// The end time of a run is not a number.
    #[error("invalid end time tf = {}: it must be a finite number of seconds", Seconds(*.tf))]
    InvalidEndTime {
        /// The rejected value.
        tf: f64,
    },
    /// Newton tolerances that cannot be met or make no sense.
    #[error("invalid Newton options: {0}")]
    InvalidNewtonOptions(&'static str),
    /// The end time is not after the start time.
    #[error("invalid time span: tf = {} must be finite and greater than t0 = {}", Seconds(*.tf), Seconds(*.t0))]
    InvalidTimeSpan {
        /// Start time.
        t0: f64,
        /// End time.
        tf: f64,
    },
    /// The run's times are too large for double precision to tell its
    /// steps apart ([`TIME_RESOLUTION`](crate::options::TIME_RESOLUTION)).
    #[error(
        "at t = {} s double precision resolves times only to {resolution:.3e} s, more than 1e-6 of dt = {} s: the \
         step times cannot be told apart; put the time origin near the run (t0 = 0)",
        Seconds::of(.t),
        Seconds(*.dt)
    )]
    TimesUnresolved {
        /// The largest time of the run, s.
        t: f64,
        /// The spacing of doubles there, s.
        resolution: f64,
        /// The time step, s.
        dt: f64,
    },
    /// The time span is not a whole number of steps.
    #[error("tf - t0 = {} s is not a whole number of steps of dt = {} s", Seconds(*.span), Seconds(*.dt))]
    StepsDoNotFit {
        /// `tf - t0`.
        span: f64,
        /// The time step.
        dt: f64,
    },
    /// A model parameter is NaN or infinite.
    #[error("parameter `{name}` = {value} is not finite")]
    NonFiniteParameter {
        /// Parameter name.
        name: &'static str,
        /// Its value.
        value: f64,
    },
    /// A model parameter beyond [`PARAMETER_RANGE`](crate::model::PARAMETER_RANGE).
    #[error(
        "parameter `{name}` = {value:e} is beyond what the equations can be evaluated with: |{name}| must lie between \
         1e-150 and 1e150{}, where products of a few parameters and coordinates stay finite in double precision",
        if *.may_be_zero { " (or be 0)" } else { "" }
    )]
    ParameterOutOfRange {
        /// Parameter name.
        name: &'static str,
        /// Its value.
        value: f64,
        /// Whether 0 is a value it may take (not declared `positive`).
        may_be_zero: bool,
    },
    /// A user-given start violates an equation that a consistent start must satisfy.
    #[error("inconsistent start: {equation} is violated by {residual:.3e} (tolerance {tolerance:.1e})")]
    InconsistentStart {
        /// The violated equation, named as in the model, e.g. "constraint `hoist` (g = 0)".
        equation: String,
        /// Its residual.
        residual: f64,
        /// The tolerance it was checked against.
        tolerance: f64,
    },
    /// The static balance at the start is rank deficient: a family of equilibria.
    #[error(
        "the static equilibrium is not unique: the balance is singular (singular value ratio \
         {singular_value_ratio:.1e}) and {free} can move freely; give the start explicitly"
    )]
    NonUniqueEquilibrium {
        /// Smallest-to-largest singular value of the equilibrated balance Jacobian.
        singular_value_ratio: f64,
        /// The coordinates along the free direction, e.g. "L1, L0, z0".
        free: String,
    },
    /// The output Jacobian `D2 phi_x` of a minimal-coordinate map is singular
    /// or ill-conditioned: the split `mu = [mu1; mu2]` does not satisfy eq. (12) there.
    #[error(
        "D2 phi_x is singular or ill-conditioned at t = {} s (condition estimate {condition:.1e}): \
         the split of the minimal coordinates violates eq. (12) on this path",
        Seconds::of(.t)
    )]
    SingularOutputJacobian {
        /// Time of the step.
        t: f64,
        /// 1-norm condition estimate of `D2 phi_x` (infinite if exactly singular).
        condition: f64,
    },
    /// Solving `phi(mu0) = q0` for the minimal start did not converge.
    #[error(
        "no minimal coordinates mu0 with phi(mu0) = q0 found from the guess: residual {residual:.3e} after \
            {iterations} iterations"
    )]
    MinimalStartNotFound {
        /// Iterations taken.
        iterations: usize,
        /// Infinity norm of `phi(mu) - q0` at the last iterate.
        residual: f64,
    },
    /// A guess of the minimal coordinates of the wrong length.
    #[error("the guess of the minimal coordinates has {found} entries; the map has {expected}")]
    MinimalGuessSize {
        /// The map's number of minimal coordinates.
        expected: usize,
        /// The guess's.
        found: usize,
    },
    /// The static-equilibrium Newton iteration did not converge.
    #[error("no static equilibrium found from the guess: residual {residual:.3e} after {iterations} iterations")]
    EquilibriumNotFound {
        /// Iterations taken.
        iterations: usize,
        /// Infinity norm of the residual at the last iterate.
        residual: f64,
    },
    /// The mass matrix is not positive semi-definite with these parameters.
    #[error(
        "the mass matrix is not positive semi-definite (smallest eigenvalue {smallest_eigenvalue:.4e}, along \
         {coordinates}): a kinetic energy cannot be negative; negative parameters: {negative_parameters}"
    )]
    IndefiniteMassMatrix {
        /// The smallest eigenvalue of `M`.
        smallest_eigenvalue: f64,
        /// The coordinates of its eigenvector (components above 10 % of the largest).
        coordinates: String,
        /// The parameters with negative values, comma separated, or `none`.
        negative_parameters: String,
    },
    /// A start has a rope of zero or negative length (a mirror solution of
    /// the rope constraint).
    #[error(
        "the state at rest at t = {} s gives rope `{rope}` the length {length}: rope lengths must be positive (try \
         another guess)",
        Seconds::of(.t)
    )]
    NonPositiveRopeLength {
        /// The rope's tension name.
        rope: &'static str,
        /// Its length there.
        length: f64,
        /// The time of the state (a run's start, or the rest state at a
        /// move's end), s.
        t: f64,
    },
    /// A parameter declared `positive` is zero or negative.
    #[error("parameter `{name}` = {} must be positive (it is declared `positive`)", Number(*.value))]
    NonPositiveParameter {
        /// Parameter name.
        name: &'static str,
        /// Its value.
        value: f64,
    },
    /// A replay was asked of a run without states.
    #[error("the run to replay has no states")]
    NothingToReplay,
    /// The two steppers of a [`Handover`](crate::stepper::Handover) do not
    /// start from the same state with the same step.
    #[error("the steppers of a hand-over must share their {what}")]
    HandoverMismatch {
        /// What differs, with both values.
        what: String,
    },
    /// A step's solution is another root of the step's equations than the
    /// one its start lies on (a rope's length, or the tension of a rope that
    /// was clearly taut, changed sign): the step is too long for the
    /// prediction to stay on its branch.
    #[error(
        "the step to t = {} s left the branch of solutions it started on (a rope's length or the tension of a \
         taut rope changed sign within one step); a smaller dt follows it",
        Seconds::of(.t)
    )]
    BranchLeft {
        /// Time of the step.
        t: f64,
    },
    /// The replay's plant cannot start where the inverse run starts.
    #[error(
        "the plant cannot start where the inverse run starts: its {equation} is violated by {residual:.3e} there \
         (a plant parameter that changes the crane's geometry moves its start); replay on parameters that keep \
         the geometry (masses, inertias, radii), or plan with the plant's"
    )]
    ReplayStartInconsistent {
        /// The plant's violated constraint, named as in the model, e.g.
        /// "constraint `rope1` (g = 0, eq. 22d)".
        equation: String,
        /// Its residual at the start.
        residual: f64,
    },
    /// A rope of the replayed plant pushed, and the forward dynamics, whose
    /// ropes are rigid links, then failed.
    #[error(
        "rope {rope} of the plant goes slack at t = {} s in the replay (the computed torques do not keep it taut \
         on this plant), and the forward dynamics, whose ropes are rigid links, cannot follow a slack rope (their \
         steps fail from t = {} s)",
        Seconds::of(.t),
        Seconds::of(.failed_at)
    )]
    ReplayRopeSlack {
        /// The rope's tension name.
        rope: &'static str,
        /// When its tension first fell below zero, s.
        t: f64,
        /// When the forward steps failed, s.
        failed_at: f64,
    },
    /// A rope of the replayed plant reached zero length, and the forward
    /// dynamics then failed.
    #[error(
        "rope {rope} of the plant reaches zero length at t = {} s in the replay (the computed torques reel its \
         load into what holds it on this plant), and the forward dynamics cannot go on past it (their steps fail \
         from t = {} s)",
        Seconds::of(.t),
        Seconds::of(.failed_at)
    )]
    ReplayRopeLength {
        /// The rope's tension name.
        rope: &'static str,
        /// When its length first reached zero, s.
        t: f64,
        /// When the forward steps failed, s.
        failed_at: f64,
    },
    /// `step_to` was asked for a time that is not the next step's.
    #[error("a step must go to t_n + dt = {} s, not {} s", Seconds::of(.expected), Seconds::of(.t))]
    WrongStepTime {
        /// The requested time.
        t: f64,
        /// `t_n + dt`.
        expected: f64,
    },
    /// The run has more steps than can be held in memory.
    #[error("a run of {steps:.3e} steps cannot be held in memory ({}); use a larger dt or a shorter span", Bytes::of(.bytes))]
    TooManySteps {
        /// Steps the run would take.
        steps: f64,
        /// Bytes its results would take (infinite if not even countable).
        bytes: f64,
    },
    /// The dummy-derivative formulation of a crane that has no such system.
    #[error("the crane `{model}` has no dummy-derivative formulation: {reason}")]
    NoDummyDerivatives {
        /// The model's type name ([`ModelInfo::name`](crate::ModelInfo::name)).
        model: &'static str,
        /// Why.
        reason: crate::model::NoDummyDerivatives,
    },
    /// The computation was stopped from outside ([`crate::cancel`]).
    #[error("cancelled (a Ctrl-C or the host stopped the computation)")]
    Cancelled,
    /// No jets of the robot coordinates can be the states the load path
    /// leaves free ([`crate::state_selection`]).
    #[error("the states the load path leaves free on the crane `{model}` cannot be selected: {reason}")]
    StatesNotSelected {
        /// The model's type name.
        model: &'static str,
        /// Why.
        reason: String,
    },
    /// Internal dynamics with an eigenvalue on the imaginary axis (an
    /// undamped oscillation the path leaves free): no unique bounded
    /// solution on the whole time axis, so no stable inversion.
    #[error(
        "the internal dynamics at t = {} s have the eigenvalue {re:.4e} {sign} {:.4}i 1/s on the imaginary axis: an \
         undamped oscillation the path leaves free has no unique bounded solution, so there is no stable inversion; \
         the causal run (eqs. 22) stays bounded",
        Seconds::of(.t),
        .im.abs(),
        sign = if *.im < 0.0 { "-" } else { "+" }
    )]
    NoBoundedSolution {
        /// Time of the rest state, s.
        t: f64,
        /// The eigenvalue's real part, 1/s.
        re: f64,
        /// Its imaginary part, 1/s.
        im: f64,
    },
    /// Stable inversion's Newton iteration over the whole move did not
    /// converge.
    #[error(
        "stable inversion did not converge after {iterations} Newton iterations over the whole move (residual \
         {residual:.3e}) from the quasi-static motion: the move may be too fast or leave the crane's workspace; \
         try a longer move"
    )]
    StableInversionNotConverged {
        /// Iterations taken.
        iterations: usize,
        /// Largest residual (dt^2-scaled forces, constraints) at the last iterate.
        residual: f64,
    },
    /// The internal dynamics at a rest state that stable inversion needs
    /// could not be computed.
    #[error("stable inversion needs the internal dynamics at the rest states: {reason}")]
    InternalDynamicsUnknown {
        /// Why they could not be computed.
        reason: crate::internal::InternalDynamicsError,
    },
    /// The crane's inputs need more derivatives of the load path than the
    /// dummy-derivative problem carries.
    #[error(
        "the inputs need the load path's derivative of order {order}; the dummy-derivative problem carries up to {max}"
    )]
    PathOrderTooHigh {
        /// The crane's path order.
        order: usize,
        /// [`MAX_PATH_ORDER`](crate::dummy_derivative::MAX_PATH_ORDER).
        max: usize,
    },
}

/// A time printed as a person writes it: the shortest decimal that reads back
/// to within 1e-12 s (0.051, not 0.051000000000000004); beyond 1e15 s in
/// scientific notation (1e300, not 301 digits), below 1e-12 s in size as 0
/// (never -0.000).
///
/// ```
/// use crane_runtime::error::Seconds;
/// assert_eq!(Seconds(0.051000000000000004).to_string(), "0.051");
/// assert_eq!(Seconds(1e300).to_string(), "1e300");
/// assert_eq!(Seconds(-1e-14).to_string(), "0");
/// ```
pub struct Seconds(pub f64);

impl Seconds {
    /// For error messages: `Seconds::of(&t)`.
    pub fn of(t: &f64) -> Self {
        Seconds(*t)
    }
}

/// A number printed as short as it reads back exactly: `{}` between 1e-4
/// and 1e15 in size (`-4`, `0.01`), scientific notation beyond (`1e300`,
/// `-2.5e-7`, where `{}` prints hundreds of digits).
///
/// ```
/// use crane_runtime::error::Number;
/// assert_eq!(Number(-4.0).to_string(), "-4");
/// assert_eq!(Number(0.01).to_string(), "0.01");
/// assert_eq!(Number(-1e300).to_string(), "-1e300");
/// assert_eq!(Number(2.5e-7).to_string(), "2.5e-7");
/// ```
pub struct Number(pub f64);

/// A measured value printed with three decimals (`{:.3}`: `43.001`,
/// `0.000`), in scientific notation with three beyond 1e9 in size
/// (`2.619e143`, where `{:.3}` prints every digit of the integer part).
///
/// ```
/// use crane_runtime::error::Rounded;
/// assert_eq!(Rounded(43.0006).to_string(), "43.001");
/// assert_eq!(Rounded(-2.6186e143).to_string(), "-2.619e143");
/// assert_eq!(Rounded(f64::INFINITY).to_string(), "inf");
/// ```
pub struct Rounded(pub f64);

impl std::fmt::Display for Rounded {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let x = self.0;
        if x.is_finite() && x.abs() >= 1e9 {
            write!(f, "{x:.3e}")
        } else {
            write!(f, "{x:.3}")
        }
    }
}

impl std::fmt::Display for Number {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let x = self.0;
        if x == 0.0 || (x.is_finite() && (1e-4..1e15).contains(&x.abs())) {
            write!(f, "{x}")
        } else {
            write!(f, "{x:e}")
        }
    }
}

impl std::fmt::Display for Seconds {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let t = self.0;
        if !t.is_finite() || t.abs() >= 1e15 {
            return write!(f, "{t:e}");
        }
        if t.abs() < 1e-12 {
            return f.write_str("0");
        }
        for digits in 0..=12 {
            let text = format!("{t:.digits$}");
            if text
                .parse::<f64>()
                .is_ok_and(|back| (back - t).abs() <= 1e-12 * t.abs().max(1.0))
            {
                return f.write_str(&text);
            }
        }
        write!(f, "{t}")
    }
}

/// A byte count in binary units.
pub struct Bytes(pub f64);

impl Bytes {
    /// For error messages: `Bytes::of(&n)`.
    pub fn of(n: &f64) -> Self {
        Bytes(*n)
    }
}

impl std::fmt::Display for Bytes {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let b = self.0;
        if !b.is_finite() {
            return f.write_str("more than can be addressed");
        }
        let (value, unit) = [
            (1u64 << 40, "TiB"),
            (1 << 30, "GiB"),
            (1 << 20, "MiB"),
            (1 << 10, "KiB"),
        ]
        .into_iter()
        .find(|&(size, _)| b >= size as f64)
        .map_or((b, "B"), |(size, unit)| (b / size as f64, unit));
        write!(f, "{value:.1} {unit}")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn times_print_as_a_person_writes_them() {
        assert_eq!(Seconds(0.051000000000000004).to_string(), "0.051");
        assert_eq!(Seconds(1.5).to_string(), "1.5");
        assert_eq!(Seconds(2.0).to_string(), "2");
        assert_eq!(Seconds(1.0 / 3.0).to_string(), "0.333333333333");
        assert_eq!(Bytes(3.5 * 1024.0 * 1024.0).to_string(), "3.5 MiB");
    }
}
