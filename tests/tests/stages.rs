//! The reduced (dummy-derivative) system solved stage by stage: its
//! Jacobian is block lower triangular by Pryce's stages on every flat
//! built-in crane, and the inputs of a run solved stage by stage are those
//! of the same run solved whole (one LU of all the jets), at every step,
//! with at most 1 % more Newton iterations (`crane_tests::stages`; a user's
//! crane of path order 6 in `user_cranes.rs`). Stage by stage, each stage's residual
//! is evaluated at the stages before it as solved, and only the system
//! Jacobian is evaluated, not the blocks left of the diagonal.

use crane_models::registry::{BuiltIn, Registry};
use crane_tests::stages::{OnCrane, check};

#[test]
fn every_flat_built_in_is_solved_stage_by_stage_as_whole() {
    let registry = BuiltIn;
    let mut compared = Vec::new();
    for entry in registry.entries() {
        if let Some(comparison) = registry.visit(entry.name, OnCrane).flatten() {
            check(&comparison);
            compared.push(comparison.crane);
        }
    }
    // the eight flat built-ins (coupled-trolley has internal dynamics)
    assert_eq!(compared.len(), 8, "{compared:?}");
    // navy-planar: 26 jets in three stages (the jets of order c - 2, c - 1
    // and c of its 10 unknowns)
    let navy = registry.visit("navy-planar", OnCrane).flatten().unwrap();
    assert_eq!(navy.blocks, [8, 8, 10]);
    // its first two stages' blocks are parts of its last's (the 10 x 10
    // system Jacobian): one LU per Newton iteration, not three, but where
    // an iteration follows an update below 1e-6 relative, whose factors it
    // keeps (472 iterations, 411 LUs over the 400 steps)
    assert_eq!(navy.factorisations.0 + navy.chord_updates, navy.iterations.0);
    assert!(
        navy.factorisations.0 * 100 <= 105 * navy.steps,
        "{} LUs in {} steps",
        navy.factorisations.0,
        navy.steps
    );
    // the jets predicted through the last eight steps are within Newton's
    // residual test at most steps, or within an update whose error the
    // quadratic term of earlier steps puts at round-off, and the step then
    // ends after one iteration: 1.18 per step (1.40 on the residual test
    // alone, 2.01 through four steps)
    assert!(
        navy.iterations.0 * 10 <= 12 * navy.steps,
        "{} iterations in {} steps",
        navy.iterations.0,
        navy.steps
    );
}
