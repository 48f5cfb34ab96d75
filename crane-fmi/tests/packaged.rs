//! An FMU packaged with a scenario's run (`crane fmu MODEL --scenario`):
//! the run travels as text, reads back as written, and the instance steps
//! it, a spline move included, as the API runs it.

use std::sync::Arc;

use crane_fmi::description::model_description;
use crane_fmi::ffi::folder_of_uri;
use crane_fmi::instance::{Component, Instance};
use crane_fmi::start::{Start, StartError};
use crane_fmi::variables::{Role, SPLINE_PATH, variables};
use crane_models::path::SplineShape;
use crane_models::study::RunSpec;
use crane_models::{Crane, PathSpec, Profile, navy_planar};
use crane_runtime::{CraneModel, Options, Solution};
use nalgebra::SVector;

type D = navy_planar::Description;

/// navy-planar's default move bent into a spline through four waypoints
/// (raised by a tenth of the move's length between its ends), at rest to
/// the crane's path order at both ends; with a heavier load, a step of
/// 5 ms and BDF-2.
fn spline_run() -> RunSpec<2> {
    let mut spec = RunSpec::<2>::default_for::<D, 7, 3>();
    let PathSpec { start, end, .. } = spec.path.clone();
    let lift = SVector::<f64, 2>::new(0.0, 0.1 * (end - start).norm());
    let points = [
        start,
        start + (end - start) / 3.0 + lift,
        start + (end - start) * (2.0 / 3.0) + lift,
        end,
    ];
    let rest = <navy_planar::NavyPlanar as CraneModel<7, 3, 2>>::STRUCTURE
        .unwrap()
        .path_order(2);
    let shape = SplineShape::through(&[0.0, 1.0 / 3.0, 2.0 / 3.0, 1.0], &points, rest).unwrap();
    spec.path.profile = Profile::Spline(Arc::new(shape));
    spec.parameters.push(("m_l".into(), 150.0));
    spec.dt = 0.005;
    spec.scheme = "bdf2".parse().unwrap();
    spec
}

/// The API's run of `spec` on crane `C` in its formulation.
fn api_run<C: Crane<N, M, A>, const N: usize, const M: usize, const A: usize>(spec: &RunSpec<A>) -> Solution<N, M, A> {
    let (case, settings) = spec.build::<C, N, M>().unwrap();
    let options = Options::new(settings.dt, case.tf())
        .unwrap()
        .with_scheme(settings.scheme);
    settings
        .formulation
        .simulate(&case, &case.start().unwrap(), &options, &mut |_, _| {})
        .unwrap()
}

/// Value references of crane `C`'s inputs and coordinates.
fn output_refs<C: Crane<N, M, A>, const N: usize, const M: usize, const A: usize>(start: &Start<A>) -> Vec<u32> {
    let table = variables::<C, N, M, A>(start).unwrap();
    let vr = |role| {
        table
            .iter()
            .find(|v| v.role == role && !v.integer)
            .unwrap()
            .value_reference
    };
    (0..A)
        .map(|k| vr(Role::Input(k)))
        .chain((0..N).map(|k| vr(Role::Coordinate(k))))
        .collect()
}

/// The instance of `start` stepped over `run`'s times, one internal step per
/// communication step, against `run` at every step (bit for bit).
fn steps_as<C: Crane<N, M, A>, const N: usize, const M: usize, const A: usize>(
    start: &Start<A>,
    run: &Solution<N, M, A>,
    set: impl FnOnce(&mut Instance<C, N, M, A>),
) {
    let refs = output_refs::<C, N, M, A>(start);
    let mut fmu = Instance::<C, N, M, A>::starting_from(start.clone()).unwrap();
    fmu.setup_experiment(run.states[0].t).unwrap();
    fmu.enter_initialization_mode().unwrap();
    set(&mut fmu);
    fmu.exit_initialization_mode().unwrap();
    let dt = run.states[1].t - run.states[0].t;
    let mut values = vec![0.0; refs.len()];
    for (i, state) in run.states.iter().enumerate() {
        if i > 0 {
            fmu.do_step(run.states[i - 1].t, dt).unwrap();
        }
        fmu.get_real(&refs, &mut values).unwrap();
        let expected: Vec<f64> = state.u.iter().chain(state.q.iter()).copied().collect();
        assert_eq!(values, expected, "at t = {}", state.t);
    }
}

/// The packaged spline run starts with `path` = 4 and its parameters,
/// step and scheme as start values, and the instance gives the API's run of
/// the same spec bit for bit; its GUID is not the default FMU's.
#[test]
fn a_packaged_spline_run_is_the_api_run_bit_for_bit() {
    let spec = spline_run();
    let start = Start::packaged::<D, 7, 3>(&spec).unwrap();
    let table = variables::<D, 7, 3, 2>(&start).unwrap();
    let start_of = |name: &str| table.iter().find(|v| v.name == name).unwrap().start;
    assert_eq!(start_of("path"), f64::from(SPLINE_PATH));
    assert_eq!(start_of("m_l"), 150.0);
    assert_eq!(start_of("dt"), 0.005);
    assert_eq!(start_of("scheme"), f64::from(spec.scheme.code()));
    let run = api_run::<D, 7, 3, 2>(&spec);
    assert!(run.states.len() > 100, "{} steps", run.states.len());
    steps_as::<D, 7, 3, 2>(&start, &run, |_| {});
    let (xml, guid) = model_description::<D, 7, 3, 2>(&start).unwrap();
    let (_, default_guid) = model_description::<D, 7, 3, 2>(&Start::default_for::<D, 7, 3>()).unwrap();
    assert_ne!(guid, default_guid);
    assert!(xml.contains("4 the spline move"), "{xml}");
}

/// `t0` and `duration` re-time the packaged shape: the instance with the
/// move starting 0.5 s later and lasting twice as long is the API's run of
/// that spline.
#[test]
fn t0_and_duration_retime_the_packaged_spline() {
    let spec = spline_run();
    let start = Start::packaged::<D, 7, 3>(&spec).unwrap();
    let mut retimed = spec.clone();
    let length = spec.path.t1 - spec.path.t0;
    retimed.path.t0 = spec.path.t0 + 0.5;
    retimed.path.t1 = retimed.path.t0 + 2.0 * length;
    retimed.tf = retimed.path.t1;
    let run = api_run::<D, 7, 3, 2>(&retimed);
    let table = variables::<D, 7, 3, 2>(&start).unwrap();
    let vr = |role| table.iter().find(|v| v.role == role).unwrap().value_reference;
    let (t0, duration) = (vr(Role::T0), vr(Role::Duration));
    steps_as::<D, 7, 3, 2>(&start, &run, |fmu| {
        fmu.set_real(&[t0, duration], &[retimed.path.t0, 2.0 * length]).unwrap();
    });
}

/// The text reads back to the run packaged; a run for another crane, a
/// control point of the wrong length and an unknown key are refused with
/// what is wrong.
#[test]
fn the_packaged_run_reads_back_as_written() {
    let start = Start::packaged::<D, 7, 3>(&spline_run()).unwrap();
    let text = start.resource.clone().unwrap();
    assert_eq!(Start::read::<D, 7, 3>(&text).unwrap(), start);
    let other = Start::read::<crane_models::gantry_3d::Description, 6, 1>(&text);
    assert!(
        matches!(other, Err(StartError::WrongModel { ref found, .. }) if found == "navy-planar"),
        "{other:?}"
    );
    let short = text.replacen("control = [[", "control = [[1.0], [", 1);
    let error = Start::read::<D, 7, 3>(&short).unwrap_err().to_string();
    assert!(error.contains("`control` has 1 numbers, not 2"), "{error}");
    let unknown = format!("colour = 1\n{text}");
    let error = Start::read::<D, 7, 3>(&unknown).unwrap_err().to_string();
    assert!(error.contains("colour"), "{error}");
    let negative = text.replace("m_l = 150.0", "m_l = -150.0");
    assert_ne!(negative, text);
    assert!(matches!(Start::read::<D, 7, 3>(&negative), Err(StartError::Run(_))));
}

/// `path` = 4 on an FMU without a spline move is refused at
/// `fmi2ExitInitializationMode`, saying how to package one.
#[test]
fn the_spline_path_without_a_packaged_spline_is_an_error() {
    let mut fmu = Instance::<D, 7, 3, 2>::new().unwrap();
    fmu.setup_experiment(0.0).unwrap();
    fmu.enter_initialization_mode().unwrap();
    fmu.set_integer(&[1], &[SPLINE_PATH]).unwrap();
    let error = fmu.exit_initialization_mode().unwrap_err();
    assert!(error.contains("--scenario"), "{error}");
}

/// A run `crane run` refuses is not packaged: a `p0` that is no start,
/// an end that is no whole number of steps, a path that leaves the
/// crane's workspace (to a point above the boom tip).
#[test]
fn a_run_crane_run_refuses_is_not_packaged() {
    let mut spec = spline_run();
    spec.p0 = vec![1.0, 2.0, 3.0, 4.0, 5.0];
    let error = Start::packaged::<D, 7, 3>(&spec).unwrap_err().to_string();
    assert!(error.contains("give a `p0` that meets every constraint"), "{error}");
    let mut spec = spline_run();
    spec.dt = 0.03;
    spec.tf = spec.path.t1 + 0.01;
    let error = Start::packaged::<D, 7, 3>(&spec).unwrap_err().to_string();
    assert!(error.contains("not a whole number of steps"), "{error}");
    let mut spec = RunSpec::<2>::default_for::<D, 7, 3>();
    spec.path.end = SVector::<f64, 2>::new(-3.0, 5.0);
    let error = Start::packaged::<D, 7, 3>(&spec).unwrap_err().to_string();
    assert!(
        error.contains("the load path leaves navy-planar's workspace") && error.contains("rope N2 would be -"),
        "{error}"
    );
}

/// The resource locations hosts pass: `file:///`, `file:/`, `localhost`,
/// percent-escapes; anything else is no local folder.
#[test]
fn resource_locations_are_file_uris() {
    let folder = |uri: &str| folder_of_uri(uri).map(|p| p.display().to_string());
    assert_eq!(
        folder("file:///tmp/a%20b/resources/").as_deref(),
        Some("/tmp/a b/resources/")
    );
    assert_eq!(folder("file:/tmp/x/resources").as_deref(), Some("/tmp/x/resources"));
    assert_eq!(folder("file://localhost/tmp/x").as_deref(), Some("/tmp/x"));
    assert_eq!(folder("FILE:///tmp/x").as_deref(), Some("/tmp/x"));
    assert_eq!(
        folder("file:///tmp/x/resources?v=1#top").as_deref(),
        Some("/tmp/x/resources")
    );
    assert_eq!(folder("file://server/share"), None);
    assert_eq!(folder("http://example.com/x"), None);
    assert_eq!(folder("file:///tmp/%zz"), None);
    assert_eq!(folder("file:relative/path"), None);
}

/// gantry-3d with a spline as its own default move (lift, carry, lower
/// through four waypoints in 9 s): no resource needed, the FMU starts on
/// `path` = 4.
struct SplineGantry;

impl Crane<6, 1, 3> for SplineGantry {
    type Model = crane_models::gantry_3d::Gantry3d;
    const NAME: &'static str = "spline-gantry";

    fn maneuver() -> crane_models::Maneuver<3> {
        let points = [
            SVector::<f64, 3>::new(0.0, 0.0, -5.0),
            SVector::<f64, 3>::new(0.0, 0.0, -3.0),
            SVector::<f64, 3>::new(6.0, 3.0, -3.0),
            SVector::<f64, 3>::new(6.0, 3.0, -5.0),
        ];
        let shape = SplineShape::through(&[0.0, 2.0 / 9.0, 7.0 / 9.0, 1.0], &points, 4).unwrap();
        crane_models::Maneuver {
            path: PathSpec {
                profile: Profile::Spline(Arc::new(shape)),
                t0: 0.0,
                t1: 9.0,
                start: points[0],
                end: points[3],
            },
            p0: vec![0.0, 0.0, 5.0],
        }
    }
}

/// A crane whose own default move is a spline has an FMU: its `path`
/// starts at 4, and the instance steps the API's run of its default move
/// bit for bit (inputs and coordinates, 900 steps).
#[test]
fn a_crane_whose_default_move_is_a_spline_has_an_fmu() {
    type G = SplineGantry;
    let start = Start::<3>::default_for::<G, 6, 1>();
    let table = variables::<G, 6, 1, 3>(&start).unwrap();
    let path = table.iter().find(|v| v.name == "path").unwrap();
    assert_eq!(path.start, f64::from(SPLINE_PATH));
    let run = api_run::<G, 6, 1, 3>(&start.spec);
    assert_eq!(run.states.len(), 901);
    steps_as::<G, 6, 1, 3>(&start, &run, |_| {});
}
