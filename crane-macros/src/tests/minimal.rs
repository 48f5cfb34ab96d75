//! The checked `minimal` block and its kernels: substitution of `let`s and
//! mapped coordinates, and the structure of `P`, `P'` and `w`.

use super::{navy_minimal_source, tokens};
use crate::check::check;
use crate::ctxt::Ctxt;
use crate::expr::{Func, Id, Sym};
use crate::model::{Kernels, Model};
use crate::parse::parse;

fn checked(source: &str) -> Model {
    let cx = Ctxt::new();
    let decl = parse(tokens(source), &cx).expect("header parses");
    let model = check(&decl, &cx);
    if let Err(error) = cx.check() {
        panic!("{error}");
    }
    model.expect("no errors, so a model")
}

const THETA: Sym = Sym::Mu(2);
const L: Sym = Sym::Mu(3);

#[test]
fn lets_and_mapped_coordinates_are_substituted() {
    let mut model = checked(&navy_minimal_source());
    let minimal = model.minimal.take().expect("a minimal block");
    let names: Vec<String> = minimal.mu.iter().map(ToString::to_string).collect();
    assert_eq!(names, ["beta", "gamma", "theta", "L"]);
    assert_eq!(minimal.n_mu1, 2);
    let phi = &minimal.phi;
    let arena = &mut model.arena;

    // L0 = d, L2 = d + L: the value of `d` itself
    let (let_name, d) = &minimal.lets[0];
    assert_eq!(let_name.to_string(), "d");
    assert_eq!(phi[2], *d);
    let big_l = arena.sym(L);
    assert_eq!(phi[1], arena.add2(*d, big_l));

    // x = x0 + L sin(theta), z = z0 - L cos(theta): x0 and z0 stand for their maps
    let theta = arena.sym(THETA);
    let sin = arena.func(Func::Sin, theta);
    let cos = arena.func(Func::Cos, theta);
    let l_sin = arena.mul2(big_l, sin);
    let l_cos = arena.mul2(big_l, cos);
    assert_eq!(phi[5], arena.add2(phi[3], l_sin));
    assert_eq!(phi[6], arena.sub(phi[4], l_cos));

    // only parameters and minimal coordinates remain
    for &entry in phi {
        for sym in arena.symbols(entry) {
            assert!(matches!(sym, Sym::Param(_) | Sym::Mu(_)), "{sym:?}");
        }
    }
}

#[test]
fn the_kernels_have_the_structure_of_eqs_8_9_17_and_40() {
    let mut model = checked(&navy_minimal_source());
    let kernels = Kernels::derive(&mut model);
    let k = kernels.minimal.expect("minimal kernels");
    let arena = &mut model.arena;
    assert_eq!((k.p.len(), k.p[0].len()), (7, 4));
    assert_eq!((k.p_rate.len(), k.p_rate[0].len()), (7, 4));
    assert_eq!(k.w.len(), 2);

    // D2 phi_x = [[L cos(theta), sin(theta)], [L sin(theta), -cos(theta)]] (eq. 40)
    let (theta, big_l) = (arena.sym(THETA), arena.sym(L));
    let (sin, cos) = (arena.func(Func::Sin, theta), arena.func(Func::Cos, theta));
    let eq40: [[Id; 2]; 2] = [[arena.mul2(big_l, cos), sin], [arena.mul2(big_l, sin), arena.neg(cos)]];
    for (i, row) in eq40.iter().enumerate() {
        assert_eq!(k.p[5 + i][2..], row[..]);
    }
    // L2 = d + L: dL2/dL = 1; L1 depends on mu1 only
    assert_eq!(arena.as_const(k.p[1][3]), Some(1.0));
    assert!(arena.is_zero(k.p[0][2]) && arena.is_zero(k.p[0][3]));

    // P' vanishes where P is constant and depends on nothing but mu and mu'
    for (row_p, row_rate) in k.p.iter().zip(&k.p_rate) {
        for (&p, &rate) in row_p.iter().zip(row_rate) {
            if arena.as_const(p).is_some() {
                assert!(arena.is_zero(rate));
            }
            for sym in arena.symbols(rate) {
                assert!(matches!(sym, Sym::Param(_) | Sym::Mu(_) | Sym::MuDot(_)));
            }
        }
    }
    // w with mu1' = 0 is the pendulum's: -L sin(theta) theta'^2 + 2 cos(theta) theta' L'
    let zero = arena.zero();
    let pendulum_only = |arena: &mut crate::expr::Arena, e: Id| {
        arena.substitute(e, &mut |s| matches!(s, Sym::MuDot(0) | Sym::MuDot(1)).then_some(zero))
    };
    let w_x = pendulum_only(arena, k.w[0]);
    let (theta_dot, l_dot) = (arena.sym(Sym::MuDot(2)), arena.sym(Sym::MuDot(3)));
    let minus_one = arena.constant(-1.0);
    let two = arena.constant(2.0);
    let theta_dot2 = arena.powi(theta_dot, 2);
    let centripetal = arena.mul(vec![minus_one, big_l, sin, theta_dot2]);
    let coriolis = arena.mul(vec![two, cos, theta_dot, l_dot]);
    assert_eq!(w_x, arena.add2(centripetal, coriolis));
}
