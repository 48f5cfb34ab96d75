//! The reduced (dummy-derivative) system solved stage by stage: its
//! Jacobian is block lower triangular by Pryce's stages on every flat
//! built-in crane and on a user's crane of path order 6, and the inputs of
//! a run solved stage by stage are those of the same run solved whole (one
//! LU of all the jets), at every step, with as many Newton iterations.

use crane_macros::crane_model;
use crane_models::registry::{BuiltIn, Registry, Visit};
use crane_models::{Case, Crane, Maneuver, PathSpec, Profile};
use crane_runtime::dummy_derivative::DummyDerivative;
use crane_runtime::model::{DummyDerivatives, VisitDummyDerivatives};
use crane_runtime::nalgebra::{DMatrix, SVector};
use crane_runtime::{CraneModel, Options, Stepper, Trajectory};

/// What a run stage by stage and the same run solved whole measured.
#[derive(Debug)]
struct Comparison {
    crane: &'static str,
    /// The diagonal blocks' sizes, in the order they are solved.
    blocks: Vec<usize>,
    /// The largest Jacobian entry above the blocks over the run's states.
    above: f64,
    /// The largest difference of an input between the two runs, relative
    /// to the largest input.
    difference: f64,
    /// Newton iterations of the two runs.
    iterations: (usize, usize),
    steps: usize,
}

struct Compare<'a, C: Crane<N, M, A>, const N: usize, const M: usize, const A: usize> {
    case: &'a Case<C, N, M, A>,
}

impl<C: Crane<N, M, A>, const N: usize, const M: usize, const A: usize> VisitDummyDerivatives<C::Model, N, M, A>
    for Compare<'_, C, N, M, A>
{
    type Output = Comparison;
    fn visit<const J: usize>(self) -> Comparison
    where
        C::Model: DummyDerivatives<N, M, A, J>,
    {
        let (model, path) = (self.case.model(), self.case.path());
        let form = DummyDerivative::<&C::Model, &crane_models::Path<A>, N, M, A, J>::stages()
            .unwrap_or_else(|| panic!("{}: no stages", C::NAME));
        let start = self.case.start().unwrap();
        let options = Options::new(0.01, self.case.tf()).unwrap();
        let mut staged = Stepper::new(DummyDerivative::new(model, path), &start, &options).unwrap();
        let mut whole = Stepper::new(DummyDerivative::new(model, path).solved_whole(), &start, &options).unwrap();
        let (mut above, mut difference, mut largest) = (0.0f64, 0.0f64, 0.0f64);
        let mut iterations = (0, 0);
        let mut steps = 0;
        while staged.state().t < self.case.tf() - 1e-9 {
            iterations.0 += staged.step().unwrap().iterations;
            iterations.1 += whole.step().unwrap().iterations;
            steps += 1;
            let (a, b) = (staged.state(), whole.state());
            largest = largest.max(b.u.amax());
            difference = difference.max((a.u - b.u).amax());
            // the Jacobian at the step's path derivatives and at jets whose
            // low orders are the state's and whose higher ones are made up:
            // the blocks above are zero whatever the jets
            let t = a.t;
            let gamma: Vec<SVector<f64, A>> = (0..=<C::Model as DummyDerivatives<N, M, A, J>>::PATH_ORDER)
                .map(|k| path.derivative(t, k))
                .collect();
            let jets = SVector::<f64, J>::from_fn(|i, _| 1.0 + (i as f64 * 0.37 + t).sin());
            let (_, jacobian) = model.dummy_derivative_system(&gamma, &jets);
            above = above.max(form.largest_above(&DMatrix::from_column_slice(J, J, jacobian.as_slice())));
        }
        Comparison {
            crane: C::NAME,
            blocks: form.block_sizes().collect(),
            above,
            difference: difference / largest,
            iterations,
            steps,
        }
    }
}

/// The comparison on a crane's default move, if it has a reduced system.
struct OnCrane;

impl Visit for OnCrane {
    type Output = Option<Comparison>;
    fn visit<C: Crane<N, M, A>, const N: usize, const M: usize, const A: usize>(self) -> Self::Output {
        let case = Case::<C, N, M, A>::maneuver().unwrap();
        <C::Model as CraneModel<N, M, A>>::visit_dummy_derivatives(Compare { case: &case }).ok()
    }
}

/// Bound on the difference of the inputs: both runs stop Newton at a
/// normalised residual of 1e-13 or a correction below 1e-10 relative, the
/// error left of the order of its square; what differs is the round-off of
/// the linear solves (an LU of each stage against one of the whole), a few
/// ulps of the condition (below 10 equilibrated on the double pendulum).
const ROUND_OFF: f64 = 1e-12;

fn check(c: &Comparison) {
    println!("{c:?}");
    assert_eq!(c.above, 0.0, "{}: entries above the stages' blocks", c.crane);
    assert!(
        c.difference <= ROUND_OFF,
        "{}: stage by stage and whole differ by {:e}",
        c.crane,
        c.difference
    );
    // Newton ends when its correction or residual reaches round-off, which
    // the two solves reach in their own last digits: a step may take one
    // iteration more or less, not more than 1 in 100 of the run's
    let (staged, whole) = (c.iterations.0 as f64, c.iterations.1 as f64);
    assert!(
        (staged - whole).abs() <= 0.01 * whole,
        "{}: Newton iterations {:?}",
        c.crane,
        c.iterations
    );
    assert!(c.blocks.len() >= 2, "{}: one stage", c.crane);
}

#[test]
fn every_flat_built_in_is_solved_stage_by_stage_as_whole() {
    let registry = BuiltIn;
    let mut compared = Vec::new();
    for entry in registry.entries() {
        if let Some(comparison) = registry.visit(entry.name, OnCrane).flatten() {
            check(&comparison);
            compared.push(comparison.crane);
        }
    }
    // the eight flat built-ins (coupled-trolley has internal dynamics)
    assert_eq!(compared.len(), 8, "{compared:?}");
    // navy-planar: 26 jets in three stages (the jets of order c - 2, c - 1
    // and c of its 10 unknowns)
    let navy = registry.visit("navy-planar", OnCrane).flatten().unwrap();
    assert_eq!(navy.blocks, [8, 8, 10]);
}

crane_model! {
    /// A double-pendulum overhead crane: the inputs need the path's 6th derivative.
    pub struct UserHook {
        params { m_t: positive = 120.0, m_h: positive = 15.0, m_l: positive = 400.0, J: positive = 0.2,
                 r: positive = 0.08, l_s: positive = 1.5, g: positive = 9.81 }
        robot  [s, L, xh, zh]
        load   [x, z]
        inputs [u1, u2]
        kinetic = 0.5*m_t*dot(s)^2 + 0.5*J/r^2*dot(L)^2
                + 0.5*m_h*(dot(xh)^2 + dot(zh)^2) + 0.5*m_l*(dot(x)^2 + dot(z)^2);
        forces { s: u1, L: u2/r, zh: -m_h*g, z: -m_l*g }
        constraints {
            #[rope(N1 = L)]
            hoist: 0.5*((xh - s)^2 + zh^2 - L^2),
            #[rope(N2 = l_s)]
            sling: 0.5*((x - xh)^2 + (z - zh)^2 - l_s^2),
        }
    }
}

struct Hook;

impl Crane<6, 2, 2> for Hook {
    type Model = UserHook;
    const NAME: &'static str = "user-hook";

    fn maneuver() -> Maneuver<2> {
        Maneuver {
            path: PathSpec {
                profile: Profile::SmoothThreePhase { tau0: 2.5 },
                t0: 0.0,
                t1: 8.0,
                start: SVector::from([0.0, -4.5]),
                end: SVector::from([3.0, -3.5]),
            },
            p0: vec![0.0, 3.0, 0.0, -3.0],
        }
    }
}

#[test]
fn a_user_s_crane_of_path_order_6_is_solved_stage_by_stage_as_whole() {
    let c = OnCrane.visit::<Hook, 6, 2, 2>().unwrap();
    check(&c);
    assert_eq!(c.steps, 800);
    // 22 jets of 8 unknowns in five stages: an LU of at most 8 x 8 each
    assert_eq!(c.blocks, [3, 3, 6, 6, 8]);
}
