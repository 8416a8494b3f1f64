//! The crate graph that `docs/architecture.md` draws is the one the manifests declare: every
//! normal dependency of one workspace crate on another is an arrow of the page's `crate-graph`
//! block, and every arrow there is such a dependency (dev-dependencies are not arrows, nor is
//! `workspace-hack`, which only pins the features of third-party crates).

use std::collections::BTreeSet;
use std::path::Path;
use std::process::Command;

/// An arrow `from → to` between crates, named without the `tvf-` prefix.
type Arrow = (String, String);

fn short(name: &str) -> String {
    name.strip_prefix("tvf-").unwrap_or(name).to_string()
}

/// The arrows of the fenced ```` ```crate-graph ```` block of `docs/architecture.md`: one line
/// per crate, `a → b, c`.
fn documented_arrows(page: &str) -> BTreeSet<Arrow> {
    let block = page
        .split("```crate-graph\n")
        .nth(1)
        .and_then(|rest| rest.split("```").next())
        .expect("docs/architecture.md has a ```crate-graph block");
    let mut arrows = BTreeSet::new();
    for line in block.lines().filter(|l| !l.trim().is_empty()) {
        let (from, targets) = line
            .split_once('→')
            .unwrap_or_else(|| panic!("not `a → b, c`: {line:?}"));
        for to in targets.split(',') {
            arrows.insert((from.trim().to_string(), to.trim().to_string()));
        }
    }
    arrows
}

/// The normal dependencies between workspace members, from `cargo metadata` (target-specific
/// ones included; dev- and build-dependencies left out, and so is `workspace-hack`, which only
/// pins features).
fn declared_arrows(root: &Path) -> BTreeSet<Arrow> {
    let cargo = std::env::var_os("CARGO").unwrap_or_else(|| "cargo".into());
    let output = Command::new(cargo)
        .args([
            "metadata",
            "--format-version",
            "1",
            "--no-deps",
            "--offline",
        ])
        .current_dir(root)
        .output()
        .expect("cargo metadata runs");
    assert!(
        output.status.success(),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
    let metadata: serde_json::Value = serde_json::from_slice(&output.stdout).expect("JSON");
    let packages = metadata["packages"].as_array().expect("packages");
    let members: BTreeSet<&str> = packages
        .iter()
        .map(|p| p["name"].as_str().unwrap())
        .collect();
    let mut arrows = BTreeSet::new();
    for package in packages {
        for dependency in package["dependencies"].as_array().unwrap() {
            let name = dependency["name"].as_str().unwrap();
            if dependency["kind"].is_null()
                && members.contains(name)
                && name != "tvf-workspace-hack"
            {
                arrows.insert((short(package["name"].as_str().unwrap()), short(name)));
            }
        }
    }
    arrows
}

#[test]
fn the_architecture_page_lists_exactly_the_declared_dependencies() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).parent().unwrap();
    let page = std::fs::read_to_string(root.join("docs/architecture.md")).unwrap();
    let documented = documented_arrows(&page);
    let declared = declared_arrows(root);
    let show = |arrows: Vec<&Arrow>| -> String {
        arrows
            .iter()
            .map(|(a, b)| format!("  {a} → {b}\n"))
            .collect()
    };
    let undocumented: Vec<&Arrow> = declared.difference(&documented).collect();
    let stale: Vec<&Arrow> = documented.difference(&declared).collect();
    assert!(
        undocumented.is_empty() && stale.is_empty(),
        "docs/architecture.md's crate-graph block and the manifests disagree.\n\
         Declared in a Cargo.toml, missing on the page:\n{}\
         On the page, declared nowhere:\n{}",
        show(undocumented),
        show(stale)
    );
}

#[test]
fn the_page_block_is_read_line_by_line() {
    let page = "text\n```crate-graph\na → b, c\nd → a\n```\nmore";
    let arrows = documented_arrows(page);
    let expected: BTreeSet<Arrow> = [("a", "b"), ("a", "c"), ("d", "a")]
        .into_iter()
        .map(|(x, y)| (x.to_string(), y.to_string()))
        .collect();
    assert_eq!(arrows, expected);
}
