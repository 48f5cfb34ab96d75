//! A run as data ([`RunSpec`]): the crane's parameters, the load path, the
//! start, the end and the settings. Scenario files and FMU variables fill
//! one in; [`RunSpec::build`] checks it once against the crane and makes
//! the [`Case`] and [`RunSettings`] of the run.

use crane_runtime::model::check_parameters;
use crane_runtime::trajectory::TrajectoryError;
use crane_runtime::{CraneModel, Options, Scheme, UnknownParameter};

use super::{DEFAULT_DT, Formulation, RunSettings};
use crate::case::Case;
use crate::crane::Crane;
use crate::path::{Path, PathSpec};

/// A run of a crane with `A` load coordinates, as data.
#[derive(Debug, Clone, PartialEq)]
pub struct RunSpec<const A: usize> {
    /// Parameter values, `(name, value)`, set in order over the model's
    /// defaults (a scenario gives those it changes, an FMU all of them).
    pub parameters: Vec<(String, f64)>,
    /// The load path.
    pub path: PathSpec<A>,
    /// The robot coordinates at the start (a guess, checked or improved
    /// when the run starts).
    pub p0: Vec<f64>,
    /// End of the run, s.
    pub tf: f64,
    /// Time step, s.
    pub dt: f64,
    /// The scheme.
    pub scheme: Scheme,
    /// The formulation.
    pub formulation: Formulation,
    /// Limits on `|u|`, `(input name, limit)`.
    pub limits: Vec<(String, f64)>,
    /// Parameters of a replay's plant that differ from the planner's.
    pub plant: Vec<(String, f64)>,
}

/// What is wrong with a [`RunSpec`] for its crane.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum SpecError {
    /// The crane has no parameter of this name.
    #[error("{source}")]
    UnknownParameter {
        /// The name given.
        name: String,
        /// The crane's answer, listing its parameters.
        source: UnknownParameter,
    },
    /// The parameters give the crane no physical meaning: a value NaN or
    /// infinite, a parameter declared `positive` that is not, an indefinite
    /// mass matrix ([`check_parameters`]).
    #[error("{0}")]
    Parameters(crane_runtime::Error),
    /// The load path cannot be built.
    #[error("the load path: {0}")]
    Path(TrajectoryError),
    /// The start has the wrong number of robot coordinates.
    #[error("the start p0 needs {expected} numbers ({names}), got {found}")]
    WrongStartLength {
        /// `n - a`.
        expected: usize,
        /// The robot coordinates' names.
        names: String,
        /// How many were given.
        found: usize,
    },
    /// The end of the run is not after its start.
    #[error("the run ends at tf = {tf} s, not after its start t0 = {t0} s")]
    EndBeforeStart {
        /// The end.
        tf: f64,
        /// The start.
        t0: f64,
    },
    /// The time step or the end is not a number the runtime accepts.
    #[error("{0}")]
    Time(crane_runtime::Error),
    /// A limit on an input the crane does not have.
    #[error("the crane has no input `{name}`; its inputs are {inputs}")]
    UnknownInput {
        /// The name given.
        name: String,
        /// The crane's inputs.
        inputs: String,
    },
    /// A limit that is not a positive number.
    #[error("the limit on `{name}` must be a positive number, got {value}")]
    LimitNotPositive {
        /// The input.
        name: String,
        /// The limit given.
        value: f64,
    },
}

impl<const A: usize> RunSpec<A> {
    /// The default manoeuvre of crane `C` with its default parameters, run
    /// to the end of the motion at `dt = 0.01 s` with backward Euler in
    /// its default formulation ([`Formulation::default_for`]; what `crane run MODEL` does).
    pub fn default_for<C: Crane<N, M, A>, const N: usize, const M: usize>() -> Self {
        let maneuver = C::maneuver();
        Self {
            parameters: Vec::new(),
            tf: maneuver.path.t1,
            path: maneuver.path,
            p0: maneuver.p0,
            dt: DEFAULT_DT,
            scheme: Scheme::default(),
            formulation: Formulation::default_for::<C, N, M, A>(),
            limits: Vec::new(),
            plant: Vec::new(),
        }
    }

    /// Check the description against crane `C` and make the run's case and
    /// settings, in this order: `tf` after `t0` and `dt` a valid step, the
    /// path buildable, every parameter known, finite and (where declared)
    /// positive with a positive semi-definite mass matrix, `p0` of the
    /// right length, every limit on a known input and positive.
    ///
    /// ```
    /// use crane_models::navy_planar::Description;
    /// use crane_models::study::{RunSpec, SpecError};
    ///
    /// let mut spec = RunSpec::default_for::<Description, 7, 3>();
    /// spec.parameters.push(("m_l".into(), 150.0));
    /// let (case, settings) = spec.build::<Description, 7, 3>().unwrap();
    /// assert_eq!(case.model().m_l, 150.0);
    /// assert_eq!(settings.dt, 0.01);
    /// spec.parameters.push(("m_l".into(), -1.0));
    /// assert!(matches!(spec.build::<Description, 7, 3>(), Err(SpecError::Parameters(_))));
    /// ```
    pub fn build<C: Crane<N, M, A>, const N: usize, const M: usize>(
        &self,
    ) -> Result<(Case<C, N, M, A>, RunSettings), SpecError> {
        let info = <C::Model as CraneModel<N, M, A>>::INFO;
        // the times first, then the path, then the crane
        let t0 = self.path.t0;
        if !(self.tf.is_finite() && self.tf > t0) {
            return Err(SpecError::EndBeforeStart { tf: self.tf, t0 });
        }
        Options::new(self.dt, self.tf).map_err(SpecError::Time)?;
        let path = Path::new(self.path.clone()).map_err(SpecError::Path)?;
        let mut model = C::Model::default();
        for (name, value) in &self.parameters {
            model
                .set_parameter(name, *value)
                .map_err(|source| SpecError::UnknownParameter {
                    name: name.clone(),
                    source,
                })?;
        }
        // finite values, masses, inertias and lengths declared positive, and
        // a positive semi-definite mass matrix
        check_parameters(&model).map_err(SpecError::Parameters)?;
        if self.p0.len() != N - A {
            return Err(SpecError::WrongStartLength {
                expected: N - A,
                names: info.coordinates[..N - A].join(", "),
                found: self.p0.len(),
            });
        }
        let mut limits = Vec::new();
        for (name, limit) in &self.limits {
            let k = info
                .inputs
                .iter()
                .position(|n| n == name)
                .ok_or_else(|| SpecError::UnknownInput {
                    name: name.clone(),
                    inputs: info.inputs.join(", "),
                })?;
            if !(limit.is_finite() && *limit > 0.0) {
                return Err(SpecError::LimitNotPositive {
                    name: name.clone(),
                    value: *limit,
                });
            }
            limits.push((k, *limit));
        }
        let case = Case::from_parts(model, path, self.p0.clone(), self.tf);
        let settings = RunSettings {
            dt: self.dt,
            formulation: self.formulation,
            scheme: self.scheme,
            limits,
            plant: self.plant.clone(),
        };
        Ok((case, settings))
    }
}
