//! UI tests of the `crane_model!` DSL (trybuild): every DSL mistake is a
//! compile error with a message and a span on the culprit, checked against
//! the `.stderr` next to each case in `tests/ui/<category>/<name>.rs`; and
//! the valid cranes of `tests/ui/pass/` compile and run in a user crate that
//! depends on crane-runtime.
//!
//! After changing a message: `TRYBUILD=overwrite cargo test -p crane-macros
//! --test ui`, then read the diff of the `.stderr` files.

#[test]
fn ui() {
    let t = trybuild::TestCases::new();
    // every category folder but `pass` (a plain `tests/ui/*/*.rs` would
    // also expect the pass cases to fail)
    let mut categories: Vec<String> = std::fs::read_dir("tests/ui")
        .expect("tests/ui exists")
        .map(|entry| entry.expect("readable tests/ui"))
        .filter(|entry| entry.path().is_dir() && entry.file_name() != "pass")
        .map(|entry| entry.file_name().to_string_lossy().into_owned())
        .collect();
    categories.sort();
    assert!(!categories.is_empty(), "no compile-fail categories in tests/ui");
    for category in categories {
        t.compile_fail(format!("tests/ui/{category}/*.rs"));
    }
    t.pass("tests/ui/pass/*.rs");
}
