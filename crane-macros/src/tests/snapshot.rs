//! The full expansion of the planar crane of sect. 5.1, as a person would
//! read it under `cargo expand`. Regenerate with `UPDATE_EXPECT=1`.

use super::{navy_planar, pretty};

#[test]
fn navy_planar_expansion() {
    let expansion = pretty(crate::expand(navy_planar()));
    expect_test::expect_file!["snapshots/navy_planar.rs"].assert_eq(&expansion);
}
