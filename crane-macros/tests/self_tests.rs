//! Two cranes in one module, `Gantry` and `GANTRY`, each with a `sample`
//! section: their generated self-tests are modules of their own (named
//! after each type as written), so the file compiles and `cargo test` runs
//! both (`__crane_self_test_Gantry::...` and `__crane_self_test_GANTRY::...`
//! beside the test below; the two once shared one lowercased name and the
//! file did not compile).
#![allow(non_camel_case_types, clippy::upper_case_acronyms)]

use crane_runtime::CraneModel;

crane_macros::crane_model! {
    /// Planar gantry crane.
    pub struct Gantry {
        params { m_t = 50.0, m_l = 200.0, J = 0.05, r = 0.1, g = 9.81 }
        robot  [s, L]
        load   [x, z]
        inputs [u1, u2]
        kinetic = 0.5*m_t*dot(s)^2 + 0.5*J/r^2*dot(L)^2 + 0.5*m_l*(dot(x)^2 + dot(z)^2);
        forces { s: u1, L: u2/r, z: -m_l*g }
        constraints { #[rope(N = L)] rope: 0.5*((x - s)^2 + z^2 - L^2) }
        sample { s = -5.0 .. 5.0, L = 1.0 .. 10.0, x = -5.0 .. 5.0, z = -10.0 .. -1.0 }
    }
}

crane_macros::crane_model! {
    /// The same gantry with a heavier load, as a second type.
    pub struct GANTRY {
        params { m_t = 50.0, m_l = 900.0, J = 0.05, r = 0.1, g = 9.81 }
        robot  [s, L]
        load   [x, z]
        inputs [u1, u2]
        kinetic = 0.5*m_t*dot(s)^2 + 0.5*J/r^2*dot(L)^2 + 0.5*m_l*(dot(x)^2 + dot(z)^2);
        forces { s: u1, L: u2/r, z: -m_l*g }
        constraints { #[rope(N = L)] rope: 0.5*((x - s)^2 + z^2 - L^2) }
        sample { s = -5.0 .. 5.0, L = 1.0 .. 10.0, x = -5.0 .. 5.0, z = -10.0 .. -1.0 }
    }
}

#[test]
fn two_cranes_named_alike_are_two_cranes() {
    assert_eq!(Gantry::default().parameter_values()[1], 200.0);
    assert_eq!(GANTRY::default().parameter_values()[1], 900.0);
    assert_eq!(<Gantry as CraneModel<4, 1, 2>>::INFO.name, "Gantry");
    assert_eq!(<GANTRY as CraneModel<4, 1, 2>>::INFO.name, "GANTRY");
}
