//! The programs in `examples/` build against an installed sphera and print what they
//! should: `install.sh` installs the library into a scratch prefix, and the examples are
//! compiled against it (C99 and C++11, warnings as errors), run, and their estimates
//! checked against values computed here (Lambert's closed form for the quad light) or
//! by the program itself (a brute-force estimate for the sphere light).
//! `examples/check-install.sh` does the same through CMake's `find_package(sphera)` and
//! `pkg-config`; it needs cmake and pkg-config (`bench/install-deps.sh`).

use std::path::{Path, PathBuf};
use std::process::Command;
use std::sync::OnceLock;

use sphera_tools::repository_root;

/// The programs of `examples/`; `every_example_has_a_check` keeps the list complete.
const EXAMPLES: [&str; 2] = ["quad_light.c", "sphere_light_ggx.cpp"];

/// Runs a command and returns its stdout, or panics with its output.
fn run(command: &mut Command, what: &str) -> String {
    let output = command
        .output()
        .unwrap_or_else(|error| panic!("cannot run {what}: {error}"));
    let stdout = String::from_utf8_lossy(&output.stdout).into_owned();
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(
        output.status.success(),
        "{what} failed with {}:\n{stdout}\n{stderr}",
        output.status
    );
    stdout
}

/// The environment of the nested scripts: this cargo, and the target directory of the
/// C ABI tests (`tools/tests/c_abi.rs` builds the same `cargo build --release -p sphera
/// --lib` there), off the outer build's lock.
fn nested(command: &mut Command) -> &mut Command {
    command
        .current_dir(repository_root())
        .env("CARGO", env!("CARGO"))
        .env(
            "CARGO_TARGET_DIR",
            repository_root().join("target").join("c-abi"),
        )
        .env_remove("CARGO_BUILD_TARGET")
}

/// `PREFIX=<scratch> bash install.sh`, once per test process; the prefix.
fn installed_prefix() -> &'static Path {
    static PREFIX: OnceLock<PathBuf> = OnceLock::new();
    PREFIX.get_or_init(|| {
        let prefix = PathBuf::from(env!("CARGO_TARGET_TMPDIR"))
            .join("examples")
            .join("prefix");
        let _ = std::fs::remove_dir_all(&prefix);
        run(
            nested(
                Command::new("bash")
                    .arg(repository_root().join("install.sh"))
                    .env("PREFIX", &prefix),
            ),
            "install.sh",
        );
        prefix
    })
}

/// Compiles `examples/<source>` against the installed prefix as strict C99 or C++11
/// (by its extension) with `cc` / `c++` (or `$CC` / `$CXX`), runs it and returns its
/// output.
fn build_and_run(source: &str) -> String {
    let prefix = installed_prefix();
    let cpp = source.ends_with(".cpp");
    let compiler = if cpp {
        std::env::var("CXX").unwrap_or_else(|_| "c++".into())
    } else {
        std::env::var("CC").unwrap_or_else(|_| "cc".into())
    };
    let program = PathBuf::from(env!("CARGO_TARGET_TMPDIR"))
        .join("examples")
        .join(source.split('.').next().unwrap());
    run(
        Command::new(&compiler)
            .arg(if cpp { "-std=c++11" } else { "-std=c99" })
            .args(["-O2", "-Wall", "-Wextra", "-Werror", "-pedantic"])
            .arg(repository_root().join("examples").join(source))
            .arg("-I")
            .arg(prefix.join("include"))
            .arg(prefix.join("lib").join("libsphera.a"))
            .arg("-lm")
            .arg("-o")
            .arg(&program),
        &format!("{compiler} {source}"),
    );
    let output = run(&mut Command::new(&program), source);
    println!("{source}:\n{output}");
    output
}

/// The numbers of the output line that starts with `label ` (the words in between
/// skipped).
fn numbers(output: &str, label: &str) -> Vec<f64> {
    let line = output
        .lines()
        .find(|line| line.starts_with(&format!("{label} ")))
        .unwrap_or_else(|| panic!("no line {label:?} in:\n{output}"));
    line.split_whitespace()
        .filter_map(|word| word.parse().ok())
        .collect()
}

use sphera_test_support::{D3, cross, dot, normalize, sub};

/// Lambert's formula: the projected solid angle `Φ = ½ Σ θ_i n·(v_i × v_{i+1})/|…|` of a
/// polygon wholly above the horizon of `normal` at `point`, in f64.
fn lambert_projected_solid_angle(point: D3, normal: D3, polygon: &[D3]) -> f64 {
    let normal = normalize(normal);
    let dirs: Vec<D3> = polygon.iter().map(|&v| normalize(sub(v, point))).collect();
    let mut sum = 0.0;
    for i in 0..dirs.len() {
        let (a, b) = (dirs[i], dirs[(i + 1) % dirs.len()]);
        let c = cross(a, b);
        let sine = dot(c, c).sqrt();
        sum += sine.atan2(dot(a, b)) * dot(normal, c) / sine;
    }
    (0.5 * sum).abs()
}

/// The irradiance of `examples/quad_light.c`'s configuration (its constants, copied
/// here): radiance 3 times Lambert's projected solid angle.
fn quad_light_irradiance() -> f64 {
    let f = |x: f32| x as f64;
    let quad = [
        [f(-1.0), f(-0.5), f(2.0)],
        [f(1.0), f(-0.5), f(2.0)],
        [f(1.0), f(0.5), f(2.5)],
        [f(-1.0), f(0.5), f(2.5)],
    ];
    3.0 * lambert_projected_solid_angle([f(0.1), f(0.2), 0.0], [0.0, f(0.6), f(0.8)], &quad)
}

/// Checks the output of `quad_light`: the MIS estimate agrees with Lambert's formula
/// within 5 standard errors, which are below 1% of it, and the library's closed form
/// (`radiance × Φ`) within 1e-5.
fn check_quad_light(output: &str) {
    let exact = quad_light_irradiance();
    let estimate = numbers(output, "irradiance");
    assert_eq!(estimate.len(), 2, "{output}");
    let (mean, error) = (estimate[0], estimate[1]);
    println!("quad light: {mean} ± {error}, Lambert's formula {exact}");
    assert!(
        error > 0.0 && error < 1e-2 * exact,
        "standard error {error}"
    );
    assert!(
        (mean - exact).abs() <= 5.0 * error + 1e-6 * exact,
        "estimate {mean} ± {error}, Lambert's formula {exact}"
    );
    let library = numbers(output, "exact");
    assert_eq!(library.len(), 1, "{output}");
    assert!(
        (library[0] - exact).abs() <= 1e-5 * exact,
        "the library's radiance × Φ {} against {exact}",
        library[0]
    );
}

/// Checks the output of `sphere_light_ggx`: per channel, the MIS estimate (joint
/// sampling + GGX sampling) and the brute-force one (uniform cap sampling) agree within
/// 5 combined standard errors, each below 1% of the value, the channels follow the
/// coloured Fresnel (red > green > blue), the MIS estimate's variance per sample (two
/// samples a round) is below uniform cap sampling's (four a round; for this light, 19°
/// wide, and roughness 0.3), and the biased real-time shading lies within 25% of the
/// estimate.
fn check_sphere_light(output: &str) {
    let mis = numbers(output, "mis");
    let uniform = numbers(output, "uniform");
    let real_time = numbers(output, "real-time");
    assert_eq!(
        (mis.len(), uniform.len(), real_time.len()),
        (6, 6, 3),
        "{output}"
    );
    for c in 0..3 {
        let (m, m_error, u, u_error) = (mis[c], mis[3 + c], uniform[c], uniform[3 + c]);
        println!(
            "channel {c}: MIS {m} ± {m_error}, uniform {u} ± {u_error}, real-time {}",
            real_time[c]
        );
        assert!(m > 0.0 && m_error > 0.0 && m_error < 1e-2 * m, "{output}");
        assert!(u_error > 0.0 && u_error < 1e-2 * u, "{output}");
        assert!(
            m_error * 2f64.sqrt() < u_error * 2.0,
            "channel {c}: MIS ± {m_error} (2 samples a round) is not better than uniform \
             cap sampling ± {u_error} (4 a round)"
        );
        let combined = (m_error * m_error + u_error * u_error).sqrt();
        assert!(
            (m - u).abs() <= 5.0 * combined,
            "channel {c}: MIS {m} ± {m_error} against uniform cap sampling {u} ± {u_error}"
        );
        assert!(
            (real_time[c] - m).abs() <= 0.25 * m,
            "channel {c}: real-time {} against {m}",
            real_time[c]
        );
    }
    assert!(mis[0] > mis[1] && mis[1] > mis[2], "{output}");
}

#[test]
fn quad_light_matches_lamberts_formula() {
    check_quad_light(&build_and_run("quad_light.c"));
}

#[test]
fn sphere_light_ggx_agrees_with_uniform_cap_sampling() {
    check_sphere_light(&build_and_run("sphere_light_ggx.cpp"));
}

/// `examples/check-install.sh`: install, then CMake and pkg-config builds of both
/// examples and a pkg-config build of `quad_light` against the shared library, whose
/// five outputs pass the checks above, and the CMake version rule.
#[test]
fn installed_examples_build_with_cmake_and_pkg_config() {
    let output = run(
        nested(
            Command::new("bash").arg(repository_root().join("examples").join("check-install.sh")),
        ),
        "examples/check-install.sh (needs cmake and pkg-config: bash bench/install-deps.sh)",
    );
    println!("{output}");
    let mut checked = Vec::new();
    for section in output.split("== ").skip(1) {
        let (title, body) = section.split_once('\n').unwrap_or((section, ""));
        match title.split_once(": ") {
            Some((_, "quad_light")) => check_quad_light(body),
            Some((_, "sphere_light_ggx")) => check_sphere_light(body),
            _ => {
                assert!(
                    title.starts_with("versions: "),
                    "unexpected section {title}"
                );
                continue;
            }
        }
        checked.push(title.to_string());
    }
    let mut expected: Vec<String> = [
        "cmake: quad_light",
        "cmake: sphere_light_ggx",
        "pkg-config: quad_light",
        "pkg-config: sphere_light_ggx",
    ]
    .map(String::from)
    .to_vec();
    if cfg!(target_os = "linux") {
        // The soname: libsphera.so.MAJOR.MINOR before 1.0, libsphera.so.MAJOR after.
        let version = sphera_tools::generators::header::package_version();
        let numbers: Vec<&str> = version.split('.').collect();
        let soname = if numbers[0] == "0" {
            format!("libsphera.so.0.{}", numbers[1])
        } else {
            format!("libsphera.so.{}", numbers[0])
        };
        expected.push(format!("shared ({soname}): quad_light"));
    }
    assert_eq!(checked, expected, "{output}");
    assert!(output.contains("== versions: "), "{output}");
}

#[test]
fn every_example_has_a_check() {
    let mut found: Vec<String> = std::fs::read_dir(repository_root().join("examples"))
        .expect("read examples/")
        .map(|entry| {
            entry
                .expect("read examples/")
                .file_name()
                .to_string_lossy()
                .into_owned()
        })
        .filter(|name| name.ends_with(".c") || name.ends_with(".cpp"))
        .collect();
    found.sort();
    assert_eq!(
        found, EXAMPLES,
        "add a check for each program in examples/ to tools/tests/examples.rs"
    );
}

/// The C program that README.md shows is `examples/quad_light.c`, which the tests above
/// build and check: the README's example cannot drift from a program that runs.
#[test]
fn the_readme_example_is_examples_quad_light_c() {
    let readme = std::fs::read_to_string(repository_root().join("README.md")).expect("README");
    let start = readme.find("```c\n").expect("a C block in README.md") + "```c\n".len();
    let end = start + readme[start..].find("```").expect("the block's end");
    let program = std::fs::read_to_string(repository_root().join("examples/quad_light.c"))
        .expect("examples/quad_light.c");
    assert_eq!(
        &readme[start..end],
        program,
        "README.md's C example is not examples/quad_light.c"
    );
}
