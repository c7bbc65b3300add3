//! The committed `include/sphera.h` must be what cbindgen generates from the sources.

#[test]
fn committed_header_matches_a_fresh_generation() {
    let path = sphera_tools::generators::header::header_path();
    let fresh = sphera_tools::generators::header::generate();
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
    let header =
        std::fs::read_to_string(sphera_tools::generators::header::header_path()).expect("header");
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
        } else if !line.starts_with('*') && line.split("/*").next().unwrap().contains('(') {
            // A declaration `type name(...` (before any trailing comment): the identifier
            // right before the first '('.
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
        header.contains("typedef struct SpheraProjectedPolygon {\n  uint32_t opaque["),
        "prepared values are not opaque"
    );
}

/// The header's `SPHERA_VERSION_*` macros are the version that the library reports
/// (`sphera_version()`, compiled from Cargo.toml's `version`), number by number.
#[test]
fn version_macros_match_the_library() {
    let header = std::fs::read_to_string(sphera_tools::generators::header::header_path())
        .expect("read include/sphera.h");
    let macro_value = |name: &str| -> String {
        let prefix = format!("#define {name} ");
        let values: Vec<&str> = header
            .lines()
            .filter_map(|line| line.strip_prefix(&prefix))
            .collect();
        assert_eq!(values.len(), 1, "{name} is defined {} times", values.len());
        values[0].trim().to_string()
    };
    // SAFETY: `sphera_version` returns a NUL-terminated string in static storage.
    let library = unsafe { std::ffi::CStr::from_ptr(sphera::ffi::sphera_version()) }
        .to_str()
        .expect("UTF-8")
        .to_string();
    let version = library.strip_suffix("+fma").unwrap_or(&library);
    assert_eq!(
        macro_value("SPHERA_VERSION_STRING"),
        format!("\"{version}\"")
    );
    let numbers: Vec<String> = version.split('.').map(str::to_string).collect();
    assert_eq!(numbers.len(), 3, "{version}");
    assert_eq!(macro_value("SPHERA_VERSION_MAJOR"), numbers[0]);
    assert_eq!(macro_value("SPHERA_VERSION_MINOR"), numbers[1]);
    assert_eq!(macro_value("SPHERA_VERSION_PATCH"), numbers[2]);
    assert_eq!(sphera_tools::generators::header::package_version(), version);
    assert!(sphera::ffi::sphera_check_version(
        numbers[0].parse().unwrap(),
        numbers[1].parse().unwrap()
    ));
}

/// The generator's macros for a few versions, and its refusal of malformed ones.
#[test]
fn version_macros_are_generated_from_the_version() {
    let macros = sphera_tools::generators::header::version_macros("12.3.45-rc.1");
    for line in [
        "#define SPHERA_VERSION_MAJOR 12",
        "#define SPHERA_VERSION_MINOR 3",
        "#define SPHERA_VERSION_PATCH 45",
        "#define SPHERA_VERSION_STRING \"12.3.45-rc.1\"",
    ] {
        assert!(
            macros.lines().any(|l| l == line),
            "{line} missing:\n{macros}"
        );
    }
    for bad in ["1.2", "1.x.3", "", "1.2.3.4"] {
        let result =
            std::panic::catch_unwind(|| sphera_tools::generators::header::version_macros(bad));
        assert!(result.is_err(), "{bad:?} accepted");
    }
}
