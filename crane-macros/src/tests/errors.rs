//! Every kind of DSL mistake: `expand` must not panic, must report the
//! message below, and must still emit the stub struct.

use super::{MINIMAL, NAVY, navy_minimal_source, tokens};
use crate::expand;

/// The messages of the `compile_error!`s in an expansion, and whether the
/// stub struct is there.
fn expand_errors(source: &str) -> (Vec<String>, bool) {
    let output = expand(tokens(source));
    let file: syn::File = match syn::parse2(output.clone()) {
        Ok(file) => file,
        Err(error) => panic!("expansion does not parse: {error}\n{output}"),
    };
    let mut messages = Vec::new();
    let mut stub = false;
    for item in file.items {
        match item {
            syn::Item::Macro(m) if m.mac.path.segments.last().is_some_and(|s| s.ident == "compile_error") => {
                let message: syn::LitStr = m.mac.parse_body().expect("a string literal");
                messages.push(message.value());
            }
            syn::Item::Struct(s) if matches!(s.fields, syn::Fields::Unit) => stub = true,
            _ => {}
        }
    }
    (messages, stub)
}

/// The planar crane with `from` replaced by `to` (which must occur).
fn navy_with(from: &str, to: &str) -> String {
    assert!(NAVY.contains(from), "test bug: `{from}` is not in the declaration");
    NAVY.replacen(from, to, 1)
}

/// The planar crane with its `minimal` block, with `from` replaced by `to`
/// in the block (where it must occur).
fn minimal_with(from: &str, to: &str) -> String {
    assert!(MINIMAL.contains(from), "test bug: `{from}` is not in the minimal block");
    navy_minimal_source().replacen(from, to, 1)
}

/// Asserts that breaking the planar crane gives exactly `expected`.
#[track_caller]
fn assert_errors(source: &str, expected: &[&str]) {
    let (messages, stub) = expand_errors(source);
    assert_eq!(messages, expected);
    assert!(stub, "no stub struct after the errors");
}

#[test]
fn the_planar_crane_has_no_errors() {
    let (messages, stub) = expand_errors(NAVY);
    assert!(messages.is_empty(), "{messages:?}");
    assert!(!stub);
}

#[test]
fn the_planar_crane_with_its_minimal_block_has_no_errors() {
    let (messages, stub) = expand_errors(&navy_minimal_source());
    assert!(messages.is_empty(), "{messages:?}");
    assert!(!stub);
}

#[test]
fn unknown_symbol() {
    assert_errors(
        &navy_with("rope0: 0.5*(x0^2", "rope0: 0.5*(xx^2"),
        &[
            "unknown symbol `xx`; did you mean `x0`? allowed in `constraints`: parameters (m_l, J1, J2, r1, r2, alpha, l, g), \
           coordinates (L1, L2, L0, x0, z0, x, z), PI",
        ],
    );
    assert_errors(
        &navy_with("z: -m_l*g", "z: -m*g"),
        &[
            "unknown symbol `m`; allowed in `forces`: parameters (m_l, J1, J2, r1, r2, alpha, l, g), \
           coordinates (L1, L2, L0, x0, z0, x, z), velocities dot(coordinate), inputs (u1, u2), PI",
        ],
    );
    assert_errors(
        &navy_with("dot(L2)^2", "dot(L3)^2"),
        &["unknown coordinate `L3` in dot(); the coordinates are: L1, L2, L0, x0, z0, x, z"],
    );
    assert_errors(
        &navy_with("z: -m_l*g", "z: -m_l*g*N1"),
        &[
            "`N1` is a rope tension and has no value in expressions; allowed in `forces`: parameters (m_l, J1, J2, \
           r1, r2, alpha, l, g), coordinates (L1, L2, L0, x0, z0, x, z), velocities dot(coordinate), inputs (u1, u2), PI",
        ],
    );
}

#[test]
fn duplicate_names() {
    assert_errors(
        &navy_with("g = 9.81", "g = 9.81, x = 1.0"),
        &["duplicate name `x`: already declared as a parameter"],
    );
    assert_errors(
        &navy_with("inputs [u1, u2]", "inputs [u1, L0]"),
        &["duplicate name `L0`: already declared as a robot coordinate"],
    );
    assert_errors(
        &navy_with("rope0:", "rope1:"),
        &["duplicate name `rope1`: already declared as a constraint"],
    );
    assert_errors(
        &navy_with("#[rope(N2 = L2 - L0)]", "#[rope(N1 = L2 - L0)]"),
        &["duplicate name `N1`: already declared as a rope tension"],
    );
    assert_errors(
        &navy_with("#[rope(N1 = L1)]", "#[rope(g = L1)]"),
        &["duplicate name `g`: already declared as a parameter"],
    );
    assert_errors(
        &navy_with("g = 9.81", "g = 9.81, PI = 3.0"),
        &["`PI` is reserved (the constant pi) and cannot be declared"],
    );
    // a raw identifier is the same name: `r#x` and `x` would be one local
    // (a parameter `r#x` beside the load's `x` once gave u1 = -45.8 N
    // where the plainly named crane gives 8.17 N)
    assert_errors(
        &navy_with("g = 9.81", "g = 9.81, r#x = 1.0"),
        &["duplicate name `x`: already declared as a parameter"],
    );
}

#[test]
fn kinetic_energy_must_be_a_constant_quadratic_form() {
    assert_errors(
        &navy_with("0.5*J2/r2^2*dot(L2)^2", "0.5*J2/r2^2*L0*dot(L2)^2"),
        &[
            "configuration-dependent mass matrix: the method needs a constant M, but the coefficient of this term \
           depends on the coordinate `L0`",
        ],
    );
    assert_errors(
        &navy_with("0.5*J2/r2^2*dot(L2)^2", "0.5*J2/r2^2*dot(L2)^3"),
        &[
            "not a quadratic form in the velocities: this term is cubic or of higher degree in the velocities (or not \
           polynomial in them)",
        ],
    );
    assert_errors(
        &navy_with("0.5*J2/r2^2*dot(L2)^2", "J2*dot(L2)"),
        &["not a quadratic form in the velocities: this term is linear in the velocity `dot(L2)`"],
    );
    assert_errors(
        &navy_with("0.5*J2/r2^2*dot(L2)^2", "0.5*J2*(dot(L2) + 1)^2"),
        &["not a quadratic form in the velocities: this term has a part without velocities"],
    );
    assert_errors(
        &navy_with("0.5*J2/r2^2*dot(L2)^2", "m_l*g*z"),
        &[
            "not a quadratic form in the velocities: this term contains no velocity (a potential belongs in \
           `forces`, as a generalized force)",
        ],
    );
    assert_errors(
        &navy_with("0.5*J2/r2^2*dot(L2)^2", "J2*cos(dot(L2))"),
        &[
            "not a quadratic form in the velocities: this term is cubic or of higher degree in the velocities (or not \
           polynomial in them)",
        ],
    );
    // one error per offending term
    assert_errors(
        &navy_with("0.5*J2/r2^2*dot(L2)^2", "x*dot(L2)^2 + dot(x0)"),
        &[
            "configuration-dependent mass matrix: the method needs a constant M, but the coefficient of this term \
             depends on the coordinate `x`",
            "not a quadratic form in the velocities: this term is linear in the velocity `dot(x0)`",
        ],
    );
}

#[test]
fn forces_must_be_linear_in_the_inputs() {
    assert_errors(
        &navy_with("L1: u1/r1", "L1: u1^2/r1"),
        &["force on `L1` is not linear in the inputs: B^T must not depend on u (eq. 11c)"],
    );
    assert_errors(
        &navy_with("L1: u1/r1", "L1: u1*u2/r1"),
        &["force on `L1` is not linear in the inputs: B^T must not depend on u (eq. 11c)"],
    );
    assert_errors(
        &navy_with("L1: u1/r1", "L1: sin(u1)"),
        &["force on `L1` is not linear in the inputs: B^T must not depend on u (eq. 11c)"],
    );
    assert_errors(
        &navy_with("L1: u1/r1", "L1: u1*dot(L1)"),
        &[
            "force on `L1`: the coefficient of the input `u1` depends on the velocity `dot(L1)`; B^T may depend only \
           on the coordinates (eq. 11c)",
        ],
    );
    assert_errors(
        &navy_with("z: -m_l*g", "z: -m_l*g + u2"),
        &[
            "the input `u2` acts on the load coordinate `z`: inputs may act only on robot coordinates \
           (B^T = [B1^T; 0], eq. 11c)",
        ],
    );
    assert_errors(
        &navy_with("L2: u2/r2", "L2: 1/r2"),
        &["input `u2` appears in no force: B^T would have a zero column"],
    );
}

#[test]
fn velocities_and_inputs_where_not_allowed() {
    assert_errors(
        &navy_with("rope0: 0.5*(x0^2", "rope0: 0.5*(dot(x0)^2"),
        &["velocity `dot(x0)` is not allowed in `constraints`: velocities may appear only in `kinetic` and `forces`"],
    );
    assert_errors(
        &navy_with("rope0: 0.5*(x0^2", "rope0: 0.5*(u1^2"),
        &["input `u1` is not allowed in `constraints`: inputs may appear only in `forces`"],
    );
    assert_errors(
        &navy_with("0.5*m_l*(dot(x)^2", "0.5*m_l*u1*(dot(x)^2"),
        &["input `u1` is not allowed in `kinetic`: inputs may appear only in `forces`"],
    );
    assert_errors(
        &navy_with("#[rope(N1 = L1)]", "#[rope(N1 = dot(L1))]"),
        &["velocity `dot(L1)` is not allowed in a rope length: velocities may appear only in `kinetic` and `forces`"],
    );
    assert_errors(
        &navy_with("dot(L1)^2", "dot(u1)^2"),
        &["dot() takes a coordinate, but `u1` is an input"],
    );
}

#[test]
fn counts() {
    assert_errors(
        &navy_with("inputs [u1, u2]", "inputs [u1]").replace("L2: u2/r2", "L2: 0"),
        &[
            "number of inputs (1) must equal the number of load coordinates (2): each input drives one prescribed \
           output (eq. 1c)",
        ],
    );
    let too_many = navy_with(
        "rope0: 0.5*(x0^2 + z0^2 - L0^2),",
        "rope0: 0.5*(x0^2 + z0^2 - L0^2), c4: x, c5: z, c6: L2, c7: L0,",
    );
    assert_errors(
        &too_many,
        &[
            "number of constraints (7) must be below the number of coordinates (7): the crane needs a degree of \
           freedom (m < n)",
        ],
    );
}

#[test]
fn forces_keyed_by_unknown_or_repeated_coordinates() {
    assert_errors(
        &navy_with("z: -m_l*g", "zz: -m_l*g"),
        &["unknown coordinate `zz` in `forces`; the coordinates are: L1, L2, L0, x0, z0, x, z"],
    );
    assert_errors(
        &navy_with("z: -m_l*g", "m_l: -m_l*g"),
        &["`m_l` is a parameter, not a coordinate: `forces` maps coordinates to generalized forces"],
    );
    assert_errors(
        &navy_with("z: -m_l*g", "z: -m_l*g, z: 1"),
        &["duplicate force on `z`: write the sum as one expression"],
    );
}

#[test]
fn unsupported_functions_and_operators() {
    assert_errors(
        &navy_with("l*sin(alpha)", "l*sinh(alpha)"),
        &[
            "unsupported function `sinh` (write `0.5*(exp(x) - exp(-x))`); supported: sin, cos, tan, sqrt, exp, ln, \
             atan2(y, x), and dot(coordinate) for a velocity",
        ],
    );
    assert_errors(
        &navy_with("rope0: 0.5*(x0^2", "rope0: 0.5*(x0%2"),
        &["unsupported operator `%`; supported: + - * / ^ (power) and parentheses"],
    );
    assert_errors(
        &navy_with("rope0: 0.5*(x0^2", "rope0: 0.5*(x0**2"),
        &["unexpected `*`: write powers as `x^n`"],
    );
    assert_errors(
        &navy_with("rope0: 0.5*(x0^2", "rope0: 0.5*(x0^z0"),
        &["exponent must be a constant number; for a variable exponent write exp(y * ln(x))"],
    );
    assert_errors(
        &navy_with("l = 10.0", "l = 10.0f32"),
        &["numeric literals take no suffix: every number is an f64"],
    );
}

#[test]
fn sections() {
    assert_errors(
        &navy_with("robot  [L1, L2, L0, x0, z0]", "robot []"),
        &["empty section `robot`: declare at least one name"],
    );
    let without_kinetic = navy_with(
        "kinetic = 0.5*J1/r1^2*dot(L1)^2 + 0.5*J2/r2^2*dot(L2)^2 + 0.5*m_l*(dot(x)^2 + dot(z)^2);",
        "",
    );
    assert_errors(
        &without_kinetic,
        &["missing section `kinetic`: declare it, e.g. `kinetic = 0.5*m*(dot(x)^2 + dot(z)^2);`"],
    );
    assert_errors(
        &navy_with("inputs [u1, u2]", "inputs [u1, u2] outputs [x, z]"),
        &[
            "unknown section `outputs`; expected one of: params, robot, load, inputs, kinetic, forces, constraints, minimal, sample; the outputs are the `load` coordinates",
        ],
    );
    assert_errors(
        &navy_with("inputs [u1, u2]", "inputs [u1, u2] inputs [u3]"),
        &["duplicate section `inputs`"],
    );
    assert_errors(
        &navy_with("forces { L1: u1/r1, L2: u2/r2, z: -m_l*g }", "forces { }"),
        &["empty section `forces`: every input must act on some coordinate"],
    );
    assert_errors(
        &navy_with("(dot(x)^2 + dot(z)^2);", "(dot(x)^2 + dot(z)^2)"),
        &["expected `;` after the kinetic energy"],
    );
    assert_errors(
        &navy_with("robot  [L1, L2, L0, x0, z0]", "robot  {L1, L2, L0, x0, z0}"),
        &["expected `[ ... ]` after `robot`"],
    );
    assert_errors(
        &navy_with("inputs [u1, u2]", "inputs [u1, u2] minimal [beta, gamma | theta, L]"),
        &["expected `{ ... }` with the map `q = phi(mu)` after `minimal [...]`"],
    );
}

#[test]
fn a_pendulum_without_constraints_section() {
    let source = r#"
        struct Pendulum {
            robot [L] load [x] inputs [u]
            kinetic = 0.5*dot(x)^2;
            forces { L: u }
        }
    "#;
    assert_errors(
        source,
        &["missing section `constraints`: declare it, e.g. `constraints { rope: 0.5*(x^2 + z^2 - L^2) }`"],
    );
}

#[test]
fn parameter_defaults_must_be_constant() {
    assert_errors(
        &navy_with("l = 10.0", "l = 2*alpha"),
        &[
            "parameter defaults must be constant (numbers, PI and functions of them); `alpha` is a parameter, set \
           on its own at run time, so a default cannot follow it: write the number, or use `alpha` where the \
           derived value is needed (in `kinetic`, `forces` or `constraints`)",
        ],
    );
    assert_errors(
        &navy_with("l = 10.0", "l = 2*L1"),
        &["parameter defaults must be constant (numbers, PI and functions of them); `L1` is a robot coordinate"],
    );
}

#[test]
fn a_constraint_must_depend_on_a_coordinate() {
    assert_errors(
        &navy_with(
            "rope0: 0.5*(x0^2 + z0^2 - L0^2),",
            "rope0: 0.5*(x0^2 + z0^2 - L0^2), c4: l - 1,",
        ),
        &["constraint `c4` does not depend on any coordinate"],
    );
}

#[test]
fn all_errors_are_reported_at_once() {
    let source = navy_with("rope0: 0.5*(x0^2", "rope0: 0.5*(xx^2").replace("L1: u1/r1", "L1: u1^2/r1");
    let (messages, stub) = expand_errors(&source);
    assert_eq!(messages.len(), 2, "{messages:?}");
    assert!(messages[0].starts_with("force on `L1` is not linear in the inputs"));
    assert!(messages[1].starts_with("unknown symbol `xx`"));
    assert!(stub);

    // and parse errors in different sections, too
    let source = navy_with("l*sin(alpha)", "l*sinh(alpha)").replace("z: -m_l*g", "z: -m_l % g");
    let (messages, _) = expand_errors(&source);
    assert_eq!(messages.len(), 2, "{messages:?}");
}

#[test]
fn the_header_must_be_a_struct() {
    let (messages, stub) = expand_errors("pub enum NavyPlanar { }");
    assert_eq!(messages, ["expected `struct`"]);
    assert!(!stub, "no name, no stub");
}

#[test]
fn garbage_never_panics() {
    let inputs = [
        "",
        "struct",
        "pub struct A",
        "struct A { }",
        "struct A { robot }",
        "struct A { kinetic = ; }",
        "struct A { kinetic = dot(); }",
        "struct A { params { = } }",
        "struct A { params { a = , b = 1,, } }",
        "struct A { constraints { #[rope] c: x } }",
        "struct A { constraints { #[rope(N)] c: x } }",
        "struct A { constraints { #[serde] c: x } }",
        "struct A { forces { : 1 } }",
        "struct A { minimal [ ] { } }",
        "struct A { minimal [a | b] }",
        "struct A { 42 robot [x] }",
        "struct A { robot [x] load [y] inputs [u] kinetic = dot(x)^2 + dot(y)^2; forces { x: u }          constraints { c: x^2 + y^2 - 1e400 } }",
        "struct A { robot [x] load [y] inputs [u] kinetic = 1/0*dot(x)^2; forces { x: u } constraints { c: x - y } }",
    ];
    for input in inputs {
        let (messages, _) = expand_errors(input);
        assert!(!messages.is_empty(), "no error for `{input}`");
    }
}

// --- the `minimal` block

#[test]
fn minimal_split() {
    assert_errors(
        &minimal_with("[beta, gamma | theta, L]", "[beta, gamma, theta, L]"),
        &[
            "missing `|` between mu1 and mu2: write `minimal [mu1, ... | mu2, ...]`, with one mu2 per load \
             coordinate (chosen so that D2 phi_x is regular, eq. 12)",
        ],
    );
    assert_errors(
        &minimal_with("[beta, gamma | theta, L]", "[beta | gamma | theta, L]"),
        &[
            "only one `|` is allowed: write `minimal [mu1, ... | mu2, ...]`, with one mu2 per load coordinate \
             (chosen so that D2 phi_x is regular, eq. 12)",
        ],
    );
    assert_errors(
        &minimal_with("[beta, gamma | theta, L]", "[beta, gamma, theta | L]"),
        &[
            "mu2 (after `|`) has 1 entry, but there are 2 load coordinates (x, z): mu2 needs one entry per load \
             coordinate, so that D2 phi_x is square (eq. 12)",
        ],
    );
}

#[test]
fn minimal_count_is_the_degrees_of_freedom() {
    assert_errors(
        &minimal_with("[beta, gamma | theta, L]", "[beta, gamma, kappa | theta, L]"),
        &[
            "`minimal` declares 5 minimal coordinates (beta, gamma, kappa, theta, L), but the crane has \
             f = n - m = 7 - 3 = 4 degrees of freedom",
        ],
    );
}

#[test]
fn minimal_coordinates_need_names_of_their_own() {
    // `g` is the gravity parameter
    let source = minimal_with("[beta, gamma | theta, L]", "[beta, gamma | g, L]")
        .replace("sin(theta)", "sin(g)")
        .replace("cos(theta)", "cos(g)");
    assert_errors(
        &source,
        &["duplicate name `g`: already declared as a parameter; minimal coordinates need names of their own"],
    );
    let source = minimal_with("[beta, gamma | theta, L]", "[beta, beta | theta, L]").replace("gamma", "beta");
    assert_errors(
        &source,
        &[
            "duplicate name `beta`: already declared as a minimal coordinate; minimal coordinates need names of \
             their own",
        ],
    );
    // `z` is a load coordinate
    let source = minimal_with("[beta, gamma | theta, L]", "[beta, gamma | theta, z]")
        .replace("d + L;", "d + z;")
        .replace("L*sin(theta)", "z*sin(theta)")
        .replace("L*cos(theta)", "z*cos(theta)");
    assert_errors(
        &source,
        &[
            "duplicate name `z`: already declared as a load coordinate; minimal coordinates need names of their \
             own",
        ],
    );
}

#[test]
fn minimal_lets_shadow_nothing() {
    assert_errors(
        &minimal_with("L0 = d;", "L0 = d; let x0 = 1;"),
        &["`let x0` would shadow `x0`, which is a robot coordinate: choose another name for the abbreviation"],
    );
    assert_errors(
        &minimal_with("L0 = d;", "L0 = d; let d = 2*l;"),
        &["`let d` would shadow `d`, which is a `let` above: choose another name for the abbreviation"],
    );
    assert_errors(
        &minimal_with("L0 = d;", "L0 = d; let theta = 0;"),
        &["`let theta` would shadow `theta`, which is a minimal coordinate: choose another name for the abbreviation"],
    );
    assert_errors(
        &minimal_with("L0 = d;", "L0 = d; let sqrt = 2;"),
        &["`let sqrt` would shadow `sqrt`, which is reserved (a function): choose another name for the abbreviation"],
    );
}

#[test]
fn minimal_maps_every_coordinate_once() {
    assert_errors(
        &minimal_with("z  = z0 - L*cos(theta);", ""),
        &[
            "coordinate `z` has no mapping in `minimal`: every redundant coordinate needs one, \
             `z = <expression in the minimal coordinates>;`",
        ],
    );
    assert_errors(
        &minimal_with("L0 = d;", "L0 = d; L0 = l - d;"),
        &["coordinate `L0` is mapped twice: the map gives each coordinate one expression"],
    );
    assert_errors(
        &minimal_with("L0 = d;", "L0 = d; beta = 1;"),
        &[
            "`beta` is a minimal coordinate, not a redundant one: the left-hand sides of `minimal` are the \
             redundant coordinates (L1, L2, L0, x0, z0, x, z); write `let name = ...;` for an abbreviation",
        ],
    );
    assert_errors(
        &minimal_with("L0 = d;", "L0 = d; alpha = 1;"),
        &[
            "`alpha` is a parameter, not a coordinate: the left-hand sides of `minimal` are the redundant \
             coordinates (L1, L2, L0, x0, z0, x, z); write `let name = ...;` for an abbreviation",
        ],
    );
    assert_errors(
        &minimal_with("L0 = d;", "L0 = d; d = 1;"),
        &[
            "`d` is a `let` abbreviation, not a coordinate: the left-hand sides of `minimal` are the redundant \
             coordinates (L1, L2, L0, x0, z0, x, z); write `let name = ...;` for an abbreviation",
        ],
    );
    assert_errors(
        &minimal_with("L0 = d;", "L00 = d;"),
        &[
            "unknown coordinate `L00` in `minimal`; the coordinates are: L1, L2, L0, x0, z0, x, z",
            "coordinate `L0` has no mapping in `minimal`: every redundant coordinate needs one, \
             `L0 = <expression in the minimal coordinates>;`",
        ],
    );
}

#[test]
fn minimal_names_on_the_right() {
    assert_errors(
        &minimal_with("L1 = l*sin(beta)/sin(gamma)", "L1 = l*sin(beta)/sin(gama)"),
        &[
            "unknown symbol `gama`; allowed in `minimal`: parameters (m_l, J1, J2, r1, r2, alpha, l, g), minimal \
             coordinates (beta, gamma, theta, L), `let` names above (d), coordinates mapped above (none yet), PI",
        ],
    );
    assert_errors(
        &minimal_with("L0 = d;", "L0 = d*u1;"),
        &["input `u1` is not allowed in `minimal`: inputs may appear only in `forces`"],
    );
    assert_errors(
        &minimal_with("L0 = d;", "L0 = d + dot(beta);"),
        &[
            "velocity `dot(beta)` is not allowed in `minimal`: the map q = phi(mu) depends on the minimal \
             coordinates only, and its derivatives P and P' are generated (eqs. 8-9)",
        ],
    );
    assert_errors(
        &minimal_with("L0 = d;", "L0 = d*N1;"),
        &[
            "`N1` is a rope tension and has no value in expressions; allowed in `minimal`: parameters (m_l, J1, J2, \
             r1, r2, alpha, l, g), minimal coordinates (beta, gamma, theta, L), `let` names above (d), coordinates \
             mapped above (L1, L2), PI",
        ],
    );
}

#[test]
fn minimal_reads_top_to_bottom() {
    // mapped coordinates stand for their mapping, once mapped
    assert_errors(
        &minimal_with("L2 = d + L;", "L2 = d + L + 0*x0;"),
        &[
            "coordinate `x0` is used above its mapping: the block reads top to bottom, so move `x0 = ...;` above \
             this line (this also rules out circular definitions)",
        ],
    );
    assert_errors(
        &minimal_with("L0 = d;", "L0 = d + 0*L0;"),
        &["`L0 = ...` uses `L0` itself: a coordinate cannot be defined in terms of itself"],
    );
    assert_errors(
        &minimal_with("L0 = d;", "L0 = d; let e = 2*e;"),
        &["`let e = ...` uses `e` itself: an abbreviation cannot be defined in terms of itself"],
    );
    assert_errors(
        &minimal_with("L0 = d;", "L0 = e; let e = d;"),
        &["`e` is used above its `let`: the block reads top to bottom, so move `let e = ...;` above this line"],
    );
    assert_errors(
        &minimal_with(
            "let d = l*sin(gamma - beta)/sin(gamma);",
            "let d = l*sin(gamma - beta)/sin(gamma) + 0*L0;",
        ),
        &[
            "coordinate `L0` is used above its mapping: the block reads top to bottom, so move `L0 = ...;` above \
             this line (this also rules out circular definitions)",
        ],
    );
}

#[test]
fn minimal_coordinates_must_all_be_used() {
    let source = minimal_with("x  = x0 + L*sin(theta);", "x  = x0;").replace("z0 - L*cos(theta)", "z0 - L");
    assert_errors(
        &source,
        &["minimal coordinate `theta` appears in no mapping: P = D phi (eq. 8) would have a zero column"],
    );
}

#[test]
fn minimal_garbage_never_panics() {
    let blocks = [
        "minimal [|] { }",
        "minimal [ | ] { x = 1; }",
        "minimal [a, | b] { }",
        "minimal [a | b,] { let = 1; }",
        "minimal [1 | b] { }",
        "minimal [a | b] { let a; }",
        "minimal [a | b] { x = ; }",
        "minimal [a | b] { x == 1; }",
        "minimal [a | b] { ;; }",
        "minimal [a | b] { let c = c; }",
        "minimal [a | b] { x = x; }",
    ];
    for block in blocks {
        let source = format!(
            "struct A {{ robot [p] load [x] inputs [u] kinetic = dot(x)^2; forces {{ p: u }} \
             constraints {{ c: x - p }} {block} }}"
        );
        let (messages, _) = expand_errors(&source);
        assert!(!messages.is_empty(), "no error for `{block}`");
    }
}

/// The planar crane with a `sample` section appended.
fn navy_with_sample(sample: &str) -> String {
    let end = NAVY.trim_end().len() - 1;
    let (head, tail) = NAVY.split_at(NAVY[..end].trim_end().len());
    format!("{head}\n{sample}\n{tail}")
}

const FULL_SAMPLE: &str = "L1 = 1.0 .. 20.0, L2 = 1.0 .. 20.0, L0 = 1.0 .. 20.0, x0 = -15.0 .. 15.0, \
                           z0 = -15.0 .. 0.0, x = -15.0 .. 15.0, z = -20.0 .. 0.0";

#[test]
fn sample_section_generates_a_self_test() {
    let source = navy_with_sample(&format!("sample {{ {FULL_SAMPLE} }}"));
    let (messages, _) = expand_errors(&source);
    assert!(messages.is_empty(), "{messages:?}");
    let output = expand(super::tokens(&source)).to_string();
    assert!(output.contains("__crane_self_test_NavyPlanar"), "no self-test module");
    assert!(output.contains("derivative_self_test"));
    // opting out removes it
    let quiet = source.replacen("pub struct", "#[crane(no_self_test)] pub struct", 1);
    let output = expand(super::tokens(&quiet)).to_string();
    assert!(!output.contains("__crane_self_test"), "self-test despite no_self_test");
}

#[test]
fn sample_section_errors() {
    assert_errors(
        &navy_with_sample("sample { L1 = 1.0 .. 20.0 }"),
        &[
            "`sample` needs a range for every coordinate; missing: L2, L0, x0, z0, x, z (write e.g. `L2 = -10.0 .. 10.0`)",
        ],
    );
    assert_errors(
        &navy_with_sample(&format!("sample {{ {FULL_SAMPLE}, m_l = 1.0 .. 2.0 }}")),
        &["`m_l` in `sample` is not a coordinate: give a range for each coordinate, e.g. `L1 = 1.0 .. 10.0`"],
    );
    assert_errors(
        &navy_with_sample(&format!("sample {{ {FULL_SAMPLE}, x = 0.0 .. 1.0 }}")),
        &["duplicate range for `x` in `sample`"],
    );
    assert_errors(
        &navy_with_sample("sample { L1 = 1.0 }"),
        &["expected a range `L1 = low .. high` (constant bounds)"],
    );
    let (messages, _) = expand_errors(&navy_with_sample(&format!(
        "sample {{ {FULL_SAMPLE}, L1 = l .. 20.0 }}"
    )));
    assert!(!messages.is_empty(), "a non-constant bound must be an error");
    assert_errors(
        &navy_with_sample(&format!("sample {{ {FULL_SAMPLE} }}")).replacen(
            "pub struct",
            "#[crane(self_check)] pub struct",
            1,
        ),
        &[
            "unknown `crane` option: expected `runtime = path::to::crane_runtime`, `no_self_test` or `no_dummy_derivatives`",
        ],
    );
}

/// Both inputs on one winch: `u1` and `u2` appear only in the dynamics of
/// `L1`, so no load path fixes them (and nothing drives `L2`): a compile
/// error naming those unknowns and equations, not a crane whose every run
/// fails.
#[test]
fn a_structurally_singular_crane_names_its_unknowns_and_equations() {
    let source = navy_with("forces { L1: u1/r1, L2: u2/r2,", "forces { L1: u1/r1 + u2/r2,");
    let (messages, stub) = expand_errors(&source);
    assert_eq!(
        messages,
        [
            "structurally singular: no load path determines the coordinates, multipliers and inputs, because `u1`, `u2` \
          (2 unknowns) appear only in the dynamics of `L1` (1 equation); each input must drive a coordinate of its own \
          that the load path reaches through the constraints"
        ]
    );
    assert!(stub);
}

/// A rope's tension is its constraint's force along its length, so the
/// constraint must depend on the length, and the length on a coordinate or
/// parameter.
#[test]
fn a_rope_constraint_depends_on_its_length() {
    assert_errors(
        &navy_with("#[rope(N1 = L1)]", "#[rope(N1 = L0)]"),
        &[
            "constraint `rope1` does not depend on the length `L0` of rope `N1`, so it exerts no force along the \
           rope: a rope's constraint relates its length to the distance between its ends, e.g. `0.5*((x - s)^2 + \
           z^2 - L^2)`; for a constraint that is no rope, remove `#[rope(...)]`",
        ],
    );
    assert_errors(
        &navy_with("#[rope(N1 = L1)]", "#[rope(N1 = 2.0)]"),
        &[
            "the length `2.0` of rope `N1` is a number: a rope's length is a coordinate (a winch's rope), a \
           parameter (a sling) or an expression of them, so that its tension, the constraint's force along the \
           length, is defined",
        ],
    );
}

/// A chain of `links` fixed-length links below a hoist rope: the inputs
/// need the path's derivative of order `2 links + 4`.
fn chain(links: usize) -> String {
    let positions: Vec<(String, String)> = (1..=links)
        .map(|i| (format!("x{i}"), format!("z{i}")))
        .chain([("x".into(), "z".into())])
        .collect();
    let robot: Vec<String> = positions[..links]
        .iter()
        .flat_map(|(x, z)| [x.clone(), z.clone()])
        .collect();
    let masses: Vec<String> = (0..=links).map(|i| format!("m{i} = {}.0", 10 + i)).collect();
    let kinetic: Vec<String> = positions
        .iter()
        .enumerate()
        .map(|(i, (x, z))| format!("0.5*m{i}*(dot({x})^2 + dot({z})^2)"))
        .collect();
    let weights: Vec<String> = positions
        .iter()
        .enumerate()
        .map(|(i, (_, z))| format!("{z}: -m{i}*g"))
        .collect();
    let mut constraints = vec![format!("#[rope(N0 = L)] hoist: 0.5*((x1 - s)^2 + z1^2 - L^2)")];
    for i in 1..=links {
        let ((x0, z0), (x1, z1)) = (&positions[i - 1], &positions[i]);
        constraints.push(format!(
            "#[rope(N{i} = l)] link{i}: 0.5*(({x1} - {x0})^2 + ({z1} - {z0})^2 - l^2)"
        ));
    }
    format!(
        "#[crane(no_self_test)] pub struct Chain {{ params {{ m_t = 50.0, J = 0.05, r = 0.1, l = 1.0, g = 9.81, {} }} \
         robot [s, L, {}] load [x, z] inputs [u1, u2] \
         kinetic = 0.5*m_t*dot(s)^2 + 0.5*J/r^2*dot(L)^2 + {}; forces {{ s: u1, L: u2/r, {} }} \
         constraints {{ {} }} }}",
        masses.join(", "),
        robot.join(", "),
        kinetic.join(" + "),
        weights.join(", "),
        constraints.join(", ")
    )
}

/// No dummy-derivative system is generated where the runtime would refuse
/// it (the inputs need more than the path's 10th derivative: a chain of 4
/// links needs the 12th), nor where the declaration turns it off; a chain
/// of 3 links (order 10) has it. (The system of a 14-link chain took the
/// macro over 300 s and 2.75 GB.)
#[test]
fn the_reduced_system_is_generated_only_where_the_runtime_takes_it() {
    let with = |source: &str| {
        expand(super::tokens(source))
            .to_string()
            .contains(":: DummyDerivatives <")
    };
    assert!(with(&chain(3)));
    assert!(!with(&chain(4)));
    assert!(!with(&chain(14)));
    let opted_out = chain(3).replacen(
        "#[crane(no_self_test)]",
        "#[crane(no_self_test)] #[crane(no_dummy_derivatives)]",
        1,
    );
    assert!(!with(&opted_out));
    assert!(expand(super::tokens(&opted_out)).to_string().contains("OptedOut"));
}

/// The messages for a control engineer's habits say what to write instead.
#[test]
fn messages_teach_the_formulation() {
    let first = |source: &str| expand_errors(source).0.into_iter().next().unwrap_or_default();
    let cases = [
        (
            navy_with("z: -m_l*g", "z: -m_lx*g"),
            "unknown symbol `m_lx`; did you mean `m_l`? allowed in `forces`",
        ),
        (
            navy_with("l*sin(alpha)", "l*sin(pi/3.0)"),
            "unknown symbol `pi`; did you mean `PI`? allowed in",
        ),
        (
            navy_with("l*sin(alpha)", "l*log(alpha)"),
            "unsupported function `log` (the natural logarithm is `ln`",
        ),
        (
            navy_with("rope0: 0.5*(x0^2", "rope0: 0.5*(pow(x0, 2)"),
            "unsupported function `pow` (write powers as `x^n`)",
        ),
        (
            navy_with("rope0: 0.5*(x0^2", "rope0: 0.5*(x0.powi(2)"),
            "unsupported operator `.`: write functions as `sin(x)` and powers as `x^2`",
        ),
        (
            navy_with("l*sin(alpha)", "l*sin(std::f64::consts::PI)"),
            "paths are not expressions: write `PI` for pi",
        ),
        (
            navy_with("rope0: 0.5*(x0^2 + z0^2 - L0^2)", "rope0: x0^2 + z0^2 = L0^2"),
            "a constraint is an expression g(q) that the motion keeps at zero, not an equation: for `a = b` write `a - (b)`",
        ),
        (
            navy_with("inputs [u1, u2]", "inputs [u1, u2] potential = m_l*g*z;"),
            "unknown section `potential`; expected one of: params, robot, load, inputs, kinetic, forces, constraints, minimal, sample; gravity and other potential forces are generalized forces in `forces`",
        ),
        (
            navy_with_sample(&format!(
                "sample {{ {} }}",
                FULL_SAMPLE.replace("L1 = 1.0 .. 20.0", "L1 = 20.0 .. 1.0")
            )),
            "the range of `L1` in `sample` is reversed (20.0 .. 1.0): write the lower end first, `L1 = 1.0 .. 20.0`",
        ),
        (
            navy_with_sample(&format!(
                "sample {{ {} }}",
                FULL_SAMPLE.replace("L1 = 1.0 .. 20.0", "L1 = 1.0 .. 1.0")
            )),
            "the range of `L1` in `sample` is empty (1.0 .. 1.0)",
        ),
    ];
    for (source, expected) in &cases {
        let message = first(source);
        assert!(
            message.starts_with(expected),
            "expected `{expected}...`, got `{message}`"
        );
    }
    // `..=` is the same box for continuous draws
    let inclusive = navy_with_sample(&format!(
        "sample {{ {} }}",
        FULL_SAMPLE.replace("1.0 .. 20.0", "1.0 ..= 20.0")
    ));
    assert_eq!(expand_errors(&inclusive).0, Vec::<String>::new());
}

/// The textbook angle formulation of a gantry crane: its mass matrix
/// depends on the angle. The message shows the rewrite in the load's
/// position with the user's names, before the missing constraint it asks
/// for.
#[test]
fn an_angle_formulation_is_shown_its_cartesian_rewrite() {
    let pendulum = r#"
        pub struct Pendulum {
            params { m_t = 10.0, m = 100.0, l = 5.0, g = 9.81 }
            robot  [s]
            load   [theta]
            inputs [u]
            kinetic = 0.5*(m_t + m)*dot(s)^2 + m*l*cos(theta)*dot(s)*dot(theta) + 0.5*m*l^2*dot(theta)^2;
            forces { s: u, theta: -m*g*l*sin(theta) }
            constraints { }
        }
    "#;
    assert_errors(
        pendulum,
        &[
            "configuration-dependent mass matrix: the method needs a constant M, but the coefficient of this term \
             depends on the coordinate `theta`; write it with the load's position instead of `theta`: the load's \
             coordinates `x`, `z` (z up) in `load`, the rope length `L` in `robot` (or a parameter), the kinetic \
             energy `0.5*m_l*(dot(x)^2 + dot(z)^2)` plus the robot's terms, gravity as the force `z: -m_l*g`, and \
             the rope as a constraint, `#[rope(N = L)] rope: 0.5*((x - s)^2 + z^2 - L^2)`; `theta` then follows \
             from the positions (sin(theta) = (x - s)/L)",
            "empty section `constraints`: declare at least one constraint",
        ],
    );
}

/// Constraints must be independent (`G` of full rank): a duplicated
/// constraint, one scaled, a sum of two, and one that does not involve the
/// coordinates are errors naming the constraints (before, the run stopped
/// at its first step: "NonUniqueEquilibrium ... free: L").
#[test]
fn dependent_constraints_are_named() {
    let duplicated = navy_with(
        "rope0: 0.5*(x0^2 + z0^2 - L0^2),",
        "rope0: 0.5*(x0^2 + z0^2 - L0^2),\n rope0_again: x0^2 + z0^2 - L0^2,",
    );
    assert_errors(
        &duplicated,
        &[
            "constraint `rope0_again` depends on `rope0`: its gradient is a combination of theirs at every \
           configuration tried, so `G = dg/dq` has rank < m (eq. 3) and the constraint forces are not unique; \
           remove it or state an independent constraint",
        ],
    );
    let sum = navy_with(
        "rope0: 0.5*(x0^2 + z0^2 - L0^2),",
        "rope0: 0.5*(x0^2 + z0^2 - L0^2),\n both: 0.5*(x0^2 + z0^2 - L0^2) + 0.5*((x0 + l*sin(alpha))^2 + \
         (z0 + l*cos(alpha))^2 - L1^2),",
    );
    let (messages, _) = expand_errors(&sum);
    assert_eq!(messages.len(), 1, "{messages:?}");
    assert!(
        messages[0].starts_with("constraint `both` depends on `rope1`, `rope0`:"),
        "{messages:?}"
    );
    // the sample points are generic: the planar crane's own constraints
    // are independent (the_planar_crane_has_no_errors), and so are the
    // built-ins' (they compile)
}

/// A load with a weight but no mass in the kinetic energy (its `dot(z)^2`
/// left out) compiles, with a warning at the force: the rope would hold
/// the weight alone, with a constant tension.
#[test]
fn a_weight_without_inertia_is_a_lint() {
    let massless = navy_with("0.5*m_l*(dot(x)^2 + dot(z)^2)", "0.5*m_l*dot(x)^2");
    let output = expand(tokens(&massless)).to_string();
    assert!(
        output.contains("z_has_a_force_but_no_inertia"),
        "no lint in the expansion"
    );
    assert!(output.contains("`z` carries a constant force but has no inertia"));
    assert!(!output.contains("compile_error"));
    // the planar crane's massless pulley (L0, x0, z0: no inertia, no force)
    // is not flagged
    let output = expand(tokens(NAVY)).to_string();
    assert!(!output.contains("deprecated"), "a lint on the planar crane");
}

/// Near misses of the declaration's punctuation and scope, each told what
/// to write.
#[test]
fn near_misses_are_told_what_to_write() {
    assert_errors(
        &navy_with("m_l = 100.0, J1 = 0.1,", "m_l = 100.0; J1 = 0.1,"),
        &["expected `,` between the items of a section, found `;`"],
    );
    assert_errors(
        &navy_with("robot  [L1, L2,", "robot  [\n /// rope 1\n L1, L2,"),
        &[
            "attributes and doc comments are not allowed on coordinates and inputs: describe them in a `//` \
           comment or in the crane's doc comment (doc comments are for the crane and its parameters)",
        ],
    );
    assert_errors(
        &navy_with("J2 = 0.1,", "J2 = 2.0*J1,"),
        &[
            "parameter defaults must be constant (numbers, PI and functions of them); `J1` is a parameter, set on \
           its own at run time, so a default cannot follow it: write the number, or use `J1` where the derived \
           value is needed (in `kinetic`, `forces` or `constraints`)",
        ],
    );
}
