//! What a run's summary warns of: results that are not a usable feedforward
//! although every step converged (unstable internal dynamics, an input far
//! beyond its size at the start) and a path too rough for the crane.

use std::fmt;

use crane_runtime::error::Seconds;

use super::summary::Summary;

/// A warning about a run.
#[derive(Debug, Clone, PartialEq)]
pub enum Warning {
    /// The internal dynamics along the path are unstable: the causal
    /// inverse grows without bound.
    UnstableInternalDynamics {
        /// The crane's name.
        model: String,
        /// Their dimension.
        dimension: usize,
        /// The largest real part of an eigenvalue, 1/s.
        max_real_part: f64,
        /// Where, s.
        at: f64,
    },
    /// The inputs depend on derivatives of the path beyond its continuity.
    PathTooRough {
        /// The crane's name.
        model: String,
        /// The highest path derivative the inputs depend on.
        needed: usize,
        /// The highest continuous one.
        continuous: usize,
    },
    /// The crane's inputs need a higher derivative of the path than the
    /// formulation's index reduction covers: its errors grow as dt shrinks.
    BeyondFormulation {
        /// The crane's name.
        model: String,
        /// The path order the crane needs.
        needed: usize,
        /// The path order the formulation covers.
        covered: usize,
    },
    /// A rope's length reaches zero or below during the run: the path leaves
    /// the crane's workspace (the start refuses such a state; along the
    /// run the equations still solve, on the mirror side of the rope).
    NonPositiveRopeLength {
        /// The crane's name.
        model: String,
        /// The rope's tension name, e.g. `N2`.
        rope: String,
        /// Its constraint's name.
        constraint: String,
        /// Its shortest length, m.
        length: f64,
        /// When, s.
        at: f64,
    },
    /// The reported states leave their constraints
    /// ([`ConstraintResidual::violated`](super::summary::ConstraintResidual::violated)).
    ConstraintsViolated {
        /// The crane's name.
        model: String,
        /// How far, where, when.
        residual: super::summary::ConstraintResidual,
    },
    /// Many steps met a singular iteration matrix ([`singular_steps`](super::summary::singular_steps)).
    SingularSteps {
        /// The crane's name.
        model: String,
        /// Steps with a minimum-norm Newton update.
        count: usize,
        /// All steps.
        steps: usize,
    },
    /// An input exceeds [`RUNAWAY_FACTOR`](crane_runtime::internal::RUNAWAY_FACTOR)
    /// times its size at the start.
    Runaway {
        /// The crane's name.
        model: String,
        /// From when, s.
        at: f64,
    },
}

impl fmt::Display for Warning {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Warning::UnstableInternalDynamics {
                model,
                dimension,
                max_real_part,
                at,
            } => write!(
                f,
                "{model} has unstable internal dynamics along this path (dimension {dimension}, largest real part \
                 {max_real_part:.4} 1/s at t = {} s): the computed inputs grow without bound; see docs/internal-dynamics.md \
                 in the guide",
                Seconds(*at)
            ),
            Warning::PathTooRough {
                model,
                needed,
                continuous,
            } => write!(
                f,
                "the inputs of {model} depend on the load path's derivatives up to order {needed}, but this path is \
                 continuous only up to order {continuous}: the exact inputs jump or carry impulses where its \
                 derivative {} jumps, and the computed ones grow there as dt shrinks (use a smoother path, e.g. \
                 trajectory = \"smooth-three-phase\")",
                continuous + 1
            ),
            Warning::NonPositiveRopeLength {
                model,
                rope,
                constraint,
                length,
                at,
            } => write!(
                f,
                "rope {rope} of {model} (constraint `{constraint}`) has the length {length:.4} m at t = {} s: the \
                 path leaves the crane's workspace, and the computed motion is not one the crane can make",
                Seconds(*at)
            ),
            Warning::ConstraintsViolated { model, residual } => write!(f, "{model}: {residual}"),
            Warning::SingularSteps { model, count, steps } => write!(
                f,
                "{count} of {steps} steps of {model} met an iteration matrix singular to working precision (a rope \
                 without tension leaves a coordinate free, as when the load hangs straight below the boom tip): \
                 the path does not determine the inputs there, and they are not a reliable result"
            ),
            Warning::BeyondFormulation { model, needed, covered } => write!(
                f,
                "the inputs of {model} depend on the load path's derivatives up to order {needed}, but this \
                 formulation (the paper's minimal extension, eqs. 22 and 24) covers order {covered}: the \
                 discretised system's index is too high for the scheme, its errors grow as dt shrinks, and the \
                 computed inputs are not a reliable result"
            ),
            Warning::Runaway { model, at } => write!(
                f,
                "an input of {model} exceeds 1e6 times its size at the start from t = {} s: not a physical result",
                Seconds(*at)
            ),
        }
    }
}

/// The warnings of a run's summary, in this order: a crane beyond the
/// formulation, unstable internal dynamics, a path too rough, a runaway input.
pub fn warnings(summary: &Summary) -> Vec<Warning> {
    let model = summary.model.clone();
    let internal = &summary.internal_dynamics;
    let mut out = Vec::new();
    if let Some(p) = internal.path_order.filter(|p| !p.is_covered()) {
        out.push(Warning::BeyondFormulation {
            model: model.clone(),
            needed: p.needed,
            covered: p.covered,
        });
    }
    if let Some(residual) = summary.constraint_residual.as_ref().filter(|r| r.violated()) {
        out.push(Warning::ConstraintsViolated {
            model: model.clone(),
            residual: residual.clone(),
        });
    }
    if !internal.stable {
        out.push(Warning::UnstableInternalDynamics {
            model: model.clone(),
            dimension: internal.dimension,
            max_real_part: internal.max_real_part.unwrap_or(f64::NAN),
            at: internal.at.unwrap_or(f64::NAN),
        });
    }
    if let Some(smooth) = summary.path_smoothness.as_ref().filter(|s| !s.sufficient) {
        out.push(Warning::PathTooRough {
            model: model.clone(),
            needed: smooth.needed,
            continuous: smooth.continuous,
        });
    }
    for r in summary.ropes.iter().filter(|r| r.leaves_workspace()) {
        out.push(Warning::NonPositiveRopeLength {
            model: model.clone(),
            rope: r.name.clone(),
            constraint: r.constraint.clone(),
            length: r.min_length,
            at: r.t_min_length,
        });
    }
    if let Some(at) = internal.runaway_at {
        out.push(Warning::Runaway {
            model: model.clone(),
            at,
        });
    }
    if super::summary::singular_steps(summary) {
        out.push(Warning::SingularSteps {
            model,
            count: summary.newton.min_norm_steps,
            steps: summary.steps,
        });
    }
    out
}
