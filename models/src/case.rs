//! [`Case`]: a built-in crane with parameters, on a load path, from a start:
//! what a run needs. The default manoeuvre is one case; a scenario file
//! makes another from the same crane.

use std::marker::PhantomData;

use crane_runtime::error::Number;
use crane_runtime::internal::internal_dynamics;
use crane_runtime::stable_inversion::{self, StableInversion, StableInversionOptions};
use crane_runtime::trajectory::{FromFn, TrajectoryError};
use crane_runtime::{CraneModel, Error, Options, Solution, State, Trajectory, dummy_derivative, init, redundant};

use crate::crane::Crane;
use crate::path::Path;

/// A crane `C` with its model's parameters on a path from a start `p0`,
/// run from the path's `t0` to `tf`.
///
/// ```
/// use crane_models::navy_planar::PaperCase;
/// use crane_runtime::Options;
///
/// let case = PaperCase::new(4.0).unwrap();         // sect. 5.1.3, tf = 4 s
/// let start = case.start().unwrap();               // eq. (46), checked
/// let run = case.simulate(&start, &Options::new(0.01, case.tf()).unwrap()).unwrap();
/// let e_u = case.relative_input_error(run.state_near(1.5).unwrap()).unwrap(); // eq. (48)
/// assert!(e_u < 2e-3);
/// ```
pub struct Case<C: Crane<N, M, A>, const N: usize, const M: usize, const A: usize> {
    /// The crane with its parameters.
    pub model: C::Model,
    /// The load path `gamma(t)`.
    pub path: Path<A>,
    /// The robot coordinates at `t0`.
    pub p0: Vec<f64>,
    /// End of the run, s.
    pub tf: f64,
    crane: PhantomData<fn() -> C>,
}

/// The most static equilibria [`Case::simulate_stable_inversion`] continues
/// along the path to find the rest state at its end.
pub const END_CONTINUATION_STEPS: usize = 64;

/// The points of the move after its start at which
/// [`Case::check_workspace`] holds the load at rest (and at the start).
pub const WORKSPACE_POINTS: usize = 64;

/// A load path that leaves the crane's workspace: with the load held at
/// rest at one of its points, a rope would be no longer than zero, or no
/// rope would pull.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum OutsideWorkspace {
    /// A rope would be no longer than zero.
    #[error(
        "the load path leaves {model}'s workspace: with the load held at rest at the path's point of t = {} s, \
         rope {rope} would be {length:.4} m long, and a rope's length must stay above zero; {KEEP_INSIDE}",
        Number(*.t)
    )]
    RopeLength {
        /// The crane's name.
        model: &'static str,
        /// The rope's tension name.
        rope: &'static str,
        /// Its length there, m: zero or below.
        length: f64,
        /// The time of the path's point, s.
        t: f64,
    },
    /// Every rope would have to push: nothing holds the load up.
    #[error(
        "{}: with the load held at rest at the path's point of t = {} s, every rope would have to push ({}), and a \
         rope only pulls: nothing holds the load up there; {}",
        if *.t == *.t0 { format!("{model} cannot hold the load at the path's start") }
        else { format!("the load path leaves {model}'s workspace") },
        Number(*.t),
        tensions.iter().map(|(rope, n)| format!("{rope} = {n:.4e} N")).collect::<Vec<_>>().join(", "),
        if *.t == *.t0 {
            "where the load hangs below its ropes, check the sign of gravity in the crane's forces (with z up, \
             `z: -m_l*g`)"
        } else {
            KEEP_INSIDE
        }
    )]
    NothingHolds {
        /// The crane's name.
        model: &'static str,
        /// Each rope's tension name and its tension there, N.
        tensions: Vec<(&'static str, f64)>,
        /// The time of the path's point, s.
        t: f64,
        /// The path's start, s.
        t0: f64,
    },
}

/// What an [`OutsideWorkspace`] error asks of the user.
const KEEP_INSIDE: &str =
    "keep the path's points where the crane can hold the load (a scenario's `end`, or its waypoints)";

impl<C: Crane<N, M, A>, const N: usize, const M: usize, const A: usize> Clone for Case<C, N, M, A> {
    fn clone(&self) -> Self {
        Self {
            model: self.model.clone(),
            path: self.path.clone(),
            p0: self.p0.clone(),
            tf: self.tf,
            crane: PhantomData,
        }
    }
}

impl<C: Crane<N, M, A>, const N: usize, const M: usize, const A: usize> Case<C, N, M, A> {
    /// `model` on `path` from `p0`, run to `tf`.
    pub fn from_parts(model: C::Model, path: Path<A>, p0: Vec<f64>, tf: f64) -> Self {
        Self {
            model,
            path,
            p0,
            tf,
            crane: PhantomData,
        }
    }

    /// The default manoeuvre with the motion ending at `t1` (and the run
    /// with it), e.g. `navy_planar::PaperCase::new(4.0)` for Figs. 5-8.
    pub fn new(t1: f64) -> Result<Self, TrajectoryError> {
        let maneuver = C::maneuver();
        let path = Path::new(crate::path::PathSpec { t1, ..maneuver.path })?;
        Ok(Self::from_parts(C::Model::default(), path, maneuver.p0, t1))
    }

    /// The default manoeuvre as it is.
    pub fn maneuver() -> Result<Self, TrajectoryError> {
        Self::new(C::maneuver().path.t1)
    }

    /// The crane.
    pub fn model(&self) -> &C::Model {
        &self.model
    }

    /// The load path.
    pub fn path(&self) -> &Path<A> {
        &self.path
    }

    /// Start of the run (and of the motion), s.
    pub fn t0(&self) -> f64 {
        self.path.spec().t0
    }

    /// End of the run, s.
    pub fn tf(&self) -> f64 {
        self.tf
    }

    /// The consistent start at `t0` from `p0` at rest, checked against the
    /// model's equations (eqs. 22d, 23 and the static balance).
    pub fn start(&self) -> Result<State<N, M, A>, Error> {
        init::check_start(&self.model, &self.path, self.t0(), &self.p0, None)
    }

    /// The start of a run: `p0` itself where it is consistent
    /// ([`start`](Self::start)). Where it is not and `p0` is the crane's
    /// default (a scenario that gives none keeps it: a guess made for the
    /// default parameters and path), the static equilibrium found from it
    /// (as [`consistent_start`](Self::consistent_start) finds it); where
    /// that fails too, the first error stands. A `p0` of the user's own is the start, never moved.
    pub fn run_start(&self) -> Result<State<N, M, A>, Error> {
        match self.start() {
            Err(e @ Error::InconsistentStart { .. }) if self.p0 == C::maneuver().p0 => {
                self.rest_start(self.t0()).map_err(|_| e)
            }
            other => other,
        }
    }

    /// The start at rest at `t0` found from `p0`: the static equilibrium;
    /// where that is a family (a slack rope leaves a massless pulley free,
    /// as at navy-planar's start, eq. 46), the member the analytical
    /// reference reaches at `t0`, if the crane has one.
    fn rest_start(&self, t0: f64) -> Result<State<N, M, A>, Error> {
        match init::static_equilibrium(&self.model, &self.path, t0, &self.p0) {
            Err(e @ Error::NonUniqueEquilibrium { .. }) => {
                let Some(reference) = self.reference(t0) else {
                    return Err(e);
                };
                let p = N - A;
                init::check_start(&self.model, &self.path, t0, &reference.q.as_slice()[..p], None)
            }
            other => other,
        }
    }

    /// The consistent start at `t0` from `p0` at rest: `p0` itself where
    /// it is consistent ([`start`](Self::start) at the path's start), else
    /// the static equilibrium found from it (parameters or a later start
    /// time moved it: the double pendulum's sling of 0.5 m instead of 2 m
    /// moves its hook 1.5 m).
    pub fn consistent_start(&self, t0: f64) -> Result<State<N, M, A>, Error> {
        init::check_start(&self.model, &self.path, t0, &self.p0, None).or_else(|e| match e {
            Error::StartOutOfRange { .. } => Err(e),
            _ => self.rest_start(t0),
        })
    }

    /// The analytical reference at `t`, if the crane has one.
    pub fn reference(&self, t: f64) -> Option<State<N, M, A>> {
        C::reference(&self.model, &self.path, t)
    }

    /// The relative error `|u - u_ref| / |u_ref|` of a state (eq. 48 at
    /// t = 1.5 s), if the crane has a reference.
    pub fn relative_input_error(&self, state: &State<N, M, A>) -> Option<f64> {
        let reference = self.reference(state.t)?;
        Some((state.u - reference.u).norm() / reference.u.norm())
    }

    /// The run in redundant coordinates (eqs. 22a-d) from `start`.
    pub fn simulate(&self, start: &State<N, M, A>, options: &Options) -> Result<Solution<N, M, A>, Error> {
        self.simulate_with_progress(start, options, &mut |_, _| {})
    }

    /// [`simulate`](Self::simulate), calling `progress(step, steps)` after every step.
    pub fn simulate_with_progress(
        &self,
        start: &State<N, M, A>,
        options: &Options,
        progress: &mut dyn FnMut(usize, usize),
    ) -> Result<Solution<N, M, A>, Error> {
        redundant::simulate_with_progress(&self.model, &self.path, start, options, progress)
    }

    /// The run in minimal coordinates (eqs. 24a-e) from `start`, if the
    /// crane's model declares a minimal map; `None` if not.
    pub fn simulate_minimal(
        &self,
        start: &State<N, M, A>,
        options: &Options,
    ) -> Option<Result<Solution<N, M, A>, Error>> {
        self.simulate_minimal_with_progress(start, options, &mut |_, _| {})
    }

    /// [`simulate_minimal`](Self::simulate_minimal) with progress.
    pub fn simulate_minimal_with_progress(
        &self,
        start: &State<N, M, A>,
        options: &Options,
        progress: &mut dyn FnMut(usize, usize),
    ) -> Option<Result<Solution<N, M, A>, Error>> {
        crate::crane::simulate_minimal::<C, N, M, A>(&self.model, &self.path, start, options, progress)
    }

    /// The run of the servo problem reduced by dummy derivatives from
    /// `start` ([`dummy_derivative::simulate_dummy_derivative`]): every
    /// crane its model declares without internal dynamics has it; for
    /// another the error says why not.
    pub fn simulate_dummy_derivative(
        &self,
        start: &State<N, M, A>,
        options: &Options,
        progress: &mut dyn FnMut(usize, usize),
    ) -> Result<Solution<N, M, A>, Error> {
        dummy_derivative::simulate_dummy_derivative(&self.model, &self.path, start, options, progress)
    }

    /// The bounded solution by stable inversion
    /// ([`crane_runtime::stable_inversion`]) from the rest
    /// state `start` at the path's start: the whole move, to the later of
    /// `options.tf()` and the path's end, with the pre- and post-actuation
    /// horizons of the internal dynamics at the two rest states, on nodes
    /// `options.dt()` apart.
    pub fn simulate_stable_inversion(
        &self,
        start: &State<N, M, A>,
        options: &Options,
    ) -> Result<StableInversion<N, M, A>, Error> {
        let t0 = self.t0();
        let tf = self.move_end(options.tf());
        let end = self.rest_at_end(start, tf, options.dt())?;
        let diagnosis = |state: &State<N, M, A>| {
            internal_dynamics(&self.model, state).map_err(|reason| Error::InternalDynamicsUnknown { reason })
        };
        let (t_pre, t_post) = stable_inversion::horizons(&diagnosis(start)?, &diagnosis(&end)?)?;
        let settings = StableInversionOptions {
            dt: options.dt(),
            t0,
            tf,
            t_pre,
            t_post,
        };
        stable_inversion::stable_inversion(&self.model, &self.path, start, &settings)
    }

    /// The static equilibrium at `tf`, continued from `start` along the
    /// path: each of at most [`END_CONTINUATION_STEPS`] equilibria (one per
    /// step of `dt` where fewer) guessed from the last one found. One solve from
    /// the start's coordinates lands on the mirror branch of a rope (length
    /// `-L`) when the move is longer than the rope (coupled-trolley 6 m
    /// across at 5 m depth); a step of the continuation moves the load a
    /// small part of the move, so each guess stays on its branch.
    fn rest_at_end(&self, start: &State<N, M, A>, tf: f64, dt: f64) -> Result<State<N, M, A>, Error> {
        let t0 = self.t0();
        let p = N - A;
        let steps = ((tf - t0) / dt).ceil().clamp(1.0, END_CONTINUATION_STEPS as f64) as usize;
        let mut rest = *start;
        // mid-move the path's acceleration may leave no balance: the guess
        // then stays the last one found, as in the march of Newton's start
        for k in 1..steps {
            let t = t0 + (tf - t0) * k as f64 / steps as f64;
            if let Ok(found) = init::static_equilibrium(&self.model, &self.path, t, &rest.q.as_slice()[..p]) {
                rest = found;
            }
        }
        init::static_equilibrium(&self.model, &self.path, tf, &rest.q.as_slice()[..p])
    }

    /// The path with its point at each time held: velocity and
    /// acceleration zero. Its static equilibrium holds the load at rest
    /// there; the equilibrium of the moving path would balance the move's
    /// acceleration too, which on a fast move swings a jib round.
    fn held(&self) -> impl Trajectory<A> + '_ {
        FromFn(|t: f64, k: usize| {
            if k == 0 {
                self.path.derivative(t, 0)
            } else {
                crane_runtime::nalgebra::SVector::<f64, A>::zeros()
            }
        })
    }

    /// The load held at rest at the path's point of `t`, found by a march
    /// of static equilibria from `t0` to `t` in `steps` steps, each guessed
    /// from the one before (from `p0` at the start): a step moves the load
    /// a small part of the way, so each guess stays on its branch of every
    /// rope. The first failure ends the march: a rope no longer than zero
    /// is [`Error::NonPositiveRopeLength`] at its time.
    pub fn rest_along(&self, t: f64, steps: usize) -> Result<State<N, M, A>, Error> {
        let held = self.held();
        let t0 = self.t0();
        let steps = steps.max(1);
        let at = |k: usize| t0 + (t - t0) * k as f64 / steps as f64;
        let mut rest = init::static_equilibrium(&self.model, &held, at(1), &self.p0)?;
        for k in 2..=steps {
            rest = init::static_equilibrium(&self.model, &held, at(k), &rest.q.as_slice()[..N - A])?;
        }
        Ok(rest)
    }

    /// Refuse a path that leaves the crane's workspace, before any run:
    /// with the load held at rest at its start and [`WORKSPACE_POINTS`]
    /// points of the move after it, every rope must be longer than zero and some
    /// rope must pull (with every rope pushing beyond round-off,
    /// [`below_floor`](crate::study::summary::below_floor) 0, nothing holds
    /// the load up against gravity: a load above a gantry's trolley). Each
    /// static equilibrium is guessed from the last one found (from `p0` at
    /// first); a point where none is found (a slack rope leaves a massless
    /// pulley free) is passed over. Every rope pushing at the start itself,
    /// where the crane's start holds the load, points at gravity declared
    /// upward, and the error says so.
    ///
    /// A point where only some ropes would push passes: one of several
    /// that goes slack leaves the load held by the others (navy-planar's
    /// rope N1 near its start), which the crane's equations with every rope
    /// taut do not tell. So does a move inside the workspace that is too
    /// fast for the crane. The run's audit measures every rope at every
    /// step.
    pub fn check_workspace(&self) -> Result<(), OutsideWorkspace> {
        let (t0, t1) = (self.t0(), self.path.spec().t1);
        let held = self.held();
        let ropes = <C::Model as CraneModel<N, M, A>>::INFO.ropes;
        let mut tensions = vec![0.0; ropes.len()];
        let mut last: Option<State<N, M, A>> = None;
        for k in 0..=WORKSPACE_POINTS {
            let t = t0 + (t1 - t0) * k as f64 / WORKSPACE_POINTS as f64;
            let guess = last.as_ref().map_or(&self.p0[..], |rest| &rest.q.as_slice()[..N - A]);
            let rest = match init::static_equilibrium(&self.model, &held, t, guess) {
                Ok(rest) => rest,
                Err(Error::NonPositiveRopeLength { rope, length, .. }) => {
                    return Err(OutsideWorkspace::RopeLength {
                        model: C::NAME,
                        rope,
                        length,
                        t,
                    });
                }
                Err(_) => continue,
            };
            self.model.rope_tensions(&rest.q, &rest.lambda, &mut tensions);
            let peak = tensions.iter().fold(0.0f64, |m, n| m.max(n.abs()));
            if !ropes.is_empty()
                && tensions
                    .iter()
                    .all(|&n| crate::study::summary::below_floor(n, 0.0, peak))
            {
                return Err(OutsideWorkspace::NothingHolds {
                    model: C::NAME,
                    tensions: ropes.iter().map(|r| r.tension).zip(tensions.iter().copied()).collect(),
                    t,
                    t0,
                });
            }
            last = Some(rest);
        }
        Ok(())
    }

    /// Where a stable inversion of a run to `tf` ends its move: the later of
    /// `tf` and the path's end (the bounded solution needs the whole move;
    /// its post-actuation follows).
    pub fn move_end(&self, tf: f64) -> f64 {
        tf.max(self.path.spec().t1)
    }

    /// Names of the derived outputs.
    pub fn derived_outputs(&self) -> &'static [&'static str] {
        C::derived_outputs()
    }

    /// The derived outputs of `state`.
    pub fn derived(&self, state: &State<N, M, A>) -> Vec<f64> {
        C::derived(&self.model, state)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::registry::{CATALOG, Visit, visit};

    /// Whether crane `C`'s default move passes [`Case::check_workspace`].
    struct DefaultInside;
    impl Visit for DefaultInside {
        type Output = Result<(), OutsideWorkspace>;
        fn visit<C: Crane<N, M, A>, const N: usize, const M: usize, const A: usize>(self) -> Self::Output {
            Case::<C, N, M, A>::maneuver()
                .expect("the default move")
                .check_workspace()
        }
    }

    /// Every built-in's default move stays inside its workspace, and so
    /// does navy-planar's moved in 2 s (too fast: a rope swings through
    /// zero length in the run, but the path's points are the same); its
    /// move to `[-3, 5]`, above the boom tip, leaves it: the hoist rope N2
    /// would be shorter than zero with the load held at rest on the way;
    /// gantry-3d's to a point above its trolley leaves it too.
    #[test]
    fn a_path_outside_the_workspace_is_refused_and_the_default_moves_are_not() {
        for entry in CATALOG {
            assert_eq!(visit(entry.name, DefaultInside), Some(Ok(())), "{}", entry.name);
        }
        type Navy = Case<crate::navy_planar::Description, 7, 3, 2>;
        assert_eq!(Navy::new(2.0).unwrap().check_workspace(), Ok(()));
        let mut above = Navy::maneuver().unwrap();
        let spec = crate::path::PathSpec {
            end: crane_runtime::nalgebra::vector![-3.0, 5.0],
            ..above.path.spec().clone()
        };
        above.path = Path::new(spec).unwrap();
        let outside = above.check_workspace().unwrap_err();
        let OutsideWorkspace::RopeLength { model, rope, length, t } = outside else {
            panic!("{outside:?}");
        };
        assert_eq!((model, rope), ("navy-planar", "N2"));
        assert!(length < 0.0 && t > 0.0 && t <= 4.0, "{outside:?}");
        // the march's own grid: one of its points, not a time between
        let k = t / 4.0 * WORKSPACE_POINTS as f64;
        assert!((k - k.round()).abs() < 1e-9, "{outside:?}");

        // gantry-3d's load lifted to 1 m above its trolley (at height 0):
        // held there the rope would push with at most the load's weight
        // (or be no longer than zero), so nothing holds the load up
        type Gantry = Case<crate::gantry_3d::Description, 6, 1, 3>;
        let mut lifted = Gantry::maneuver().unwrap();
        let spec = crate::path::PathSpec {
            end: crane_runtime::nalgebra::vector![6.0, 3.0, 1.0],
            ..lifted.path.spec().clone()
        };
        lifted.path = Path::new(spec).unwrap();
        let outside = lifted.check_workspace().unwrap_err();
        let message = outside.to_string();
        match outside {
            OutsideWorkspace::NothingHolds { tensions, .. } => {
                let weight = lifted.model.m_l * lifted.model.g;
                assert!(tensions.len() == 1 && tensions[0].1 < 0.0, "{tensions:?}");
                assert!(-tensions[0].1 <= weight * (1.0 + 1e-9), "{tensions:?}");
                assert!(message.contains("every rope would have to push (N = -"), "{message}");
            }
            OutsideWorkspace::RopeLength { rope, length, .. } => assert!(rope == "N" && length <= 0.0),
        }
    }
}
