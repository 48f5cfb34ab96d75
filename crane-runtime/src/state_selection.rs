//! The servo problem of a crane with internal dynamics reduced by dummy
//! derivatives with state selection ([`SelectedStates`]), as a [`Problem`]
//! on the stepper seam.
//!
//! Where the load path leaves `d` states free, the dummy-derivative system
//! of eqs. (22a-d) has `J - d` equations in its `J` jets
//! ([`DummyDerivatives::DIMENSION`]). State selection (Mattsson and
//! Soderlind) takes `d` jets of the robot coordinates as states: those whose
//! columns a regular square block of the system's Jacobian at the start
//! leaves out, preferring the lowest derivatives (positions, then
//! velocities) as states. Given them, every other jet is algebraic at each
//! time, as in the flat case. The run's scheme integrates the states: for a
//! state `y = x^(l)` of coordinate `x` with derivative `x^(l+1)`, BDF-k's
//! ```text
//! x^(l+1) = (c / dt) (x^(l) - ybar)
//! ```
//! closes the system with `d` rows. The inputs are then exact up to the
//! scheme's error in the `d` states, and a flat crane (`d = 0`) is the
//! dummy-derivative problem itself ([`simulate`]).
//!
//! The linearisation of the states' equations at a state of the crane gives
//! the eigenvalues of its internal dynamics ([`SelectedStates::eigenvalues`]).

use std::ops::{Deref, Range};

use nalgebra::{Complex, DMatrix, DVector, SVector};

use crate::driver::record;
use crate::dummy_derivative::{DummyDerivative, DummyDerivativeStepper, PathJets};
use crate::error::Error;
use crate::model::{CraneModel, DummyDerivatives, VisitDummyDerivatives};
use crate::newton::{NonlinearSystem, RowPattern, normalised_residual_sparse};
use crate::options::Options;
use crate::problem::{Accepted, Predictor, Problem, Start};
use crate::scheme::{Method, StepFormula};
use crate::solution::{Solution, State};
use crate::stepper::{Advance, StepReport, Stepper, rope_branch_left};
use crate::trajectory::Trajectory;

/// Consecutive jets of one robot coordinate selected as states: `x^(order)`
/// and, if `count` is 2, `x^(order + 1)` (a second-order state).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Chain {
    /// The robot coordinate (index into `q`).
    pub coordinate: usize,
    /// The lowest derivative selected.
    pub order: u8,
    /// How many consecutive derivatives: 1 or 2.
    pub count: u8,
}

/// How much further from singular a new selection's algebraic block must
/// be than the present one's for the states to change
/// ([`SelectedStates::reselect`]): a margin that keeps a selection from
/// switching back and forth where two are about as good.
pub const RESELECT_GAIN: f64 = 10.0;

/// How far the pivot ratio of a step's iteration matrix may fall below the
/// first step's before the states are selected anew
/// ([`SelectedStatesStepper`]): the ratio is free, the selection is not.
pub const RESELECT_TRIGGER: f64 = 1e-2;

impl Chain {
    /// Its jets, `(coordinate, order)`, lowest first.
    pub fn jets(self) -> impl Iterator<Item = (usize, u8)> {
        (self.order..self.order + self.count).map(move |order| (self.coordinate, order))
    }
}

/// Relative size below which a column of the row-equilibrated Jacobian is
/// taken as dependent on the columns already chosen (the Jacobian's entries
/// are exact derivatives: a dependent column is so to round-off, 1e-16).
const DEPENDENT: f64 = 1e-9;

/// The states among the jets `columns` (`(unknown of [q, lambda, u],
/// order)` of each column of `jacobian`, whose first `jacobian.ncols() -
/// dimension` rows are the equations): the `dimension` jets of the first
/// `robot` coordinates, below each coordinate's highest, that a regular
/// square block of the row-equilibrated Jacobian leaves out, chosen
/// greedily (the highest derivatives first as dummy derivatives, within a
/// derivative the column most independent of those chosen; a jet below a
/// state is a state, so that each coordinate's states are its lowest
/// jets).
pub fn select(
    jacobian: &DMatrix<f64>,
    columns: &[(usize, u8)],
    offsets: &[u8],
    robot: usize,
    dimension: usize,
) -> Result<Vec<Chain>, String> {
    let rows = jacobian.ncols() - dimension;
    let mut scaled = jacobian.rows(0, rows).into_owned();
    for mut row in scaled.row_iter_mut() {
        let largest = row.amax();
        if largest > 0.0 {
            row /= largest;
        }
    }
    let candidate = |&(j, order): &(usize, u8)| j < robot && order < offsets[j];
    let mut basis: Vec<DVector<f64>> = Vec::with_capacity(rows);
    // the part of column `k` independent of the basis, relative to its size
    let residual = |basis: &[DVector<f64>], k: usize| {
        let mut v = scaled.column(k).into_owned();
        let size = v.norm();
        // twice: Gram-Schmidt loses orthogonality once
        for _ in 0..2 {
            for b in basis {
                let projection = b.dot(&v);
                v.axpy(-projection, b, 1.0);
            }
        }
        let norm = v.norm();
        (
            if size > 0.0 { norm / size } else { 0.0 },
            v / norm.max(f64::MIN_POSITIVE),
        )
    };
    for (k, column) in columns.iter().enumerate() {
        if candidate(column) {
            continue;
        }
        let (independence, direction) = residual(&basis, k);
        if independence <= DEPENDENT {
            return Err(format!(
                "the jets of the multipliers, the inputs and the highest derivatives are dependent at the start (the \
                 column of jet {} of unknown {} is {independence:.1e} of its size independent of them): the states \
                 the path leaves free are not all jets of the robot coordinates",
                column.1, column.0
            ));
        }
        basis.push(direction);
    }
    let top = columns.iter().filter(|c| candidate(c)).map(|c| c.1).max().unwrap_or(0);
    let mut states: Vec<(usize, u8)> = Vec::new();
    for order in (0..=top).rev() {
        // a jet below a state is a state too (Mattsson and Soderlind: the
        // dummies of a level are chosen among the jets whose derivatives
        // are dummies), so the states of a coordinate are its lowest jets
        let (forced, mut pending): (Vec<usize>, Vec<usize>) = (0..columns.len())
            .filter(|&k| candidate(&columns[k]) && columns[k].1 == order)
            .partition(|&k| states.contains(&(columns[k].0, order + 1)));
        states.extend(forced.iter().map(|&k| columns[k]));
        while basis.len() < rows && !pending.is_empty() {
            let (at, (independence, direction)) = pending
                .iter()
                .map(|&k| residual(&basis, k))
                .enumerate()
                .max_by(|a, b| a.1.0.total_cmp(&b.1.0))
                .expect("pending is not empty");
            if independence <= DEPENDENT {
                break;
            }
            basis.push(direction);
            pending.swap_remove(at);
        }
        states.extend(pending.iter().map(|&k| columns[k]));
    }
    if basis.len() < rows || states.len() != dimension {
        return Err(format!(
            "{} jets of the robot coordinates are left free where the structure leaves {dimension} (the \
             Jacobian at the start has rank {} of {rows})",
            states.len(),
            basis.len()
        ));
    }
    states.sort_unstable();
    let mut chains: Vec<Chain> = Vec::new();
    for (j, order) in states {
        match chains.last_mut() {
            Some(chain) if chain.coordinate == j && chain.order + chain.count == order && chain.count == 1 => {
                chain.count = 2;
            }
            Some(chain) if chain.coordinate == j => {
                return Err(format!(
                    "the states of robot coordinate {j} are not one or two consecutive derivatives (derivatives {} \
                     and {order})",
                    chain.order
                ));
            }
            _ => chains.push(Chain {
                coordinate: j,
                order,
                count: 1,
            }),
        }
    }
    Ok(chains)
}

/// The dummy-derivative system of a crane with internal dynamics, closed by
/// the scheme's formula for its selected states (see the module docs): a
/// [`Problem`] whose `N` discretised coordinates are, for each robot
/// coordinate with states, its lowest state jet (`y`), the next jet (`y'`)
/// and the one after (`y''`, for a second-order state); the others are 0.
pub struct SelectedStates<H, Tr, const N: usize, const M: usize, const A: usize, const J: usize> {
    /// The system and the crane's state in its jets.
    system: DummyDerivative<H, Tr, N, M, A, J>,
    /// The states, selected at the start.
    chains: Vec<Chain>,
    /// The jets in the order of the unknowns, `(unknown, order)`.
    columns: Vec<(usize, u8)>,
    /// The step's formula.
    formula: StepFormula<N>,
    /// The Jacobian's entries not zero by structure, with the states' rows.
    nonzeros: RowPattern,
    /// One relative stopping test for all jets.
    blocks: Vec<Range<usize>>,
}

impl<H, Tr, const N: usize, const M: usize, const A: usize, const J: usize> SelectedStates<H, Tr, N, M, A, J>
where
    H: Deref<Target: DummyDerivatives<N, M, A, J> + Sized>,
    Tr: Trajectory<A>,
{
    /// The problem of the crane behind `model` on `trajectory`; its states
    /// are selected at the start of a run ([`Problem::start`]).
    pub fn new(model: H, trajectory: Tr) -> Self {
        let system = DummyDerivative::new(model, trajectory);
        let offsets = <H::Target as DummyDerivatives<N, M, A, J>>::OFFSETS;
        let mut columns = vec![(0, 0); J];
        for (j, &offset) in offsets.iter().enumerate() {
            if (N - A..N).contains(&j) {
                continue;
            }
            for order in 0..=offset {
                if let Some(column) = columns.get_mut(system.slot(j, order.into())) {
                    *column = (j, order);
                }
            }
        }
        Self {
            system,
            chains: Vec::new(),
            columns,
            formula: StepFormula::unprepared(),
            nonzeros: RowPattern::new(J, &[]),
            blocks: vec![Range { start: 0, end: J }],
        }
    }

    /// The selected states (empty before the start).
    pub fn chains(&self) -> &[Chain] {
        &self.chains
    }

    /// The selected states by name: `phi`, `phi'`, `phi''`, `phi^(3)`.
    pub fn state_names(&self) -> Vec<String> {
        let coordinates = <H::Target as CraneModel<N, M, A>>::INFO.coordinates;
        let prime = |order: u8| match order {
            0..=2 => "'".repeat(order.into()),
            _ => format!("^({order})"),
        };
        (self.chains.iter())
            .flat_map(|chain| chain.jets())
            .map(|(coordinate, order)| {
                let name = coordinates.get(coordinate).copied().unwrap_or("?");
                format!("{name}{}", prime(order))
            })
            .collect()
    }

    /// The discretised coordinates of the jets `z` (each coordinate with
    /// states: its lowest state jet) and their rates (the next jets).
    pub fn coordinates(&self, z: &DVector<f64>) -> (SVector<f64, N>, SVector<f64, N>) {
        let mut y = SVector::zeros();
        let mut v = SVector::zeros();
        for chain in &self.chains {
            let slot = self.system.slot(chain.coordinate, chain.order.into());
            y[chain.coordinate] = z[slot];
            v[chain.coordinate] = z[slot + 1];
        }
        (y, v)
    }

    /// Take `chains` as the states, with the Jacobian's pattern of their
    /// rows (the model's entries, then the states' rows). It allocates.
    fn set_chains(&mut self, chains: Vec<Chain>) {
        self.chains = chains;
        let nonzeros = <H::Target as DummyDerivatives<N, M, A, J>>::JACOBIAN_NONZEROS;
        let mut entries: Vec<u32> = nonzeros.to_vec();
        let mut row = Self::equations();
        for chain in &self.chains {
            for k in 0..chain.count {
                let y = self.system.slot(chain.coordinate, usize::from(chain.order + k));
                entries.extend([y * J + row, (y + 1) * J + row].map(|e| e as u32));
                row += 1;
            }
        }
        self.nonzeros = RowPattern::new(J, &entries);
    }

    /// The slots of the states of `chains` in `z`, in chain order.
    fn state_slots(&self, chains: &[Chain]) -> Vec<usize> {
        (chains.iter())
            .flat_map(|chain| chain.jets())
            .map(|(j, order)| self.system.slot(j, order.into()))
            .collect()
    }

    /// How far from singular the algebraic block of `jacobian` is with
    /// `chains` as the states: the smallest-to-largest pivot ratio of the
    /// LU of the block of the other columns, rows and columns scaled to a
    /// largest entry of 1 (0 where it is singular).
    fn quality(&self, jacobian: &DMatrix<f64>, chains: &[Chain]) -> f64 {
        let rows = Self::equations();
        let states = self.state_slots(chains);
        let algebraic: Vec<usize> = (0..J).filter(|k| !states.contains(k)).collect();
        if algebraic.len() != rows {
            return 0.0;
        }
        let mut block = DMatrix::from_fn(rows, rows, |i, k| jacobian[(i, algebraic[k])]);
        for mut row in block.row_iter_mut() {
            let largest = row.amax();
            if largest > 0.0 {
                row /= largest;
            }
        }
        for mut column in block.column_iter_mut() {
            let largest = column.amax();
            if largest > 0.0 {
                column /= largest;
            }
        }
        let u = block.lu().u();
        let pivots = u.diagonal().map(f64::abs);
        let (smallest, largest) = (pivots.min(), pivots.max());
        if largest > 0.0 && smallest.is_finite() {
            smallest / largest
        } else {
            0.0
        }
    }

    /// Set the path's derivatives to those at `t` (the time of jets about
    /// to be [`reselect`](Self::reselect)ed after a failed step prepared
    /// another).
    pub fn prepare_time(&mut self, t: f64) {
        self.system.gamma = self.system.drive(t);
    }

    /// Select the states anew at the jets `z` (and the prepared path
    /// derivatives): the new selection where it differs from the present
    /// one and its algebraic block is at least [`RESELECT_GAIN`] times
    /// further from singular (the pivot ratio of its scaled LU); `None` where the
    /// present one stays. It allocates.
    pub fn reselect(&mut self, z: &DVector<f64>) -> Option<&[Chain]> {
        if self.chains.is_empty() {
            return None;
        }
        let jacobian = self.model_jacobian(z);
        let offsets = <H::Target as DummyDerivatives<N, M, A, J>>::OFFSETS;
        let dimension = <H::Target as DummyDerivatives<N, M, A, J>>::DIMENSION;
        let chains = select(&jacobian, &self.columns, offsets, N - A, dimension).ok()?;
        let better = chains != self.chains
            && self.quality(&jacobian, &self.chains) * RESELECT_GAIN < self.quality(&jacobian, &chains);
        better.then(|| {
            self.set_chains(chains);
            self.chains.as_slice()
        })
    }

    /// The rows of the model's equations.
    fn equations() -> usize {
        J - <H::Target as DummyDerivatives<N, M, A, J>>::DIMENSION
    }

    /// The model's Jacobian at the jets `z` and the prepared path derivatives
    /// (its first [`equations`](Self::equations) rows), as a new matrix.
    fn model_jacobian(&self, z: &DVector<f64>) -> DMatrix<f64> {
        let mut residual = DVector::zeros(J);
        let mut jacobian = DMatrix::zeros(J, J);
        (self.system.model).dummy_derivative_system_into(
            &self.system.gamma,
            z.as_slice(),
            residual.as_mut_slice(),
            jacobian.as_mut_slice(),
        );
        jacobian
    }

    /// The eigenvalues of the selected states' equations linearised at the
    /// jets `z`, the path's derivatives held (those of the last prepared
    /// step, or of the start): `s' = A s` with `A` from the implicit
    /// function theorem on the system's equations. `None` before the
    /// states are selected or where the algebraic block is singular. A
    /// diagnostic: it allocates.
    pub fn eigenvalues(&self, z: &DVector<f64>) -> Option<Vec<Complex<f64>>> {
        let d = <H::Target as DummyDerivatives<N, M, A, J>>::DIMENSION;
        if self.chains.is_empty() || d == 0 {
            return None;
        }
        let rows = Self::equations();
        let jacobian = self.model_jacobian(z);
        // the states' columns in chain order, the other columns in order
        let states = self.state_slots(&self.chains);
        let algebraic: Vec<usize> = (0..J).filter(|k| !states.contains(k)).collect();
        let f_a = DMatrix::from_fn(rows, rows, |i, k| jacobian[(i, algebraic[k])]);
        let f_s = DMatrix::from_fn(rows, d, |i, k| jacobian[(i, states[k])]);
        // d(algebraic jets)/d(states) = -F_a^-1 F_s
        let sensitivity = -f_a.lu().solve(&f_s)?;
        let a = DMatrix::from_fn(d, d, |row, col| {
            let derivative = states[row] + 1;
            match states.iter().position(|&s| s == derivative) {
                Some(k) => f64::from(u8::from(k == col)),
                None => algebraic
                    .iter()
                    .position(|&k| k == derivative)
                    .map_or(f64::NAN, |k| sensitivity[(k, col)]),
            }
        });
        a.iter()
            .all(|x| x.is_finite())
            .then(|| a.complex_eigenvalues().iter().copied().collect())
    }
}

impl<H, Tr, const N: usize, const M: usize, const A: usize, const J: usize> NonlinearSystem
    for SelectedStates<H, Tr, N, M, A, J>
where
    H: Deref<Target: DummyDerivatives<N, M, A, J> + Sized>,
    Tr: Trajectory<A>,
{
    fn dim(&self) -> usize {
        J
    }

    /// The model's equations, then each state's row of the scheme's
    /// formula, `x^(l) - ybar - (dt / c) x^(l+1)` (the value's offset for
    /// the lowest state of a coordinate, the rate's for the next).
    fn evaluate(&mut self, z: &DVector<f64>, r: &mut DVector<f64>, jac: &mut DMatrix<f64>) {
        (self.system.model).dummy_derivative_system_into(
            &self.system.gamma,
            z.as_slice(),
            r.as_mut_slice(),
            jac.as_mut_slice(),
        );
        let step = 1.0 / self.formula.rate;
        let mut row = Self::equations();
        // (rows a selection of other states wrote are cleared)
        jac.rows_mut(row, J - row).fill(0.0);
        for chain in &self.chains {
            let i = chain.coordinate;
            for k in 0..chain.count {
                let y = self.system.slot(i, usize::from(chain.order + k));
                let offset = if k == 0 {
                    self.formula.value_offset[i]
                } else {
                    self.formula.rate_offset[i]
                };
                r[row] = z[y] - offset - step * z[y + 1];
                jac[(row, y)] = 1.0;
                jac[(row, y + 1)] = -step;
                row += 1;
            }
        }
    }

    fn normalised_residual(&self, z: &DVector<f64>, r: &DVector<f64>, jac: &DMatrix<f64>) -> f64 {
        normalised_residual_sparse(r, jac, z, &self.nonzeros)
    }

    fn blocks(&self) -> &[Range<usize>] {
        &self.blocks
    }

    /// Yes: one solve per step time of smooth jets.
    fn nearby_solves(&self) -> bool {
        true
    }
}

impl<H, Tr, const N: usize, const M: usize, const A: usize, const J: usize> Problem<N, M, A, N>
    for SelectedStates<H, Tr, N, M, A, J>
where
    H: Deref<Target: DummyDerivatives<N, M, A, J> + Sized>,
    Tr: Trajectory<A>,
{
    type Model = H::Target;
    type Drive = PathJets<A>;

    /// The jets range from metres to N/s^6: equilibrate.
    const EQUILIBRATED: bool = true;

    fn model(&self) -> &H::Target {
        &self.system.model
    }

    fn path_order_covered(&self) -> Option<usize> {
        self.system.path_order_covered()
    }

    /// As the flat system's: the polynomial through the last eight steps.
    fn predictor(&self) -> Predictor {
        self.system.predictor()
    }

    fn drive(&self, t: f64) -> PathJets<A> {
        self.system.drive(t)
    }

    fn check_drive(&self, gamma: &PathJets<A>, t: f64) -> Result<(), Error> {
        self.system.check_drive(gamma, t)
    }

    /// The start's jets as the flat system's; the states selected there
    /// (a state above the velocities needs a start at rest, where the
    /// higher jets are 0).
    fn start(&mut self, start: &State<N, M, A>, dt: f64, z: &mut DVector<f64>) -> Result<Start<N>, Error> {
        let name = <H::Target as CraneModel<N, M, A>>::INFO.name;
        let dimension = <H::Target as DummyDerivatives<N, M, A, J>>::DIMENSION;
        let flat = self.system.start(start, dt, z)?;
        self.prepare_time(start.t);
        let jacobian = self.model_jacobian(z);
        let offsets = <H::Target as DummyDerivatives<N, M, A, J>>::OFFSETS;
        let chains = select(&jacobian, &self.columns, offsets, N - A, dimension)
            .map_err(|reason| Error::StatesNotSelected { model: name, reason })?;
        self.set_chains(chains);
        if !flat.at_rest && self.chains.iter().any(|c| c.order + c.count > 2) {
            return Err(Error::StatesNotSelected {
                model: name,
                reason: "a state above the velocities needs a start at rest (the start gives positions and \
                         velocities only)"
                    .into(),
            });
        }
        let (y0, v0) = self.coordinates(z);
        Ok(Start {
            y0,
            v0,
            at_rest: flat.at_rest,
        })
    }

    fn prepare(&mut self, gamma: &PathJets<A>, formula: StepFormula<N>) {
        self.system.gamma = *gamma;
        self.formula = formula;
    }

    fn accept(&mut self, t: f64, z: &DVector<f64>) -> Result<Accepted<N, M, A, N>, Error> {
        let (y, v) = self.coordinates(z);
        Ok(Accepted {
            state: self.system.state(t, z),
            y,
            v,
            trailing: None,
        })
    }

    /// Where a rope's length or a taut rope's tension changed sign.
    fn leaves_branch(&self, before: &State<N, M, A>, after: &State<N, M, A>) -> bool {
        rope_branch_left(&*self.system.model, before, after)
    }
}

/// The reduced servo problem with state selection one step at a time, on
/// the scheme `S`: a [`Stepper`] of [`SelectedStates`] that selects the
/// states anew where the selection degenerates along the move (a bob whose
/// horizontal position is a state passing the horizontal, where its height
/// no longer follows from it): where a step's iteration matrix has a pivot
/// ratio below [`RESELECT_TRIGGER`] times the first step's, or a step
/// fails, [`SelectedStates::reselect`] at the last accepted jets, and the
/// scheme's history of the new states from the last steps' jets
/// ([`Stepper::rediscretise`]). [`reselections`](Self::reselections) says
/// when and to what. A step that does not reselect does not allocate.
pub struct SelectedStatesStepper<H, Tr, S: Method, const N: usize, const M: usize, const A: usize, const J: usize> {
    stepper: Stepper<SelectedStates<H, Tr, N, M, A, J>, S, N, M, A, N>,
    /// The first step's pivot ratio.
    healthy: f64,
    reselections: Vec<(f64, Vec<String>)>,
}

impl<H, Tr, S, const N: usize, const M: usize, const A: usize, const J: usize>
    SelectedStatesStepper<H, Tr, S, N, M, A, J>
where
    H: Deref<Target: DummyDerivatives<N, M, A, J> + Sized>,
    Tr: Trajectory<A>,
    S: Method,
{
    /// A stepper for the crane behind `model` on `trajectory` from the
    /// consistent `start`, with the step, scheme and tolerances of
    /// `options`; the states selected at the start.
    pub fn new(model: H, trajectory: Tr, start: &State<N, M, A>, options: &Options<S>) -> Result<Self, Error> {
        Ok(Self {
            stepper: Stepper::new(SelectedStates::new(model, trajectory), start, options)?,
            healthy: f64::NAN,
            reselections: Vec::new(),
        })
    }

    /// The stepper of the problem.
    pub fn stepper(&self) -> &Stepper<SelectedStates<H, Tr, N, M, A, J>, S, N, M, A, N> {
        &self.stepper
    }

    /// When the states were selected anew, and the new states.
    pub fn reselections(&self) -> &[(f64, Vec<String>)] {
        &self.reselections
    }

    /// Advance one step on the problem's path, the states selected anew
    /// before it where it fails, after it where its matrix degenerates.
    pub fn step(&mut self) -> Result<StepReport, Error> {
        let report = match self.stepper.step() {
            Ok(report) => report,
            Err(error @ (Error::NewtonNotConverged { .. } | Error::SingularIterationMatrix { .. })) => {
                if !self.reselect() {
                    return Err(error);
                }
                self.stepper.step()?
            }
            Err(error) => return Err(error),
        };
        let ratio = self.stepper.pivot_ratio();
        if self.healthy.is_nan() {
            self.healthy = ratio;
        } else if ratio < RESELECT_TRIGGER * self.healthy {
            self.reselect();
        }
        Ok(report)
    }

    /// Select the states anew at the last accepted step; whether they
    /// changed.
    fn reselect(&mut self) -> bool {
        let z = self.stepper.accepted_unknowns().clone();
        let t = self.stepper.state().t;
        let problem = self.stepper.problem_mut();
        problem.prepare_time(t);
        if problem.reselect(&z).is_none() {
            return false;
        }
        self.stepper.rediscretise(|problem, z| problem.coordinates(z));
        self.reselections.push((t, self.stepper.problem().state_names()));
        true
    }
}

impl<H, Tr, S, const N: usize, const M: usize, const A: usize, const J: usize> Advance<N, M, A>
    for SelectedStatesStepper<H, Tr, S, N, M, A, J>
where
    H: Deref<Target: DummyDerivatives<N, M, A, J> + Sized>,
    Tr: Trajectory<A>,
    S: Method,
{
    type Model = H::Target;
    fn model(&self) -> &H::Target {
        self.stepper.problem().model()
    }
    fn step(&mut self) -> Result<StepReport, Error> {
        SelectedStatesStepper::step(self)
    }
    fn state(&self) -> &State<N, M, A> {
        self.stepper.state()
    }
    fn dt(&self) -> f64 {
        self.stepper.dt()
    }
    fn scheme_name(&self) -> &'static str {
        Advance::scheme_name(&self.stepper)
    }
    fn path_order_covered(&self) -> Option<usize> {
        self.stepper.problem().path_order_covered()
    }
}

/// Solve the reduced servo problem at every step time from `start` to
/// `options.tf()`, calling `progress(step, steps)` after every step: a flat
/// crane's by [`DummyDerivativeStepper`], one with internal dynamics by
/// [`SelectedStates`] on the scheme of `options` (the selected states in
/// [`Solution::selected_states`]). Any crane `crane_model!` declares with a
/// regular structure has the system; for another, the error says why it
/// has none.
pub fn simulate<Mdl, Tr, S, const N: usize, const M: usize, const A: usize>(
    model: &Mdl,
    trajectory: Tr,
    start: &State<N, M, A>,
    options: &Options<S>,
    progress: &mut dyn FnMut(usize, usize),
) -> Result<Solution<N, M, A>, Error>
where
    Mdl: CraneModel<N, M, A>,
    Tr: Trajectory<A> + Clone,
    S: Method,
{
    /// The run, with the system's size.
    struct Simulate<'a, Mdl, Tr, S: Method, const N: usize, const M: usize, const A: usize> {
        model: &'a Mdl,
        trajectory: Tr,
        start: &'a State<N, M, A>,
        options: &'a Options<S>,
        progress: &'a mut dyn FnMut(usize, usize),
    }
    impl<Mdl, Tr, S, const N: usize, const M: usize, const A: usize> VisitDummyDerivatives<Mdl, N, M, A>
        for Simulate<'_, Mdl, Tr, S, N, M, A>
    where
        Tr: Trajectory<A> + Clone,
        S: Method,
    {
        type Output = Result<Solution<N, M, A>, Error>;
        fn visit<const J: usize>(self) -> Self::Output
        where
            Mdl: DummyDerivatives<N, M, A, J>,
        {
            if Mdl::DIMENSION == 0 {
                let mut stepper = DummyDerivativeStepper::<_, _, _, N, M, A, J>::new(
                    self.model,
                    self.trajectory,
                    self.start,
                    self.options,
                )?;
                let mut solution = record(&mut stepper, self.options.tf(), self.progress)?;
                solution.redundant_start_steps = stepper.fallback_steps();
                return Ok(solution);
            }
            let mut stepper = SelectedStatesStepper::<_, _, _, N, M, A, J>::new(
                self.model,
                self.trajectory,
                self.start,
                self.options,
            )?;
            let selected = stepper.stepper().problem().state_names();
            let mut solution = record(&mut stepper, self.options.tf(), self.progress)?;
            solution.selected_states = selected;
            solution.reselected_states = stepper.reselections().to_vec();
            Ok(solution)
        }
    }
    let visit = Simulate {
        model,
        trajectory,
        start,
        options,
        progress,
    };
    Mdl::visit_dummy_derivatives(visit).map_err(|reason| Error::NoDummyDerivatives {
        model: Mdl::INFO.name,
        reason,
    })?
}

/// The eigenvalues of the internal dynamics of `Mdl` at the consistent
/// state `at`, at rest, on `trajectory` ([`SelectedStates::eigenvalues`]
/// with the states selected there, the jets above the velocities 0 as at
/// rest); `None` for a flat crane, one without the system, a state not at
/// rest, or where the states cannot be selected.
pub fn eigenvalues_at<Mdl, Tr, const N: usize, const M: usize, const A: usize>(
    model: &Mdl,
    trajectory: Tr,
    at: &State<N, M, A>,
) -> Option<Vec<Complex<f64>>>
where
    Mdl: CraneModel<N, M, A>,
    Tr: Trajectory<A>,
{
    /// The linearisation, with the system's size.
    struct Linearise<'a, Mdl, Tr, const N: usize, const M: usize, const A: usize> {
        model: &'a Mdl,
        trajectory: Tr,
        at: &'a State<N, M, A>,
    }
    impl<Mdl, Tr, const N: usize, const M: usize, const A: usize> VisitDummyDerivatives<Mdl, N, M, A>
        for Linearise<'_, Mdl, Tr, N, M, A>
    where
        Tr: Trajectory<A>,
    {
        type Output = Option<Vec<Complex<f64>>>;
        fn visit<const J: usize>(self) -> Self::Output
        where
            Mdl: DummyDerivatives<N, M, A, J>,
        {
            if Mdl::DIMENSION == 0 {
                return None;
            }
            let mut problem = SelectedStates::<_, _, N, M, A, J>::new(self.model, self.trajectory);
            let mut z = DVector::zeros(J);
            let start = problem.start(self.at, 1.0, &mut z).ok()?;
            // (the jets above the velocities are known only at rest)
            start.at_rest.then(|| problem.eigenvalues(&z))?
        }
    }
    Mdl::visit_dummy_derivatives(Linearise { model, trajectory, at }).ok()?
}

/// A stepper of the reduced servo problem of the crane behind `model`
/// (`Box<Mdl>`, `Arc<Mdl>`) that owns its model and path, behind
/// [`Advance`], for long-lived runs such as an FMU instance: a flat crane's
/// [`DummyDerivativeStepper`], one
/// with internal dynamics a [`Stepper`] of [`SelectedStates`] on the scheme
/// of `options`.
#[allow(clippy::type_complexity)]
pub fn boxed_stepper<H, Tr, S, const N: usize, const M: usize, const A: usize>(
    model: H,
    trajectory: Tr,
    start: &State<N, M, A>,
    options: &Options<S>,
) -> Result<Box<dyn Advance<N, M, A, Model = H::Target> + Send>, Error>
where
    H: Deref<Target: CraneModel<N, M, A> + Sized> + Clone + Send + 'static,
    Tr: Trajectory<A> + Clone + Send + 'static,
    S: Method + 'static,
{
    /// The stepper, with the system's size.
    struct Build<'a, H, Tr, S: Method, const N: usize, const M: usize, const A: usize> {
        model: H,
        trajectory: Tr,
        start: &'a State<N, M, A>,
        options: &'a Options<S>,
    }
    impl<H, Tr, S, const N: usize, const M: usize, const A: usize> VisitDummyDerivatives<H::Target, N, M, A>
        for Build<'_, H, Tr, S, N, M, A>
    where
        H: Deref<Target: CraneModel<N, M, A> + Sized> + Clone + Send + 'static,
        Tr: Trajectory<A> + Clone + Send + 'static,
        S: Method + 'static,
    {
        type Output = Result<Box<dyn Advance<N, M, A, Model = H::Target> + Send>, Error>;
        fn visit<const J: usize>(self) -> Self::Output
        where
            H::Target: DummyDerivatives<N, M, A, J>,
        {
            if <H::Target as DummyDerivatives<N, M, A, J>>::DIMENSION == 0 {
                let stepper = DummyDerivativeStepper::<_, _, _, N, M, A, J>::new(
                    self.model,
                    self.trajectory,
                    self.start,
                    self.options,
                )?;
                return Ok(Box::new(stepper));
            }
            let stepper = SelectedStatesStepper::<_, _, _, N, M, A, J>::new(
                self.model,
                self.trajectory,
                self.start,
                self.options,
            )?;
            Ok(Box::new(stepper))
        }
    }
    let build = Build {
        model,
        trajectory,
        start,
        options,
    };
    H::Target::visit_dummy_derivatives(build).map_err(|reason| Error::NoDummyDerivatives {
        model: <H::Target as CraneModel<N, M, A>>::INFO.name,
        reason,
    })?
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A Jacobian whose last column is the sum of the first two: the
    /// greedy choice keeps the highest jets and leaves the lowest free.
    #[test]
    fn the_lowest_dependent_jet_is_the_state() {
        // columns: x^(0), x^(1), x^(2) of coordinate 0, u^(0) (unknown 1)
        let columns = [(0, 0), (0, 1), (0, 2), (1, 0)];
        // rows: x'' + x' + u = 0, u - x' = 0, (and one row left for the
        // state): x^(0) appears nowhere, so it is the state
        let jacobian = DMatrix::from_row_slice(
            4,
            4,
            &[
                0.0, 1.0, 1.0, 1.0, 0.0, -1.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0,
            ],
        );
        let chains = select(&jacobian.rows(0, 4).into_owned(), &columns, &[2, 0], 1, 2).unwrap();
        assert_eq!(
            chains,
            [Chain {
                coordinate: 0,
                order: 0,
                count: 2
            }]
        );
    }
}
