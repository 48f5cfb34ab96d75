//! The full expansion of the planar crane of sect. 5.1 with the minimal
//! coordinates of sect. 5.1.2, as a person would read it under
//! `cargo expand`. Regenerate with `UPDATE_EXPECT=1`.

use super::{navy_minimal_source, pretty, tokens};

#[test]
fn navy_planar_expansion() {
    let expansion = pretty(crate::expand(tokens(&navy_minimal_source())));
    expect_test::expect_file!["snapshots/navy_planar.rs"].assert_eq(&expansion);
}
