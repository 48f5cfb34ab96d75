//! Generated code is not affected by the names in the user's scope: the
//! planar crane of sect. 5.1 declared next to constants, functions and
//! unit structs named like every one of its parameters, coordinates,
//! inputs, minimal coordinates, ropes and constraints (and like the
//! generated code's own arguments `q`, `v`, `mu`, `t0`, `out`) compiles and
//! gives bit for bit the numbers of the same declaration in a module
//! without them.
#![allow(non_upper_case_globals, non_camel_case_types, non_snake_case, dead_code)]

use crane_runtime::nalgebra::SVector;
use crane_runtime::{CraneModel, DummyDerivatives, MinimalMap};

/// The declaration, written once for both modules.
macro_rules! navy_planar {
    () => {
        crane_macros::crane_model! {
            /// Planar US Navy crane with massless main pulley (paper, sect. 5.1).
            pub struct NavyPlanar {
                params { m_l = 100.0, J1 = 0.1, J2 = 0.1, r1 = 0.1, r2 = 0.1,
                         alpha = PI / 3.0, l = 10.0, g = 9.81 }
                robot  [L1, L2, L0, x0, z0]
                load   [x, z]
                inputs [u1, u2]
                kinetic = 0.5*J1/r1^2*dot(L1)^2 + 0.5*J2/r2^2*dot(L2)^2 + 0.5*m_l*(dot(x)^2 + dot(z)^2);
                forces { L1: u1/r1, L2: u2/r2, z: -m_l*g }
                constraints {
                    #[rope(N1 = L1)]
                    rope1: 0.5*((x0 + l*sin(alpha))^2 + (z0 + l*cos(alpha))^2 - L1^2),
                    rope0: 0.5*(x0^2 + z0^2 - L0^2),
                    #[rope(N2 = L2 - L0)]
                    hoist: 0.5*((x - x0)^2 + (z - z0)^2 - (L2 - L0)^2),
                }
                minimal [beta, gamma | theta, L] {
                    let d = l*sin(gamma - beta)/sin(gamma);
                    L1 = l*sin(beta)/sin(gamma);  L2 = d + L;  L0 = d;
                    x0 = -d*sin(alpha - beta);    z0 = -d*cos(alpha - beta);
                    x  = x0 + L*sin(theta);       z  = z0 - L*cos(theta);
                }
            }
        }
    };
}

/// A planar gantry crane whose parameters `J`, `g` and coordinate `L` are
/// common names of a user's constants, functions and types.
macro_rules! gantry {
    () => {
        crane_macros::crane_model! {
            /// Planar gantry crane: trolley, hoist winch, load on one rope.
            pub struct Gantry {
                params { m_t = 50.0, m_l = 200.0, J = 0.05, r = 0.1, g = 9.81 }
                robot  [s, L]
                load   [x, z]
                inputs [u1, u2]
                kinetic = 0.5*m_t*dot(s)^2 + 0.5*J/r^2*dot(L)^2 + 0.5*m_l*(dot(x)^2 + dot(z)^2);
                forces { s: u1, L: u2/r, z: -m_l*g }
                constraints { #[rope(N = L)] rope: 0.5*((x - s)^2 + z^2 - L^2) }
            }
        }
    };
}

mod clean {
    navy_planar!();
    gantry!();
}

/// The names of the gantry's example: a constant `J`, a function `g`, a
/// unit struct `L` (values unlike the model's, so that a capture could not
/// hide in equal numbers).
mod user {
    const J: f64 = 7.0;
    fn g() -> f64 {
        1.0
    }
    struct L;

    gantry!();
}

/// Every name of the declaration taken by an item of the user's.
mod hostile {
    const m_l: f64 = -1.0;
    const J1: f64 = -2.0;
    const J2: f64 = -3.0;
    const r1: u8 = 4;
    static r2: f64 = -5.0;
    const alpha: i32 = 6;
    const l: f64 = -7.0;
    fn g() -> f64 {
        -8.0
    }
    const L1: f64 = -9.0;
    struct L2;
    const L0: f64 = -10.0;
    fn x0() {}
    const z0: f64 = -11.0;
    struct x;
    const z: f64 = -12.0;
    const u1: f64 = -13.0;
    fn u2() {}
    const N1: f64 = -14.0;
    struct N2;
    const rope1: f64 = -15.0;
    const rope0: f64 = -16.0;
    fn hoist() {}
    const beta: f64 = -17.0;
    struct gamma;
    const theta: f64 = -18.0;
    struct L;
    const d: f64 = -19.0;
    const q: f64 = -20.0;
    const v: f64 = -21.0;
    const mu: f64 = -22.0;
    const t0: f64 = -23.0;
    struct out;
    const lambda: f64 = -24.0;
    const u: f64 = -25.0;
    const t: f64 = -26.0;
    const z_: f64 = -27.0;

    navy_planar!();
}

#[test]
fn a_gantry_beside_a_constant_j_a_function_g_and_a_struct_l_gives_the_same_numbers() {
    let (a, b) = (clean::Gantry::new(), user::Gantry::new());
    assert_eq!(a.parameter_values(), b.parameter_values());
    let q = SVector::<f64, 4>::from([0.3, 5.2, 1.1, -4.9]);
    let v = SVector::<f64, 4>::from([0.1, -0.2, 0.3, 0.4]);
    let lambda = SVector::<f64, 1>::from([-39.0]);
    assert_eq!(a.constraints(&q), b.constraints(&q));
    assert_eq!(a.constraint_jacobian(&q), b.constraint_jacobian(&q));
    assert_eq!(a.constraint_hessian(&q, &lambda), b.constraint_hessian(&q, &lambda));
    assert_eq!(a.mass_matrix::<f64>(), b.mass_matrix::<f64>());
    assert_eq!(a.forces(&q, &v), b.forces(&q, &v));
    assert_eq!(a.input_matrix(&q), b.input_matrix(&q));
}

#[test]
fn a_crane_beside_items_of_its_names_gives_the_same_numbers() {
    let (a, b) = (clean::NavyPlanar::new(), hostile::NavyPlanar::new());
    assert_eq!(a.parameter_values(), b.parameter_values());
    let q = SVector::<f64, 7>::from([8.1, 13.2, 4.9, 0.7, -4.6, 1.3, -11.8]);
    let v = SVector::<f64, 7>::from([0.1, -0.2, 0.3, 0.4, -0.5, 0.6, 0.7]);
    let lambda = SVector::<f64, 3>::from([0.3, -1.1, 2.0]);
    assert_eq!(a.constraints(&q), b.constraints(&q));
    assert_eq!(a.constraint_jacobian(&q), b.constraint_jacobian(&q));
    assert_eq!(a.constraint_hessian(&q, &lambda), b.constraint_hessian(&q, &lambda));
    assert_eq!(a.mass_matrix::<f64>(), b.mass_matrix::<f64>());
    assert_eq!(a.forces(&q, &v), b.forces(&q, &v));
    assert_eq!(a.input_matrix(&q), b.input_matrix(&q));
    assert_eq!(a.force_jacobians(&q, &v), b.force_jacobians(&q, &v));
    let inputs = SVector::<f64, 2>::from([40.0, -3.0]);
    assert_eq!(a.input_jacobian(&q, &inputs), b.input_jacobian(&q, &inputs));
    let (mut ropes_a, mut ropes_b) = ([0.0; 2], [0.0; 2]);
    a.rope_lengths(&q, &mut ropes_a);
    b.rope_lengths(&q, &mut ropes_b);
    assert_eq!(ropes_a, ropes_b);
    let mu = SVector::<f64, 4>::from([0.9, 1.7, 0.2, 6.0]);
    let mu_dot = SVector::<f64, 4>::from([0.01, -0.02, 0.3, -0.1]);
    assert_eq!(a.phi(&mu), b.phi(&mu));
    assert_eq!(a.null_space(&mu), b.null_space(&mu));
    assert_eq!(a.null_space_rate(&mu, &mu_dot), b.null_space_rate(&mu, &mu_dot));
    let gamma = [
        SVector::from([1.3, -11.8]),
        SVector::from([0.2, 0.1]),
        SVector::from([-0.3, 0.05]),
        SVector::from([0.4, -0.2]),
        SVector::from([0.1, 0.3]),
    ];
    let jets = SVector::<f64, 26>::from_fn(|i, _| 0.5 + 0.1 * i as f64);
    assert_eq!(
        a.dummy_derivative_system(&gamma, &jets),
        b.dummy_derivative_system(&gamma, &jets)
    );
}
