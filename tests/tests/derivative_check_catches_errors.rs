//! The derivative checks that the generated self-tests and users rely on must
//! fail on a wrong derivative: a model whose `G` has one wrong entry, one
//! whose `G` has a wrong entry 5e-9 the size of the largest, and one whose
//! constraint Hessian is missing a term, are caught with O(1) errors, while
//! the correct model passes with ~1e-9.

use crane_runtime::check::{SampleBox, check_derivatives};
use crane_runtime::{CraneModel, ModelInfo, Scalar, UnknownParameter};
use crane_tests::handwritten::HandNavyPlanar;
use nalgebra::{SMatrix, SVector};

/// Which derivative to break.
#[derive(Clone, Copy, PartialEq)]
enum Flaw {
    None,
    /// `dg_hoist/dx` off by a factor 2.
    Jacobian,
    /// The `rope1` term missing from `d(G^T lambda)/dq`.
    Hessian,
    /// A structural zero of `G` (`dg_hoist/dL1`) set to 1e-7, about 5e-9 of
    /// the largest entry: below what central differences can see normwise.
    SmallEntry,
}

/// The hand-written planar crane with one deliberately wrong derivative.
struct Broken {
    model: HandNavyPlanar,
    flaw: Flaw,
}

impl CraneModel<7, 3, 2> for Broken {
    const INFO: ModelInfo = HandNavyPlanar::INFO;
    fn parameter_values(&self) -> Vec<f64> {
        self.model.parameter_values()
    }
    fn set_parameter(&mut self, name: &str, value: f64) -> Result<(), UnknownParameter> {
        self.model.set_parameter(name, value)
    }
    fn constraints<T: Scalar>(&self, q: &SVector<T, 7>) -> SVector<T, 3> {
        self.model.constraints(q)
    }
    fn constraint_jacobian<T: Scalar>(&self, q: &SVector<T, 7>) -> SMatrix<T, 3, 7> {
        let mut jac = self.model.constraint_jacobian(q);
        if self.flaw == Flaw::Jacobian {
            jac[(2, 5)] *= 2.0;
        }
        if self.flaw == Flaw::SmallEntry {
            jac[(2, 0)] += T::from(1e-7);
        }
        jac
    }
    fn constraint_hessian<T: Scalar>(&self, q: &SVector<T, 7>, lambda: &SVector<T, 3>) -> SMatrix<T, 7, 7> {
        if self.flaw == Flaw::Hessian {
            let mut without_rope1 = *lambda;
            without_rope1[0] = T::from(0.0);
            self.model.constraint_hessian(q, &without_rope1)
        } else {
            self.model.constraint_hessian(q, lambda)
        }
    }
    fn mass_matrix<T: Scalar>(&self) -> SMatrix<T, 7, 7> {
        self.model.mass_matrix()
    }
    fn forces<T: Scalar>(&self, q: &SVector<T, 7>, v: &SVector<T, 7>) -> SVector<T, 7> {
        self.model.forces(q, v)
    }
    fn force_jacobians<T: Scalar>(&self, q: &SVector<T, 7>, v: &SVector<T, 7>) -> (SMatrix<T, 7, 7>, SMatrix<T, 7, 7>) {
        self.model.force_jacobians(q, v)
    }
    fn input_matrix<T: Scalar>(&self, q: &SVector<T, 7>) -> SMatrix<T, 7, 2> {
        self.model.input_matrix(q)
    }
    fn input_jacobian<T: Scalar>(&self, q: &SVector<T, 7>, u: &SVector<T, 2>) -> SMatrix<T, 7, 7> {
        self.model.input_jacobian(q, u)
    }
    fn rope_lengths(&self, q: &SVector<f64, 7>, out: &mut [f64]) {
        self.model.rope_lengths(q, out)
    }
}

fn sample() -> SampleBox<7> {
    SampleBox {
        q: [
            (1.0, 20.0),
            (1.0, 20.0),
            (1.0, 20.0),
            (-15.0, 15.0),
            (-15.0, 0.0),
            (-15.0, 15.0),
            (-20.0, 0.0),
        ],
        velocity: 1.0,
        multiplier: 500.0,
        input: 100.0,
    }
}

#[test]
fn a_wrong_jacobian_entry_is_caught() {
    let report = check_derivatives(
        &Broken {
            model: HandNavyPlanar::default(),
            flaw: Flaw::Jacobian,
        },
        &sample(),
        50,
        1,
    );
    println!("{report}");
    // the doubled entry (x - x0) is of the size of the matrix: O(1) relative error
    assert!(report.get("G = dg/dq").unwrap().worst_relative_error > 0.1, "{report}");
    // the other quantities are untouched
    assert!(report.get("df/dq").unwrap().worst_relative_error < 1e-6);
}

#[test]
fn a_missing_hessian_term_is_caught() {
    let report = check_derivatives(
        &Broken {
            model: HandNavyPlanar::default(),
            flaw: Flaw::Hessian,
        },
        &sample(),
        50,
        2,
    );
    println!("{report}");
    assert!(
        report.get("d(G^T lambda)/dq").unwrap().worst_relative_error > 0.1,
        "{report}"
    );
    assert!(report.get("G = dg/dq").unwrap().worst_relative_error < 1e-6);
}

#[test]
fn the_correct_model_passes() {
    let report = check_derivatives(
        &Broken {
            model: HandNavyPlanar::default(),
            flaw: Flaw::None,
        },
        &sample(),
        50,
        3,
    );
    // central differences on quadratic constraints: round-off only, ~1e-10
    assert!(report.worst() < 1e-6, "{report}");
}

/// A wrong entry far below the matrix's size: the normwise central-difference
/// error is about 5e-9 (it would pass), the entry-wise dual-number
/// comparison sees it as wrong by 100 %.
#[test]
fn a_wrong_small_entry_is_caught() {
    let report = check_derivatives(
        &Broken {
            model: HandNavyPlanar::default(),
            flaw: Flaw::SmallEntry,
        },
        &sample(),
        50,
        4,
    );
    println!("{report}");
    assert!(report.get("G = dg/dq").unwrap().worst_relative_error > 0.5, "{report}");
    assert!(report.get("df/dq").unwrap().worst_relative_error < 1e-6);
}
