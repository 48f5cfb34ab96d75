//! Nothing allocates after initialisation: a counting global allocator sees
//! no allocation in the `do_step` and `get_real` calls of a whole move, for
//! the built-in path and the external target, with one and with several
//! internal steps per communication step. One test function, so that no
//! other test allocates while one counts.

use crane_fmi::instance::{Component, Instance};
use crane_fmi::start::Start;
use crane_fmi::variables::{Role, variables};
use crane_models::navy_planar;
use crane_runtime::Trajectory;
use crane_tests::counting::{Counting, allocations_during, assert_counter_works};

#[global_allocator]
static GLOBAL: Counting = Counting;

#[test]
fn do_step_does_not_allocate() {
    type D = navy_planar::Description;
    let table = variables::<D, 7, 3, 2>(&Start::default_for::<D, 7, 3>()).unwrap();
    let vr = |role| {
        table
            .iter()
            .find(|v| v.role == role && !v.integer)
            .unwrap()
            .value_reference
    };
    let refs = [
        vr(Role::Input(0)),
        vr(Role::Input(1)),
        vr(Role::Coordinate(5)),
        vr(Role::Tension(1)),
    ];
    let targets: Vec<u32> = (0..2)
        .flat_map(|k| (0..3).map(move |o| (k, o)))
        .map(|(k, o)| vr(Role::Target(k, o)))
        .collect();
    let path = navy_planar::PaperCase::maneuver().unwrap().path().clone();
    for (path_kind, h) in [(0, 0.01), (0, 0.05), (3, 0.01), (3, 0.04)] {
        let mut fmu = Instance::<D, 7, 3, 2>::new().unwrap();
        fmu.setup_experiment(0.0).unwrap();
        fmu.enter_initialization_mode().unwrap();
        fmu.set_integer(&[1], &[path_kind]).unwrap();
        fmu.exit_initialization_mode().unwrap();
        let steps = (4.0f64 / h).round() as usize;
        let mut out = [0.0; 4];
        let mut values = [0.0; 6];
        let (allocations, ()) = allocations_during(|| {
            for i in 0..steps {
                let t = i as f64 * h;
                if path_kind == 3 {
                    // the built-in move, handed over as the external target
                    for k in 0..2 {
                        for o in 0..3 {
                            values[3 * k + o] = path.derivative(t + h, o)[k];
                        }
                    }
                    fmu.set_real(&targets, &values).ok();
                }
                let status = fmu.do_step(t, h);
                let read = fmu.get_real(&refs, &mut out);
                assert!(status.is_ok() && read.is_ok());
            }
        });
        assert_eq!(
            allocations, 0,
            "path {path_kind}, h = {h}: {allocations} allocations in {steps} steps"
        );
    }
    assert_counter_works();
}
