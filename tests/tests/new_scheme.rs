//! A scheme defined here, outside the runtime, runs on every problem: the
//! second-order numerical differentiation formula NDF-2 (Klopfenstein;
//! Shampine and Reichelt, the default of MATLAB's `ode15s`) is one
//! `impl Method` of a dozen lines, and the servo problem in redundant and
//! in minimal coordinates and the forward dynamics take it as they take the
//! built-in BDF-k, without a line of them changed.
//!
//! NDF-2 is BDF-2 plus `-kappa gamma_2 nabla^3 y_{n+1}` with `kappa = -1/9`,
//! `gamma_2 = 3/2`:
//! `5/3 y_{n+1} - 5/2 y_n + y_{n-1} - 1/6 y_{n-2} = dt y'_{n+1}`. As a
//! difference quotient it is `y' - dt^2 y'''/6 + O(dt^3)` (Taylor: the
//! coefficients times the cubes of the offsets 0, -1, -2, -3, over 6),
//! against BDF-2's `y' - dt^2 y'''/3`: the inputs, which come from the
//! rates of the rates, should be order 2 with half BDF-2's error.

use crane_models::{navy_planar, navy_planar_pulley};
use crane_runtime::forward::Forward;
use crane_runtime::scheme::{Formula, Method};
use crane_runtime::{Options, Scheme, Stepper, Trajectory, simulate, simulate_minimal};
use crane_tests::kit;

/// NDF-2, started with backward Euler and BDF-2 while its history is short
/// (a start at rest has a full history and uses NDF-2 from the first step).
#[derive(Debug, Clone, Copy)]
struct Ndf2;

impl Method for Ndf2 {
    fn name(&self) -> &'static str {
        "ndf2"
    }

    fn order(&self) -> usize {
        2
    }

    fn formula(&self, known: usize) -> Formula {
        match known {
            1 => Formula::new(1.0, &[-1.0]),
            2 => Formula::new(1.5, &[-4.0 / 3.0, 1.0 / 3.0]),
            _ => Formula::new(5.0 / 3.0, &[-1.5, 0.6, -0.1]),
        }
    }
}

/// The steps of the study: the last two well inside the asymptotic range
/// of BDF-2 on these cranes (kit's scheme tests), above round-off.
const DTS: [f64; 3] = [0.02, 0.01, 0.005];

/// e_u (eq. 48) of NDF-2 in both formulations at each step of `DTS`, and
/// of BDF-2 in redundant coordinates at the smallest.
fn errors<C, const N: usize, const M: usize, const A: usize, const F: usize>(
    case: &crane_models::Case<C, N, M, A>,
    guess: impl Fn(&C::Model, &crane_runtime::State<N, M, A>) -> crane_runtime::nalgebra::SVector<f64, F>,
) -> ([f64; 3], [f64; 3], f64)
where
    C: crane_models::Crane<N, M, A>,
    C::Model: crane_runtime::MinimalMap<N, M, A, F>,
{
    let start = case.start().unwrap();
    let e_u = |run: &crane_runtime::Solution<N, M, A>| kit::e_u(case, run);
    let mut redundant = [0.0; 3];
    let mut minimal = [0.0; 3];
    for (i, &dt) in DTS.iter().enumerate() {
        let options = Options::new(dt, kit::T_ERROR).unwrap().with_scheme(Ndf2);
        let run = simulate(case.model(), case.path(), &start, &options).unwrap();
        assert_eq!(run.scheme, "ndf2");
        redundant[i] = e_u(&run);
        let guess = guess(case.model(), &start);
        minimal[i] = e_u(&simulate_minimal(case.model(), case.path(), &start, &guess, &options).unwrap());
    }
    let bdf2 = Options::new(DTS[2], kit::T_ERROR).unwrap().with_scheme(Scheme::Bdf2);
    let bdf2 = e_u(&simulate(case.model(), case.path(), &start, &bdf2).unwrap());
    (redundant, minimal, bdf2)
}

/// Order 2 (each halving of dt divides e_u by 4, within 25 %) in both
/// formulations, and at the smallest step an error between 0.4 and 0.6 of
/// BDF-2's (1/2 from the difference quotients' error terms; the band leaves
/// room for the next term).
fn assert_ndf2(name: &str, (redundant, minimal, bdf2): ([f64; 3], [f64; 3], f64)) {
    println!("{name}: NDF-2 e_u redundant {redundant:?}, minimal {minimal:?}; BDF-2 {bdf2:.4e}");
    for errors in [redundant, minimal] {
        for w in errors.windows(2) {
            kit::assert_ratio_of_order(&format!("{name} ndf2"), Scheme::Bdf2, w[0] / w[1]);
        }
    }
    let ratio = redundant[2] / bdf2;
    assert!((0.4..=0.6).contains(&ratio), "{name}: NDF-2 / BDF-2 = {ratio}");
}

#[test]
fn ndf2_defined_here_converges_with_order_2_on_the_planar_crane() {
    let case = navy_planar::PaperCase::new(4.0).unwrap();
    assert_ndf2("navy-planar", errors(&case, navy_planar::minimal_guess));
}

#[test]
fn ndf2_defined_here_converges_with_order_2_on_the_pulley_crane() {
    let case = navy_planar_pulley::PaperCase::new(4.0).unwrap();
    assert_ndf2("navy-planar-pulley", errors(&case, navy_planar_pulley::minimal_guess));
}

/// The forward problem on NDF-2: the pulley crane driven by the analytical
/// inputs of Appendix A follows the analytical load path, and the load's
/// deviation at 1.5 s falls with order 2.
#[test]
fn ndf2_defined_here_runs_the_forward_dynamics() {
    let case = navy_planar_pulley::PaperCase::new(4.0).unwrap();
    let start = case.start().unwrap();
    let inputs = |t: f64| case.reference(t).expect("the reference is defined on the move").u;
    let deviation = |dt: f64| {
        let options = Options::new(dt, kit::T_ERROR).unwrap().with_scheme(Ndf2);
        let mut stepper = Stepper::new(Forward::new(case.model(), inputs), &start, &options).unwrap();
        let steps = (kit::T_ERROR / dt).round() as usize;
        for _ in 0..steps {
            stepper.step().unwrap();
        }
        let state = stepper.state();
        let load = case.path().derivative(state.t, 0);
        (state.q.fixed_rows::<3>(5) - load).amax()
    };
    let d: Vec<f64> = DTS.iter().map(|&dt| deviation(dt)).collect();
    println!("navy-planar-pulley forward NDF-2: |x - gamma| at 1.5 s {d:?}");
    for w in d.windows(2) {
        kit::assert_ratio_of_order("navy-planar-pulley forward ndf2", Scheme::Bdf2, w[0] / w[1]);
    }
}
