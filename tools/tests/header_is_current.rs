//! The committed `include/sphera.h` must be what cbindgen generates from the sources.

#[test]
fn committed_header_matches_a_fresh_generation() {
    let path = sphera_tools::header::header_path();
    let fresh = sphera_tools::header::generate();
    let committed = std::fs::read_to_string(&path).unwrap_or_default();
    if committed != fresh {
        let first_difference = committed
            .lines()
            .zip(fresh.lines())
            .position(|(a, b)| a != b)
            .unwrap_or_else(|| committed.lines().count().min(fresh.lines().count()));
        panic!(
            "{} is not current (first difference at line {}); \
             run `cargo run -p sphera-tools --bin generate_header` to refresh it",
            path.display(),
            first_difference + 1
        );
    }
}

/// Nothing unprefixed leaks into C's global namespace: every macro, type and function
/// the header declares is named `SPHERA_…`, `Sphera…` or `sphera_…` (issue 19, 3: the
/// tables' `LTC_TABLE_SIZE` and friends, and `CapIntersection`, leaked before), and the
/// header is the one the generator writes for C users (prepared values opaque, no
/// rustdoc links).
#[test]
fn every_name_in_the_header_is_prefixed() {
    let header = std::fs::read_to_string(sphera_tools::header::header_path()).expect("header");
    let mut names = Vec::new();
    for line in header.lines() {
        let line = line.trim_start();
        if let Some(rest) = line.strip_prefix("#define ") {
            names.push(rest.split_whitespace().next().unwrap_or("").to_string());
        } else if let Some(rest) = ["typedef struct ", "typedef union ", "typedef enum "]
            .iter()
            .find_map(|p| line.strip_prefix(p))
        {
            names.push(rest.split_whitespace().next().unwrap_or("").to_string());
        } else if !line.starts_with('*') && !line.starts_with("/*") && line.contains('(') {
            // A declaration `type name(...`: the identifier right before the first '('.
            let before = &line[..line.find('(').unwrap()];
            if let Some(name) = before
                .split(|c: char| !(c.is_alphanumeric() || c == '_'))
                .next_back()
                && !name.is_empty()
                && !before.trim_start().starts_with('#')
            {
                names.push(name.to_string());
            }
        }
    }
    let allowed =
        |n: &str| n.starts_with("SPHERA_") || n.starts_with("Sphera") || n.starts_with("sphera_");
    let leaks: Vec<&String> = names.iter().filter(|n| !allowed(n)).collect();
    assert!(
        names.len() > 100,
        "the scan found only {} names",
        names.len()
    );
    assert!(
        leaks.is_empty(),
        "unprefixed names in the header: {leaks:?}"
    );
    assert!(
        !header.contains("]("),
        "a rustdoc link is left in the header"
    );
    assert!(
        header.contains("typedef struct SpheraProjectedSolidAnglePolygon {\n  /**\n   * Opaque"),
        "prepared values are not opaque"
    );
}
