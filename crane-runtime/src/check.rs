//! Check every generated derivative of a model against central finite
//! differences at random points (docs/numerics.md).
//!
//! Two independent measures per derivative, and the larger counts:
//!
//! - central differences with step `h = 1e-6 (1 + |q_j|)` of the generated
//!   value functions: truncation error `O(h^2 |f'''|)` ~ 1e-12 and round-off
//!   `O(eps |f| / h)` ~ 1e-10 relative to the function's size, judged
//!   normwise (`max |A - FD| / max |A|`): ~1e-9 for a correct derivative;
//! - forward-mode dual numbers pushed through the same value functions,
//!   exact to round-off, judged entry by entry against each entry's own size
//!   with a floor of 1e-12 of the matrix's largest entry
//!   (`max_ij |A_ij - D_ij| / max(|A_ij|, |D_ij|, 1e-12 max|A|)`): ~1e-15
//!   for a correct derivative, and O(1) for a wrong entry however small
//!   next to the others (the normwise measure passes a wrong entry below
//!   1e-6 of the largest).
//!
//! A correct derivative therefore shows a worst error around 1e-9 or below,
//! a wrong one an error of order 1.
//!
//! ```
//! # use crane_runtime::check::{check_derivatives, SampleBox};
//! # fn demo<Mdl: crane_runtime::CraneModel<7, 3, 2>>(model: &Mdl, boxes: [(f64, f64); 7]) {
//! let report = check_derivatives(model, &SampleBox::new(boxes), 100, 42);
//! assert!(report.worst() < 1e-6, "{report}");
//! # }
//! ```

use std::fmt;

use nalgebra::{SMatrix, SVector};
use rand::rngs::SmallRng;
use rand::{Rng, SeedableRng};

use crate::model::{CraneModel, MinimalMap};
use num_dual::Dual64;

/// Where to sample: a box for the coordinates and symmetric ranges for the
/// velocities, multipliers and inputs.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SampleBox<const N: usize> {
    /// `(low, high)` for each coordinate.
    pub q: [(f64, f64); N],
    /// Velocities are drawn from `[-velocity, velocity]`.
    pub velocity: f64,
    /// Multipliers are drawn from `[-multiplier, multiplier]`.
    pub multiplier: f64,
    /// Inputs are drawn from `[-input, input]`.
    pub input: f64,
}

impl<const N: usize> SampleBox<N> {
    /// Coordinates in the given box; velocities, multipliers and inputs in `[-1, 1]`.
    pub fn new(q: [(f64, f64); N]) -> Self {
        Self {
            q,
            velocity: 1.0,
            multiplier: 1.0,
            input: 1.0,
        }
    }
}

/// Worst error found for one generated quantity.
#[derive(Debug, Clone, PartialEq)]
pub struct QuantityError {
    /// The quantity, e.g. `"G = dg/dq"`.
    pub quantity: &'static str,
    /// Largest normwise relative error `max|A - FD| / max(max|A|, max|FD|)`
    /// over all points (0 where both are zero).
    pub worst_relative_error: f64,
    /// The coordinates where it occurred.
    pub at: Vec<f64>,
}

impl QuantityError {
    /// No error yet for each of `names`.
    fn none_of(names: &[&'static str]) -> Vec<Self> {
        names
            .iter()
            .map(|&quantity| QuantityError {
                quantity,
                worst_relative_error: 0.0,
                at: Vec::new(),
            })
            .collect()
    }

    /// Keep, per quantity, the larger of its worst error and `errors` at the
    /// point `at` (a NaN error counts as infinite).
    fn record(worst: &mut [Self], errors: &[f64], at: &[f64]) {
        for (entry, &error) in worst.iter_mut().zip(errors) {
            if error > entry.worst_relative_error || error.is_nan() {
                entry.worst_relative_error = if error.is_nan() { f64::INFINITY } else { error };
                entry.at = at.to_vec();
            }
        }
    }
}

/// Result of [`check_derivatives`].
#[derive(Debug, Clone, PartialEq)]
pub struct DerivativeReport {
    /// Number of random points.
    pub points: usize,
    /// One entry per checked quantity.
    pub quantities: Vec<QuantityError>,
    /// For a minimal map: where in the box `D2 phi_x` (eq. 12) comes closest
    /// to singular.
    pub output_jacobian: Option<OutputJacobian>,
}

/// The conditioning of `D2 phi_x` over the sampled box of a minimal map:
/// the split `mu = [mu1; mu2]` needs it regular along the motion (eq. 12).
#[derive(Debug, Clone, PartialEq)]
pub struct OutputJacobian {
    /// The smallest singular value of `D2 phi_x` over the points.
    pub smallest_singular_value: f64,
    /// The largest condition number (largest over smallest singular value).
    pub largest_condition: f64,
    /// The minimal coordinates where the smallest singular value occurred.
    pub at: Vec<f64>,
}

impl DerivativeReport {
    /// The largest error over all quantities.
    pub fn worst(&self) -> f64 {
        self.quantities
            .iter()
            .map(|q| q.worst_relative_error)
            .fold(0.0, f64::max)
    }

    /// The entry for one quantity.
    pub fn get(&self, quantity: &str) -> Option<&QuantityError> {
        self.quantities.iter().find(|q| q.quantity == quantity)
    }
}

impl fmt::Display for DerivativeReport {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        writeln!(f, "derivatives against central differences at {} points:", self.points)?;
        for q in &self.quantities {
            writeln!(
                f,
                "  {:<28} worst relative error {:.2e}",
                q.quantity, q.worst_relative_error
            )?;
        }
        if let Some(d2) = &self.output_jacobian {
            writeln!(
                f,
                "  D2 phi_x (eq. 12)            smallest singular value {:.3e} (condition up to {:.2e}) at mu = {:?}",
                d2.smallest_singular_value, d2.largest_condition, d2.at
            )?;
        }
        Ok(())
    }
}

fn relative_error<const R: usize, const C: usize>(a: &SMatrix<f64, R, C>, b: &SMatrix<f64, R, C>) -> f64 {
    let size = a.amax().max(b.amax());
    if size == 0.0 { 0.0 } else { (a - b).amax() / size }
}

/// Entry-wise relative error, each entry against its own size with a floor
/// of 1e-12 of the largest entry.
fn entrywise_error<const R: usize, const C: usize>(a: &SMatrix<f64, R, C>, b: &SMatrix<f64, R, C>) -> f64 {
    let floor = 1e-12 * a.amax().max(b.amax());
    a.iter()
        .zip(b.iter())
        .map(|(x, y)| {
            let scale = x.abs().max(y.abs()).max(floor);
            if scale == 0.0 { 0.0 } else { (x - y).abs() / scale }
        })
        .fold(0.0, f64::max)
}

/// Jacobian of `func` at `x` by forward-mode dual numbers, column by column.
fn dual_jacobian<const R: usize, const N: usize>(
    x: &SVector<f64, N>,
    func: impl Fn(&SVector<Dual64, N>) -> SVector<Dual64, R>,
) -> SMatrix<f64, R, N> {
    let mut jac = SMatrix::<f64, R, N>::zeros();
    for j in 0..N {
        let seeded = SVector::<Dual64, N>::from_fn(|i, _| Dual64::new(x[i], if i == j { 1.0 } else { 0.0 }));
        jac.set_column(j, &func(&seeded).map(|d| d.eps));
    }
    jac
}

/// The larger of the normwise central-difference error and the entry-wise
/// dual-number error of `derivative`.
fn both_errors<const R: usize, const C: usize>(
    derivative: &SMatrix<f64, R, C>,
    central: &SMatrix<f64, R, C>,
    dual: &SMatrix<f64, R, C>,
) -> f64 {
    relative_error(derivative, central).max(entrywise_error(derivative, dual))
}

/// Central-difference Jacobian of `func` at `x`, column `j` with step `h_j = 1e-6 (1 + |x_j|)`.
fn central_jacobian<const R: usize, const N: usize>(
    x: &SVector<f64, N>,
    func: impl Fn(&SVector<f64, N>) -> SVector<f64, R>,
) -> SMatrix<f64, R, N> {
    let mut jac = SMatrix::<f64, R, N>::zeros();
    for j in 0..N {
        let h = 1e-6 * (1.0 + x[j].abs());
        let (mut plus, mut minus) = (*x, *x);
        plus[j] += h;
        minus[j] -= h;
        jac.set_column(j, &((func(&plus) - func(&minus)) / (2.0 * h)));
    }
    jac
}

/// Compare the model's generated derivatives with central finite differences
/// and with dual numbers (see the module docs)
/// at `points` random points drawn from `sample` (seeded, reproducible):
/// `G` against `g`, `d(G^T lambda)/dq` against `G^T lambda`, `df/dq` and
/// `df/dq'` against `f`, `d(B^T u)/dq` against `B^T u`, and `M` against the
/// kinetic energy's second differences are implied by the macro (M is
/// constant and checked by the models' tests).
pub fn check_derivatives<Mdl, const N: usize, const M: usize, const A: usize>(
    model: &Mdl,
    sample: &SampleBox<N>,
    points: usize,
    seed: u64,
) -> DerivativeReport
where
    Mdl: CraneModel<N, M, A>,
{
    let mut rng = SmallRng::seed_from_u64(seed);
    let names = ["G = dg/dq", "d(G^T lambda)/dq", "df/dq", "df/dq'", "d(B^T u)/dq"];
    let mut worst = QuantityError::none_of(&names);
    for _ in 0..points {
        let q = SVector::<f64, N>::from_fn(|i, _| rng.random_range(sample.q[i].0..=sample.q[i].1));
        let v = SVector::<f64, N>::from_fn(|_, _| rng.random_range(-1.0..=1.0) * sample.velocity);
        let lambda = SVector::<f64, M>::from_fn(|_, _| rng.random_range(-1.0..=1.0) * sample.multiplier);
        let u = SVector::<f64, A>::from_fn(|_, _| rng.random_range(-1.0..=1.0) * sample.input);

        let (df_dq, df_dv) = model.force_jacobians(&q, &v);
        let dual = |x: &SVector<f64, N>| x.map(Dual64::from);
        let (v_d, lambda_d, u_d) = (dual(&v), lambda.map(Dual64::from), u.map(Dual64::from));
        let errors = [
            both_errors(
                &model.constraint_jacobian(&q),
                &central_jacobian(&q, |q| model.constraints(q)),
                &dual_jacobian(&q, |q| model.constraints(q)),
            ),
            both_errors(
                &model.constraint_hessian(&q, &lambda),
                &central_jacobian(&q, |q| model.constraint_jacobian(q).tr_mul(&lambda)),
                &dual_jacobian(&q, |q| model.constraint_jacobian(q).tr_mul(&lambda_d)),
            ),
            both_errors(
                &df_dq,
                &central_jacobian(&q, |q| model.forces(q, &v)),
                &dual_jacobian(&q, |q| model.forces(q, &v_d)),
            ),
            both_errors(
                &df_dv,
                &central_jacobian(&v, |v| model.forces(&q, v)),
                &dual_jacobian(&v, |v| model.forces(&dual(&q), v)),
            ),
            both_errors(
                &model.input_jacobian(&q, &u),
                &central_jacobian(&q, |q| model.input_matrix(q) * u),
                &dual_jacobian(&q, |q| model.input_matrix(q) * u_d),
            ),
        ];
        QuantityError::record(&mut worst, &errors, q.as_slice());
    }
    DerivativeReport {
        points,
        quantities: worst,
        output_jacobian: None,
    }
}

/// Check a minimal-coordinate map at `points` random `mu` from the box
/// `mu_box` (velocities `mu'` from `[-mu_dot, mu_dot]`): that it satisfies
/// the constraints, `g(phi(mu)) = 0` (eq. 7, relative to `|q|^2` since `g`
/// carries 1/2 of squared lengths), that `P` is the null space of `G`
/// (`|G P| / (|G| |P|)`, eq. 11), and `P = D phi` (eq. 8) and `P'` (eq. 9)
/// against central differences, and the derivatives of the minimal Newton
/// matrix from [`MinimalMap::map_derivatives`]: its `phi`, `P`, `P'` against
/// the single functions, and the second derivatives `dP/dmu_k` and
/// `d(P' mu')/dmu` against central differences and dual numbers (errors as
/// in [`check_derivatives`]).
pub fn check_minimal_map<Mdl, const N: usize, const M: usize, const A: usize, const F: usize>(
    model: &Mdl,
    mu_box: &[(f64, f64); F],
    mu_dot: f64,
    points: usize,
    seed: u64,
) -> DerivativeReport
where
    Mdl: MinimalMap<N, M, A, F>,
{
    let mut rng = SmallRng::seed_from_u64(seed);
    let names = [
        "g(phi(mu)) = 0",
        "G P = 0",
        "P = D phi",
        "P' = dP/dt",
        "map_derivatives: phi, P, P'",
        "dP/dmu_k",
        "d(P' mu')/dmu",
    ];
    let mut output_jacobian: Option<OutputJacobian> = None;
    let mut worst = QuantityError::none_of(&names);
    for _ in 0..points {
        let mu = SVector::<f64, F>::from_fn(|i, _| rng.random_range(mu_box[i].0..=mu_box[i].1));
        let mu_rate = SVector::<f64, F>::from_fn(|_, _| rng.random_range(-1.0..=1.0) * mu_dot);
        let mu_rate_d = mu_rate.map(Dual64::from);
        let q = model.phi(&mu);
        let p = model.null_space(&mu);
        let derivatives = model.map_derivatives(&mu, &mu_rate);
        let jac_g = model.constraint_jacobian(&q);
        let scale = q.amax().max(1.0);
        // P' is the derivative of P along mu': central difference in that direction
        let h = 1e-6 * (1.0 + mu.amax()) / mu_rate.amax().max(1e-300);
        let p_rate_fd = (model.null_space(&(mu + mu_rate * h)) - model.null_space(&(mu - mu_rate * h))) / (2.0 * h);
        let (off, split) = (N - A, F - A);
        let d2 = nalgebra::DMatrix::from_fn(A, A, |i, k| p[(off + i, split + k)]);
        let singular = d2.singular_values();
        let (smallest, largest) = (singular.min(), singular.max());
        let worse = output_jacobian
            .as_ref()
            .is_none_or(|o: &OutputJacobian| smallest < o.smallest_singular_value);
        let condition = if smallest > 0.0 {
            largest / smallest
        } else {
            f64::INFINITY
        };
        let largest_condition = output_jacobian
            .as_ref()
            .map_or(condition, |o| o.largest_condition.max(condition));
        if worse {
            output_jacobian = Some(OutputJacobian {
                smallest_singular_value: smallest,
                largest_condition,
                at: mu.iter().copied().collect(),
            });
        } else if let Some(o) = output_jacobian.as_mut() {
            o.largest_condition = largest_condition;
        }
        let errors = [
            model.constraints(&q).amax() / (scale * scale),
            (jac_g * p).amax() / (jac_g.amax() * p.amax()).max(1e-300),
            relative_error(&p, &central_jacobian(&mu, |mu| model.phi(mu))),
            relative_error(&model.null_space_rate(&mu, &mu_rate), &p_rate_fd),
            // the fused map_derivatives against phi, P and P' (same
            // expressions, other common subexpressions: round-off apart)
            relative_error(&derivatives.phi, &q)
                .max(relative_error(&derivatives.null_space, &p))
                .max(relative_error(
                    &derivatives.null_space_rate(&mu_rate),
                    &model.null_space_rate(&mu, &mu_rate),
                )),
            // the second derivatives dP/dmu_k, each against P along e_k
            (0..F)
                .map(|k| {
                    let unit = SVector::<f64, F>::from_fn(|i, _| if i == k { 1.0 } else { 0.0 });
                    let h = 1e-6 * (1.0 + mu[k].abs());
                    let central = (model.null_space(&(mu + unit * h)) - model.null_space(&(mu - unit * h))) / (2.0 * h);
                    let seeded = SVector::<Dual64, F>::from_fn(|i, _| Dual64::new(mu[i], unit[i]));
                    let dual = model.null_space(&seeded).map(|d| d.eps);
                    both_errors(&derivatives.null_space_derivatives[k], &central, &dual)
                })
                .fold(0.0, f64::max),
            both_errors(
                &derivatives.curvature_jacobian,
                &central_jacobian(&mu, |mu| model.null_space_rate(mu, &mu_rate) * mu_rate),
                &dual_jacobian(&mu, |mu| model.null_space_rate(mu, &mu_rate_d) * mu_rate_d),
            ),
        ];
        QuantityError::record(&mut worst, &errors, mu.as_slice());
    }
    DerivativeReport {
        points,
        quantities: worst,
        output_jacobian,
    }
}

/// The check the generated self-test of a model with a `sample` section
/// runs: [`check_derivatives`] at 100 seeded random points of the box `q`
/// (velocities, multipliers, inputs in `[-1, 1]`), passed if every error is
/// below 1e-6 (correct derivatives show ~1e-9, a wrong one O(1)).
pub fn derivative_self_test<Mdl, const N: usize, const M: usize, const A: usize>(
    model: &Mdl,
    q: &[(f64, f64); N],
) -> Result<DerivativeReport, DerivativeReport>
where
    Mdl: CraneModel<N, M, A>,
{
    let report = check_derivatives(model, &SampleBox::new(*q), 100, 0x5eed);
    if report.worst() < 1e-6 { Ok(report) } else { Err(report) }
}

/// The check the generated self-test of a minimal map runs:
/// [`check_minimal_map`] at 100 seeded random points of the box `mu`,
/// passed if `g(phi(mu)) = 0` holds to 1e-12 (relative to `|q|^2`) and every
/// other error is below 1e-6.
pub fn minimal_map_self_test<Mdl, const N: usize, const M: usize, const A: usize, const F: usize>(
    model: &Mdl,
    mu: &[(f64, f64); F],
) -> Result<DerivativeReport, DerivativeReport>
where
    Mdl: MinimalMap<N, M, A, F>,
{
    let report = check_minimal_map(model, mu, 1.0, 100, 0x5eed);
    let constraints = report
        .get("g(phi(mu)) = 0")
        .map_or(f64::INFINITY, |e| e.worst_relative_error);
    if constraints < 1e-12 && report.worst() < 1e-6 {
        Ok(report)
    } else {
        Err(report)
    }
}
