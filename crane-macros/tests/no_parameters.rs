//! A crane declared without `params` compiles without a warning (its
//! `set_parameter` once ended in code after a `match` whose every arm
//! returned: "unreachable expression" in the user's crate) and refuses any
//! parameter name.
#![deny(warnings)]

use crane_runtime::CraneModel;

crane_macros::crane_model! {
    #[crane(no_self_test)]
    /// A planar gantry with unit masses and the rope on a direct drive.
    pub struct Bare {
        robot [s, L] load [x, z] inputs [u1, u2]
        kinetic = 0.5*dot(s)^2 + 0.5*dot(L)^2 + 0.5*(dot(x)^2 + dot(z)^2);
        forces { s: u1, L: u2, z: -9.81 }
        constraints { #[rope(N = L)] rope: 0.5*((x - s)^2 + z^2 - L^2) }
    }
}

#[test]
fn a_crane_without_parameters_has_none_to_set() {
    let mut crane = Bare::default();
    assert!(crane.parameter_values().is_empty());
    let error = crane.set_parameter("m", 1.0).unwrap_err();
    assert_eq!(error.name, "m");
    assert_eq!(error.known, "");
}
