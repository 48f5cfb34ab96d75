//! A spline path through four waypoints runs on every flat built-in crane:
//! the default move's start and end with two waypoints between, a third
//! and two thirds of the way, raised by a tenth of the move's length (a
//! lift, a traverse, a lowering).
//!
//! At the default degree, `2 p + 1` for the crane's path order `p` (at rest
//! to order `p` at both ends, continuous to order `p` at the waypoints),
//! its inputs are continuous: the largest change of an input from one step
//! to the next halves with the step (a jump would keep it).
//!
//! On the same waypoints continuous to order `p + 3` (degree `2 p + 7`), the
//! exact reduced formulation's inputs are those of eqs. (22) with BDF-4:
//! from a tenth of the move on (eqs. (22) start with an index-3 transient)
//! they differ by at most 3e-3 of the peak at dt = 5 ms and 2e-4 at 2.5 ms,
//! falling at BDF-4's order (measured on every flat built-in, 15 to 16-fold
//! from 5 to 2.5 ms: navy-planar 2.5e-3, 1.6e-4; navy-3d-pulley 9.7e-9,
//! 6.0e-10; double-pendulum 3.8e-7, 2.5e-8; at 1.25 ms a further 16-fold,
//! but for elastic-drive, at its round-off near 2e-8). The spline gives
//! eqs. (22) its target in double-double (`Trajectory::target_extended`):
//! evaluated in `f64`, its rounding, differentiated by the scheme, made the
//! difference *grow* as the step shrank on the cranes of path order 6
//! (navy-3d-pulley: 1.0e-4, 1.7e-3, 2.6e-2 at 5, 2.5, 1.25 ms). Where the
//! path is continuous only to order `p` (the default), eqs. (22) converge
//! to it at about order 1.5 near the waypoints (navy-planar: 1.6e-2,
//! 7.1e-3, 1.9e-3 at 5, 2.5, 1.25 ms): their scheme differentiates the jumps
//! of derivative `p + 1`.
//!
//! A crane of path order 8 (a triple pendulum: a hook block on the hoist,
//! a second block on a sling, the load on a third) gets continuous inputs
//! from a spline of degree 17 through waypoints, and inputs that jump
//! from one of degree 9 (at rest only to order 4), which a scenario
//! refuses for it.

use crane_models::path::{Profile, SplineShape};
use crane_models::registry::{BuiltIn, Registry, Visit};
use crane_models::study::{Formulation, RunSpec};
use crane_models::{Case, Crane, Maneuver, PathSpec};
use crane_runtime::nalgebra::SVector;
use crane_runtime::{CraneModel, Options, Scheme, Solution};

/// What the spline runs of one crane measured.
#[derive(Debug)]
struct Measured {
    crane: &'static str,
    path_order: usize,
    /// The default degree.
    degree: usize,
    /// The largest change of an input between two steps, relative to the
    /// peak input, at dt = 10 ms and at 5 ms (the default degree).
    largest_change: (f64, f64),
    /// The largest difference between the exact inputs and eqs. (22) with
    /// BDF-4, relative to the peak, from a tenth of the move on, at dt = 5
    /// ms and 2.5 ms (degree `2 p + 7`).
    against_bdf4: (f64, f64),
}

/// The waypoints of the lift, traverse and lowering along the default move.
fn waypoints<const A: usize>(start: SVector<f64, A>, end: SVector<f64, A>, height: usize) -> [SVector<f64, A>; 4] {
    let lift = SVector::<f64, A>::from_fn(|i, _| if i == height { 0.1 * (end - start).norm() } else { 0.0 });
    [
        start,
        start + (end - start) / 3.0 + lift,
        start + (end - start) * (2.0 / 3.0) + lift,
        end,
    ]
}

/// The largest difference of the inputs of `b` from those of `exact` at the
/// times both have, from `from` on, relative to `peak`.
fn difference<const N: usize, const M: usize, const A: usize>(
    b: &Solution<N, M, A>,
    exact: &Solution<N, M, A>,
    from: f64,
    peak: f64,
) -> f64 {
    b.states
        .iter()
        .filter(|s| s.t >= from)
        .map(|s| {
            let e = exact.state_near(s.t).expect("a step near");
            assert!((e.t - s.t).abs() < 1e-9, "no exact step at {}", s.t);
            (s.u - e.u).amax()
        })
        .fold(0.0, f64::max)
        / peak
}

struct FourWaypoints;

impl Visit for FourWaypoints {
    type Output = Option<Measured>;
    fn visit<C: Crane<N, M, A>, const N: usize, const M: usize, const A: usize>(self) -> Self::Output {
        crane_runtime::dummy_derivative::system_size::<C::Model, N, M, A>().ok()?;
        let default = RunSpec::<A>::default_for::<C, N, M>();
        let PathSpec { t0, t1, start, end, .. } = default.path.clone();
        let loads = &<C::Model as CraneModel<N, M, A>>::INFO.coordinates[N - A..];
        let height = loads.iter().position(|&x| x == "z").expect("a load height z");
        let points = waypoints(start, end, height);
        let path_order = <C::Model as CraneModel<N, M, A>>::STRUCTURE
            .expect("a declared structure")
            .path_order(A);
        // the runs of the spline at rest to order `rest`
        let runs = |rest: usize, runs: &[(Formulation, Scheme, f64)]| {
            let shape = SplineShape::through(&[0.0, 1.0 / 3.0, 2.0 / 3.0, 1.0], &points, rest).expect("a spline");
            let degree = shape.degree();
            let mut spec = default.clone();
            spec.path = PathSpec {
                profile: Profile::Spline(std::sync::Arc::new(shape)),
                t0,
                t1,
                start,
                end,
            };
            let (case, _) = spec.build::<C, N, M>().expect("the spline move");
            let begin = case.start().expect("a consistent start");
            let solutions: Vec<Solution<N, M, A>> = runs
                .iter()
                .map(|&(formulation, scheme, dt)| {
                    let options = Options::new(dt, case.tf()).expect("a step").with_scheme(scheme);
                    formulation
                        .simulate(&case, &begin, &options, &mut |_, _| {})
                        .unwrap_or_else(|e| panic!("{} ({formulation:?}, {scheme:?}, dt = {dt}): {e}", C::NAME))
                })
                .collect();
            (degree, solutions)
        };
        let exact = |dt| (Formulation::DummyDerivative, Scheme::BackwardEuler, dt);
        let bdf4 = |dt| (Formulation::Redundant, Scheme::Bdf4, dt);
        let peak = |run: &Solution<N, M, A>| {
            run.states
                .iter()
                .flat_map(|s| s.u.iter())
                .fold(0.0f64, |m, u| m.max(u.abs()))
        };

        let (degree, continuous) = runs(path_order, &[exact(0.01), exact(0.005)]);
        let largest_change = |run: &Solution<N, M, A>| {
            run.states
                .windows(2)
                .map(|w| (w[1].u - w[0].u).amax())
                .fold(0.0, f64::max)
                / peak(&continuous[1])
        };

        let from = t0 + 0.1 * (t1 - t0);
        let smoother = [exact(0.005), bdf4(0.005), exact(0.0025), bdf4(0.0025)];
        let (_, smooth) = runs(path_order + 3, &smoother);
        let top = peak(&smooth[0]);
        let against_bdf4 = (
            difference(&smooth[1], &smooth[0], from, top),
            difference(&smooth[3], &smooth[2], from, top),
        );
        Some(Measured {
            crane: C::NAME,
            path_order,
            degree,
            largest_change: (largest_change(&continuous[0]), largest_change(&continuous[1])),
            against_bdf4,
        })
    }
}

#[test]
fn a_spline_through_four_waypoints_runs_on_every_flat_crane_with_continuous_inputs() {
    let mut measured = Vec::new();
    for entry in BuiltIn.entries() {
        if let Some(m) = BuiltIn.visit(entry.name, FourWaypoints).expect("a built-in") {
            println!("{m:?}");
            measured.push(m);
        }
    }
    // every built-in but coupled-trolley, which has internal dynamics
    assert_eq!(measured.len(), 8, "{measured:?}");
    for m in &measured {
        assert_eq!(m.degree, 2 * m.path_order + 1, "{m:?}");
        // continuous inputs: their largest change per step halves with the
        // step (measured 0.500 to 0.519)
        let ratio = m.largest_change.1 / m.largest_change.0;
        assert!((0.45..0.55).contains(&ratio), "{}: ratio {ratio}", m.crane);
        // BDF-4's order: falling at least 8-fold from 5 ms to 2.5 ms
        // (measured 15 to 16-fold on every one)
        let (coarse, finer) = m.against_bdf4;
        assert!(coarse <= 3e-3 && finer <= 2e-4, "{m:?}");
        assert!(finer * 8.0 <= coarse, "{m:?}");
    }
    // the cranes of path order 4 and those of 6 are both here
    assert!(measured.iter().any(|m| m.path_order == 6));
    assert!(measured.iter().any(|m| m.path_order == 4));
}

crane_macros::crane_model! {
    /// A triple-pendulum overhead crane: trolley, hoist, a hook block on the
    /// hoist rope, a second block on a sling below it, the load on a third
    /// sling. Its inputs need the load path's 8th derivative.
    pub struct TriplePendulum {
        params { m_t: positive = 100.0, J: positive = 0.1, r: positive = 0.1, m1: positive = 20.0,
                 m2: positive = 20.0, m_l: positive = 200.0, l2: positive = 2.0, l3: positive = 2.0,
                 g: positive = 9.81 }
        robot  [s, L, x1, z1, x2, z2]
        load   [x, z]
        inputs [u1, u2]
        kinetic = 0.5*m_t*dot(s)^2 + 0.5*J/r^2*dot(L)^2 + 0.5*m1*(dot(x1)^2 + dot(z1)^2)
                + 0.5*m2*(dot(x2)^2 + dot(z2)^2) + 0.5*m_l*(dot(x)^2 + dot(z)^2);
        forces { s: u1, L: u2/r, z1: -m1*g, z2: -m2*g, z: -m_l*g }
        constraints {
            #[rope(N1 = L)]
            hoist: 0.5*((x1 - s)^2 + z1^2 - L^2),
            #[rope(N2 = l2)]
            upper: 0.5*((x2 - x1)^2 + (z2 - z1)^2 - l2^2),
            #[rope(N3 = l3)]
            lower: 0.5*((x - x2)^2 + (z - z2)^2 - l3^2),
        }
    }
}

/// The triple pendulum, hanging at rest: the load 7 m below the trolley.
struct Triple;

impl Crane<8, 3, 2> for Triple {
    type Model = TriplePendulum;
    const NAME: &'static str = "triple-pendulum";

    fn maneuver() -> Maneuver<2> {
        Maneuver {
            path: PathSpec {
                profile: Profile::Poly9,
                t0: 0.0,
                t1: 8.0,
                start: SVector::from([0.0, -7.0]),
                end: SVector::from([4.0, -6.0]),
            },
            p0: vec![0.0, 3.0, 0.0, -3.0, 0.0, -5.0],
        }
    }
}

/// The largest change of an input per step, relative to the peak input, of
/// the triple pendulum's exact run through four waypoints at rest to order
/// `rest`, at dt = 10 ms and 5 ms.
fn triple_largest_change(rest: usize) -> (f64, f64) {
    let default = Case::<Triple, 8, 3, 2>::maneuver().unwrap();
    let spec = default.path().spec().clone();
    let points = waypoints(spec.start, spec.end, 1);
    let shape = SplineShape::through(&[0.0, 1.0 / 3.0, 2.0 / 3.0, 1.0], &points, rest).unwrap();
    let mut run_spec = RunSpec::<2>::default_for::<Triple, 8, 3>();
    run_spec.path = PathSpec {
        profile: Profile::Spline(std::sync::Arc::new(shape)),
        ..spec
    };
    let (case, _) = run_spec.build::<Triple, 8, 3>().unwrap();
    let begin = case.start().unwrap();
    let runs: Vec<Solution<8, 3, 2>> = [0.01, 0.005]
        .iter()
        .map(|&dt| {
            let options = Options::new(dt, case.tf()).unwrap();
            Formulation::DummyDerivative
                .simulate(&case, &begin, &options, &mut |_, _| {})
                .unwrap()
        })
        .collect();
    let peak = runs[1].states.iter().map(|s| s.u.amax()).fold(0.0, f64::max);
    let change = |run: &Solution<8, 3, 2>| {
        run.states
            .windows(2)
            .map(|w| (w[1].u - w[0].u).amax())
            .fold(0.0, f64::max)
            / peak
    };
    (change(&runs[0]), change(&runs[1]))
}

#[test]
fn a_crane_of_path_order_eight_gets_continuous_inputs_from_a_spline_of_degree_seventeen() {
    let order = <TriplePendulum as CraneModel<8, 3, 2>>::STRUCTURE
        .unwrap()
        .path_order(2);
    assert_eq!(order, 8);
    // degree 17, at rest to order 8: the largest change halves with the step
    // (measured 0.534)
    let smooth = triple_largest_change(8);
    let ratio = smooth.1 / smooth.0;
    println!("degree 17: {smooth:?}, ratio {ratio}");
    assert!((0.45..0.55).contains(&ratio), "{smooth:?}");
    // degree 9, at rest only to order 4: derivatives 5 .. 8 jump at the
    // waypoints and ends, and so do the inputs (the change keeps its size:
    // measured 1.054)
    let rough = triple_largest_change(4);
    let ratio = rough.1 / rough.0;
    println!("degree 9: {rough:?}, ratio {ratio}");
    assert!(ratio > 0.9, "{rough:?}");
}
