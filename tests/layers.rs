//! The module layers of `docs/design.md`: lower layers never import higher ones, and
//! no two top-level modules import each other (directly or round a loop). Read from
//! the sources (`crate::` paths outside comments and test modules).

use std::collections::{BTreeMap, BTreeSet};
use std::path::Path;

/// Top-level module → the top-level modules its code names through `crate::`.
fn imports(src: &Path) -> BTreeMap<String, BTreeSet<String>> {
    let mut files = Vec::new();
    let mut stack = vec![src.to_path_buf()];
    while let Some(dir) = stack.pop() {
        for e in std::fs::read_dir(&dir).unwrap().flatten() {
            let p = e.path();
            if p.is_dir() {
                stack.push(p);
            } else if p.extension().is_some_and(|x| x == "rs") {
                files.push(p);
            }
        }
    }
    let module_of = |p: &Path| {
        let rel = p.strip_prefix(src).unwrap();
        let first = rel
            .components()
            .next()
            .unwrap()
            .as_os_str()
            .to_string_lossy();
        first.trim_end_matches(".rs").to_string()
    };
    let modules: BTreeSet<String> = files.iter().map(|p| module_of(p)).collect();
    let mut out: BTreeMap<String, BTreeSet<String>> = BTreeMap::new();
    for f in &files {
        let module = module_of(f);
        let text = std::fs::read_to_string(f).unwrap();
        let code = text.split("#[cfg(test)]").next().unwrap();
        for line in code.lines().filter(|l| !l.trim_start().starts_with("//")) {
            for (i, _) in line.match_indices("crate::") {
                let name: String = line[i + 7..]
                    .chars()
                    .take_while(|c| c.is_alphanumeric() || *c == '_')
                    .collect();
                if name != module && modules.contains(&name) {
                    out.entry(module.clone()).or_default().insert(name);
                }
            }
        }
    }
    out
}

fn reaches(g: &BTreeMap<String, BTreeSet<String>>, from: &str, to: &str) -> bool {
    let mut seen = BTreeSet::new();
    let mut stack = vec![from.to_string()];
    while let Some(m) = stack.pop() {
        for n in g.get(&m).into_iter().flatten() {
            if n == to {
                return true;
            }
            if seen.insert(n.clone()) {
                stack.push(n.clone());
            }
        }
    }
    false
}

/// No module of `g` imports one that leads back to it.
fn assert_acyclic(g: &BTreeMap<String, BTreeSet<String>>, tree: &str) {
    for (m, targets) in g {
        for t in targets {
            assert!(
                !reaches(g, t, m),
                "{tree}: {m} imports {t}, which leads back to {m}"
            );
        }
    }
}

#[test]
fn the_library_has_no_import_cycles_and_its_core_imports_no_tool() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let g = imports(&root.join("src"));
    assert_acyclic(&g, "src");
    // The frame's path knows nothing of the tools, the service or the command line.
    for core in [
        "config",
        "projection",
        "grid",
        "mixed_pixels",
        "analysis",
        "verdict",
        "pipeline",
        "link",
        "memory",
    ] {
        for tool in ["sim", "inspect", "validate", "service", "cli", "bench"] {
            assert!(
                !g.get(core).is_some_and(|t| t.contains(tool)),
                "{core} imports {tool}"
            );
        }
    }
    let d = imports(&root.join("drivers/src"));
    assert_acyclic(&d, "drivers/src");
    // The camera contract knows no backend.
    let camera = d.get("camera").cloned().unwrap_or_default();
    for backend in ["v4l", "freenect", "fake", "source"] {
        assert!(
            !camera.contains(backend),
            "drivers: camera.rs imports {backend}"
        );
    }
}
