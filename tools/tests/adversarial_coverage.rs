//! Every function that `include/sphera.h` exports is called by the adversarial C test
//! (`ffi-tests/test_adversarial.c`), so that a new entry point cannot ship without being
//! driven with special floats, null pointers and the hard cases (issue 8).

use sphera_tools::repository_root;

/// The names of the functions the header declares: `sphera_…(` at the start of a
/// declaration, after its return type.
fn exported_functions(header: &str) -> Vec<String> {
    let mut names: Vec<String> = Vec::new();
    for line in header.lines() {
        // The code before any trailing comment.
        let line = line.trim_start().split("/*").next().unwrap_or_default();
        if line.starts_with('*') || line.starts_with("#") {
            continue;
        }
        let Some(start) = line.find("sphera_") else {
            continue;
        };
        let rest = &line[start..];
        let Some(end) = rest.find('(') else {
            continue;
        };
        let name = &rest[..end];
        if name.chars().all(|c| c.is_ascii_alphanumeric() || c == '_')
            && !names.iter().any(|n| n == name)
        {
            names.push(name.to_string());
        }
    }
    names
}

/// Whether `name` occurs in `source` as a whole identifier (called, or passed to the
/// family macro `CHECK_FAMILY`, which calls it).
fn calls(source: &str, name: &str) -> bool {
    source.match_indices(name).any(|(at, _)| {
        let before = source[..at].chars().next_back();
        let after = source[at + name.len()..].chars().next();
        let is_ident = |c: Option<char>| c.is_some_and(|c| c.is_ascii_alphanumeric() || c == '_');
        !is_ident(before) && !is_ident(after)
    })
}

#[test]
fn every_exported_function_is_driven_by_the_adversarial_test() {
    let root = repository_root();
    let header = std::fs::read_to_string(root.join("include/sphera.h")).expect("read the header");
    let suite = std::fs::read_to_string(root.join("ffi-tests/test_adversarial.c"))
        .expect("read the adversarial test");
    let functions = exported_functions(&header);
    assert!(
        functions.len() > 100,
        "only {} functions found in the header",
        functions.len()
    );
    let missing: Vec<&String> = functions
        .iter()
        .filter(|name| !calls(&suite, name))
        .collect();
    assert!(
        missing.is_empty(),
        "{} exported functions are not called by ffi-tests/test_adversarial.c: {missing:?}",
        missing.len()
    );
}
