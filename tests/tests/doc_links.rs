//! The front door and the guide hold together: every relative link and
//! image in `README.md` and `docs/*.md` points at a file that exists, and
//! every `#anchor` at a heading of its target (GitHub's slugs: lower case,
//! punctuation dropped, spaces to `-`, a repeated heading numbered `-1`,
//! `-2`, ...). Fenced code blocks and inline code are not links.

use std::collections::HashSet;
use std::path::{Path, PathBuf};

/// The repository root (this crate is `tests/`).
fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("..")
}

/// The lines of `path` outside fenced code blocks.
fn prose(path: &Path) -> Vec<String> {
    let text = std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let mut fenced = false;
    let mut lines = Vec::new();
    for line in text.lines() {
        if line.trim_start().starts_with("```") {
            fenced = !fenced;
        } else if !fenced {
            lines.push(line.to_string());
        }
    }
    lines
}

/// GitHub's anchor of a heading's text.
fn slug(heading: &str) -> String {
    heading
        .trim()
        .to_lowercase()
        .chars()
        .filter(|c| c.is_alphanumeric() || matches!(c, '_' | '-' | ' '))
        .map(|c| if c == ' ' { '-' } else { c })
        .collect()
}

/// The anchors of the headings of a markdown file.
fn anchors(path: &Path) -> HashSet<String> {
    let mut seen = std::collections::HashMap::<String, usize>::new();
    let mut out = HashSet::new();
    for line in prose(path) {
        let level = line.chars().take_while(|&c| c == '#').count();
        let Some(text) = line.get(level..).and_then(|rest| rest.strip_prefix(' ')) else {
            continue;
        };
        if !(1..=6).contains(&level) {
            continue;
        }
        let base = slug(text);
        let n = seen.entry(base.clone()).or_insert(0);
        out.insert(if *n == 0 { base.clone() } else { format!("{base}-{n}") });
        *n += 1;
    }
    out
}

/// The targets of the `[text](target)` links of a text, outside inline code.
fn link_targets(text: &str) -> Vec<String> {
    // drop inline code spans
    let mut plain = String::new();
    for (i, part) in text.split('`').enumerate() {
        if i % 2 == 0 {
            plain.push_str(part);
        }
    }
    let mut targets = Vec::new();
    let mut rest = plain.as_str();
    while let Some(at) = rest.find("](") {
        let after = &rest[at + 2..];
        let end = after
            .find(|c: char| c == ')' || c.is_whitespace())
            .unwrap_or(after.len());
        if after[end..].starts_with(')') {
            targets.push(after[..end].to_string());
        }
        rest = &after[end..];
    }
    targets
}

#[test]
fn every_relative_link_of_the_readme_and_the_guide_resolves() {
    let root = root();
    let mut files = vec![root.join("README.md")];
    let mut docs: Vec<PathBuf> = std::fs::read_dir(root.join("docs"))
        .expect("docs/ exists")
        .map(|entry| entry.expect("a readable docs/").path())
        .filter(|path| path.extension().is_some_and(|e| e == "md"))
        .collect();
    docs.sort();
    assert!(docs.len() >= 10, "the guide has its chapters: {docs:?}");
    files.extend(docs);
    let (mut checked, mut broken) = (0, Vec::new());
    for file in &files {
        let text = prose(file).join("\n");
        for target in link_targets(&text) {
            if target.contains("://") || target.starts_with("mailto:") {
                continue;
            }
            checked += 1;
            let (path, anchor) = target.split_once('#').unwrap_or((&target, ""));
            let dest = if path.is_empty() {
                file.clone()
            } else {
                file.parent().expect("a file has a folder").join(path)
            };
            if !dest.exists() {
                broken.push(format!("{}: {target}: no file {}", file.display(), dest.display()));
            } else if !anchor.is_empty()
                && (dest.extension().is_none_or(|e| e != "md") || !anchors(&dest).contains(anchor))
            {
                broken.push(format!("{}: {target}: no heading #{anchor}", file.display()));
            }
        }
    }
    println!("{checked} relative links checked in {} files", files.len());
    assert!(checked > 100, "the links were found: {checked}");
    assert!(broken.is_empty(), "broken links:\n{}", broken.join("\n"));
}

/// The checker itself: a broken file, a broken anchor and a link in code
/// are told apart from good ones.
#[test]
fn the_link_checker_sees_links_anchors_and_code() {
    assert_eq!(
        slug("Results: the paper's planar cranes"),
        "results-the-papers-planar-cranes"
    );
    assert_eq!(
        slug("Schemes: backward Euler and BDF-2 to BDF-5"),
        "schemes-backward-euler-and-bdf-2-to-bdf-5"
    );
    assert_eq!(
        link_targets("see [a](docs/a.md#x), `[b](not/a/link.md)` and ![c](figures/c.svg)"),
        ["docs/a.md#x", "figures/c.svg"]
    );
}
