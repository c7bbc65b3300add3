//! The C ABI tested from C: builds the real static library (`libsphera.a`, without the
//! `std` feature), compiles every `ffi-tests/*.c` against `include/sphera.h` as strict
//! C99, links it with nothing but `libsphera.a -lm`, runs it, and checks that the header
//! also compiles as C++11 and describes the same struct layouts as the Rust code.

use std::path::{Path, PathBuf};
use std::process::Command;
use std::sync::OnceLock;

use sphera_tools::repository_root;

/// The C test programs; `every_c_test_file_has_a_test` keeps this list complete.
const C_TESTS: [&str; 19] = [
    "test_polygon_clip",
    "test_projected_polygon",
    "test_solid_angle_polygon",
    "test_solid_angle_sizes",
    "test_baselines",
    "test_frame",
    "test_warps",
    "test_ggx",
    "test_mis",
    "test_ltc",
    "test_polygon_light",
    "test_phase",
    "test_sphere_caps",
    "test_sptd",
    "test_vsgl",
    "test_sg",
    "test_adversarial",
    "test_determinism",
    "test_version",
];

/// The C tests that link the example tracer's sources (`bench/src`) and Embree 3
/// besides `libsphera.a`; they need `libembree-dev` and `libpng-dev` installed
/// (`bench/install-deps.sh`).
const TRACER_TESTS: [&str; 2] = ["test_tracer_end_to_end", "test_tracer_indirect"];

/// The tracer's sources that the tracer tests link (all but its `main.c`).
const TRACER_SOURCES: [&str; 5] = [
    "scenes.c",
    "techniques.c",
    "render.c",
    "image.c",
    "indirect.c",
];

const C_FLAGS: [&str; 5] = ["-std=c99", "-Wall", "-Wextra", "-Werror", "-pedantic"];

/// The host's target triple, from the constants of `std` (the tests run on the host).
fn host_triple() -> String {
    use std::env::consts::{ARCH, OS};
    match OS {
        "linux" => format!("{ARCH}-unknown-linux-gnu"),
        "macos" => format!("{ARCH}-apple-darwin"),
        "windows" => format!("{ARCH}-pc-windows-msvc"),
        other => format!("{ARCH}-unknown-{other}"),
    }
}

/// The C (or C++) compiler that the `cc` crate picks for the host, as a command.
fn compiler(cpp: bool) -> Command {
    let triple = host_triple();
    cc::Build::new()
        .cpp(cpp)
        .target(&triple)
        .host(&triple)
        .opt_level(2)
        .debug(false)
        .cargo_metadata(false)
        .get_compiler()
        .to_command()
}

/// A scratch directory for the compiled programs.
fn output_dir() -> PathBuf {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("c-abi");
    std::fs::create_dir_all(&dir).expect("create the scratch directory");
    dir
}

/// Runs a command, returning its combined output, or a message with that output when
/// it cannot start or exits with a failure.
fn run(command: &mut Command) -> Result<String, String> {
    // The command without its environment (the `cc` crate clears and sets it).
    let description = std::iter::once(command.get_program())
        .chain(command.get_args())
        .map(|part| part.to_string_lossy())
        .collect::<Vec<_>>()
        .join(" ");
    let output = command
        .output()
        .map_err(|error| format!("cannot run {description}: {error}"))?;
    let text = format!(
        "{}{}",
        String::from_utf8_lossy(&output.stdout),
        String::from_utf8_lossy(&output.stderr)
    );
    if output.status.success() {
        Ok(text)
    } else {
        Err(format!(
            "{description} failed with {}:\n{text}",
            output.status
        ))
    }
}

/// Builds `libsphera.a` once per test process with a nested
/// `cargo build --release -p sphera --lib`. Its own target directory keeps it off the
/// outer build's lock and builds the core alone, so the `std` feature that the tools
/// turn on is not unified into it.
fn static_library() -> &'static Path {
    static LIBRARY: OnceLock<Result<PathBuf, String>> = OnceLock::new();
    let result = LIBRARY.get_or_init(|| {
        let root = repository_root();
        let target_dir = root.join("target").join("c-abi");
        run(Command::new(env!("CARGO"))
            .args(["build", "--release", "-p", "sphera", "--lib"])
            .current_dir(&root)
            .env("CARGO_TARGET_DIR", &target_dir)
            .env_remove("CARGO_BUILD_TARGET"))?;
        let library = target_dir.join("release").join("libsphera.a");
        if library.is_file() {
            Ok(library)
        } else {
            Err(format!(
                "the nested build did not produce {}",
                library.display()
            ))
        }
    });
    match result {
        Ok(path) => path,
        Err(message) => panic!("building the static library failed: {message}"),
    }
}

/// Compiles `source` with the given language flags against `include/`, links it with
/// `libsphera.a -lm` only, runs it and panics (naming `what`) unless every step
/// succeeds; prints the program's output.
fn build_and_run(source: &Path, program: &Path, cpp: bool, flags: &[&str], what: &str) {
    let root = repository_root();
    let compiled = run(compiler(cpp)
        .args(flags)
        .arg("-I")
        .arg(root.join("include"))
        .arg(source)
        .arg(static_library())
        .arg("-lm")
        .arg("-o")
        .arg(program));
    if let Err(message) = compiled {
        panic!("{what} does not compile and link:\n{message}");
    }
    match run(&mut Command::new(program)) {
        Ok(output) => println!("{what}:\n{output}"),
        Err(message) => panic!("{what} failed:\n{message}"),
    }
}

/// Compiles `ffi-tests/<name>.c` as strict C99, links it with `libsphera.a -lm` only,
/// runs it and asserts that it exits with status 0.
fn run_c_test(name: &str) {
    let source = repository_root()
        .join("ffi-tests")
        .join(format!("{name}.c"));
    build_and_run(
        &source,
        &output_dir().join(name),
        false,
        &C_FLAGS,
        &format!("{name}.c"),
    );
}

#[test]
fn test_polygon_clip() {
    run_c_test("test_polygon_clip");
}

#[test]
fn test_solid_angle_polygon() {
    run_c_test("test_solid_angle_polygon");
}

#[test]
fn test_solid_angle_sizes() {
    run_c_test("test_solid_angle_sizes");
}

#[test]
fn test_baselines() {
    run_c_test("test_baselines");
}

#[test]
fn test_frame() {
    run_c_test("test_frame");
}

#[test]
fn test_projected_polygon() {
    run_c_test("test_projected_polygon");
}

#[test]
fn test_warps() {
    run_c_test("test_warps");
}

#[test]
fn test_ggx() {
    run_c_test("test_ggx");
}

#[test]
fn test_mis() {
    run_c_test("test_mis");
}

#[test]
fn test_ltc() {
    run_c_test("test_ltc");
}

#[test]
fn test_polygon_light() {
    run_c_test("test_polygon_light");
}

#[test]
fn test_phase() {
    run_c_test("test_phase");
}

#[test]
fn test_sphere_caps() {
    run_c_test("test_sphere_caps");
}

#[test]
fn test_sptd() {
    run_c_test("test_sptd");
}

#[test]
fn test_vsgl() {
    run_c_test("test_vsgl");
}

#[test]
fn test_sg() {
    run_c_test("test_sg");
}

#[test]
fn test_adversarial() {
    run_c_test("test_adversarial");
}

/// The header's version macros against `sphera_version()`, and `sphera_check_version`.
#[test]
fn test_version() {
    run_c_test("test_version");
}

/// Runs in the test's working directory (`tools/`), from which the program finds
/// `../ffi-tests/determinism_table.txt`.
#[test]
fn test_determinism() {
    run_c_test("test_determinism");
}

/// Compiles `main` with the tracer's sources into the program `name`, linking
/// `libsphera.a`, Embree 3, libpng and pthreads; panics with the compiler's output when
/// that fails.
fn build_with_tracer(name: &str, main: &Path) -> PathBuf {
    let root = repository_root();
    let program = output_dir().join(name);
    let mut command = compiler(false);
    command
        .args(C_FLAGS)
        .arg("-I")
        .arg(root.join("include"))
        .arg("-I")
        .arg(root.join("bench").join("src"))
        .arg("-I")
        .arg(root.join("ffi-tests"))
        .arg(main);
    for source in TRACER_SOURCES {
        command.arg(root.join("bench").join("src").join(source));
    }
    command
        .arg(static_library())
        .args(["-lembree3", "-lpng", "-lpthread", "-lm", "-o"])
        .arg(&program);
    if let Err(message) = run(&mut command) {
        panic!(
            "{name} does not compile and link (Embree 3 and libpng must be installed: \
             bash bench/install-deps.sh):\n{message}"
        );
    }
    program
}

/// Compiles `bench/tests/<name>.c` (the tracer's own tests, beside it) with the tracer's
/// sources, runs it and asserts that it exits with status 0.
fn run_tracer_test(name: &str) {
    let root = repository_root();
    let program = build_with_tracer(
        name,
        &root.join("bench").join("tests").join(format!("{name}.c")),
    );
    match run(&mut Command::new(&program)) {
        Ok(output) => println!("{name}.c:\n{output}"),
        Err(message) => panic!("{name}.c failed:\n{message}"),
    }
}

/// Issue 16 (8): the tracer's command line (`bench/src/main.c`, built with the
/// tracer's sources): every bad value gets a message and exit status 2 (an infinite or
/// huge time budget ran without end, a NaN or non-numeric exposure was read as a black
/// image or 0, `--curve` without `--reference` wrote only a header); a NaN reference
/// pixel gives `"rmse": null`, which is JSON, not `nan`; the indirect scene says why it
/// exits 1 on an unwritable output.
#[test]
fn tracer_command_line_rejects_bad_values() {
    let root = repository_root();
    let program = build_with_tracer(
        "sphera-trace-cli",
        &root.join("bench").join("src").join("main.c"),
    );
    let small = ["--width", "8", "--height", "8", "--spp", "1", "--quiet"];
    for bad in [
        vec!["--time-ms", "inf"],
        vec!["--time-ms", "1e300"],
        vec!["--exposure", "nan"],
        vec!["--exposure", "abc"],
        vec!["--obj-scale", "inf"],
        vec!["--curve", "curve.csv"],
        vec!["--scene", "indirect", "--exposure", "nan"],
    ] {
        let output = Command::new(&program)
            .args(&bad)
            .args(small)
            .output()
            .expect("run");
        let stderr = String::from_utf8_lossy(&output.stderr);
        assert_eq!(output.status.code(), Some(2), "{bad:?}: {stderr}");
        assert!(
            stderr.contains("sphera-trace"),
            "{bad:?}: no message: {stderr}"
        );
    }
    // A reference with a NaN pixel: the errors are not finite, printed as null.
    let reference = output_dir().join("nan-reference.pfm");
    let mut pfm = b"PF\n8 8\n-1.0\n".to_vec();
    for i in 0..8 * 8 * 3 {
        let value: f32 = if i == 7 { f32::NAN } else { 0.5 };
        pfm.extend_from_slice(&value.to_le_bytes());
    }
    std::fs::write(&reference, pfm).expect("write the reference");
    let output = Command::new(&program)
        .args(small)
        .arg("--reference")
        .arg(&reference)
        .output()
        .expect("run");
    let stdout = String::from_utf8_lossy(&output.stdout);
    assert!(
        output.status.success(),
        "{stdout} {}",
        String::from_utf8_lossy(&output.stderr)
    );
    assert!(
        stdout.contains("\"rmse\": null") && !stdout.contains("nan"),
        "{stdout}"
    );
    let output = Command::new(&program)
        .args([
            "--scene", "indirect", "--width", "16", "--height", "16", "--quiet",
        ])
        .args(["--out-png", "/proc/sphera-cannot-write-here/x.png"])
        .output()
        .expect("run");
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert_eq!(output.status.code(), Some(1), "{stderr}");
    assert!(stderr.contains("cannot write"), "no message: {stderr}");
}

#[test]
fn test_tracer_end_to_end() {
    run_tracer_test("test_tracer_end_to_end");
}

#[test]
fn test_tracer_indirect() {
    run_tracer_test("test_tracer_indirect");
}

#[test]
fn every_c_test_file_has_a_test() {
    let c_files = |dir: &str| -> Vec<String> {
        std::fs::read_dir(repository_root().join(dir))
            .unwrap_or_else(|error| panic!("read {dir}/: {error}"))
            .filter_map(|entry| {
                let path = entry.expect("read a directory entry").path();
                let is_c = path.extension().is_some_and(|extension| extension == "c");
                is_c.then(|| path.file_stem().unwrap().to_string_lossy().into_owned())
            })
            .collect()
    };
    // ffi-tests/ holds only tests of the C ABI; the tracer's tests live beside it.
    let mut found = c_files("ffi-tests");
    found.extend(c_files("bench/tests"));
    found.sort();
    let mut known: Vec<String> = C_TESTS
        .iter()
        .chain(TRACER_TESTS.iter())
        .map(|name| name.to_string())
        .collect();
    known.sort();
    assert_eq!(
        found, known,
        "add a #[test] and a C_TESTS (or TRACER_TESTS) entry in tools/tests/c_abi.rs for each ffi-tests/*.c (bench/tests/*.c)"
    );
}

/// Linking succeeds only when the symbols that the programs reach are defined; this
/// checks the whole archive, so that no member leaves an unwinding or Rust runtime
/// symbol to the C linker. (`readelf` rather than `nm`: the members embed LLVM bitcode,
/// which a system `nm` may try, and fail, to read through its LTO plugin.)
#[test]
fn static_library_has_no_unwinding_or_rust_runtime_symbols() {
    let library = static_library();
    let listing = match run(Command::new("readelf").arg("-sW").arg(library)) {
        Ok(listing) => listing,
        Err(message) => {
            println!("readelf is not available ({message}); linking the C tests is the check");
            return;
        }
    };
    let mut defined = std::collections::BTreeSet::new();
    let mut undefined = std::collections::BTreeSet::new();
    for line in listing.lines() {
        // Num: Value Size Type Bind Vis Ndx Name
        let fields: Vec<&str> = line.split_whitespace().collect();
        if fields.len() < 8 || !fields[0].ends_with(':') || fields[4] == "LOCAL" {
            continue;
        }
        let (section, symbol) = (fields[6], fields[7]);
        if section == "UND" {
            undefined.insert(symbol.to_string());
        } else {
            defined.insert(symbol.to_string());
        }
    }
    let external: Vec<&String> = undefined.difference(&defined).collect();
    println!("symbols libsphera.a leaves to the C linker: {external:?}");
    let forbidden: Vec<&&String> = external
        .iter()
        .filter(|symbol| {
            let symbol = symbol.trim_start_matches('_');
            symbol.contains("rust_eh_personality")
                || symbol.starts_with("Unwind")
                || symbol.starts_with("rust")
                || symbol.starts_with("ZN")
                || symbol.starts_with('R')
        })
        .collect();
    assert!(
        forbidden.is_empty(),
        "libsphera.a needs Rust runtime or unwinding symbols: {forbidden:?}"
    );
    let header = std::fs::read_to_string(repository_root().join("include").join("sphera.h"))
        .expect("read include/sphera.h");
    let declared: Vec<&str> = header
        .split(|c: char| !(c.is_ascii_alphanumeric() || c == '_'))
        .filter(|word| word.starts_with("sphera_") && header.contains(&format!("{word}(")))
        .collect();
    assert!(
        declared.len() >= 18,
        "too few functions found in the header: {declared:?}"
    );
    for function in declared {
        assert!(
            defined.contains(function),
            "libsphera.a does not define {function}"
        );
    }
}

/// The header compiles as C++11 and a C++ program links against the library.
#[test]
fn header_compiles_and_links_as_cpp11() {
    let dir = output_dir();
    let source = dir.join("header_as_cpp.cpp");
    let program = dir.join("header_as_cpp");
    std::fs::write(
        &source,
        r#"#include "sphera.h"
#include <cstdio>

int main() {
    SpheraVec3 quad[SPHERA_MAX_POLYGON_VERTICES] = {
        {-1.0f, -1.0f, 1.0f}, {1.0f, -1.0f, 1.0f}, {1.0f, 1.0f, 1.0f}, {-1.0f, 1.0f, 1.0f}};
    SpheraSolidAnglePolygon polygon;
    sphera_solid_angle_polygon_prepare(&polygon, quad, 4);
    SpheraSample sample = sphera_solid_angle_polygon_sample(nullptr, 0.5f, 0.5f);
    SpheraFrame frame;
    bool ok = sphera_frame_from_normal(&frame, SpheraVec3{0.0f, 0.0f, 1.0f});
    std::printf("C++: pdf %g, frame %d, fma %d\n", sample.pdf, ok ? 1 : 0,
                sphera_has_hardware_fma() ? 1 : 0);
    return sample.pdf == 0.0f && sample.dir.z == 1.0f && ok ? 0 : 1;
}
"#,
    )
    .expect("write the C++ program");
    build_and_run(
        &source,
        &program,
        true,
        &["-std=c++11", "-Wall", "-Wextra", "-Werror", "-pedantic"],
        "the header as C++11",
    );
}

/// The header's structs have the sizes, alignments and public field offsets of the
/// Rust types behind them.
#[test]
fn struct_layouts_match_rust() {
    use std::mem::{align_of, offset_of, size_of};

    use sphera::brdf::{GgxBrdf, Ltc};
    use sphera::ffi::{SpheraSample, SpheraVec3};
    use sphera::math::Frame;
    use sphera::polygon::LtcPolygon;
    use sphera::polygon::baselines::{
        ArvoPolygon, ArvoProjectedPolygon, HartBilinearPolygon, HartBiquadraticPolygon, TurkPolygon,
    };
    use sphera::polygon::light::{LightSample, Material, PolygonLight};
    use sphera::polygon::{
        ClippedSolidAnglePolygon, ProjectedPolygon, SolidAnglePolygon, SolidAngleQuad,
        SolidAngleTriangle,
    };
    use sphera::sg::{Asg, Sg, SgShading, SgShadingPoint};
    use sphera::sphere::{
        Cap, CapUnion, GgxPivot, SolidAngleSphere, SphereLightSampler, SphereLightShading,
        SptdInCap,
    };
    use sphera::vsgl::{Vpl, Vsgl, VsglAccumulator, VsglTexel};

    let expected: Vec<(&str, usize)> = vec![
        ("sizeof(SpheraVec3)", size_of::<SpheraVec3>()),
        ("alignof(SpheraVec3)", align_of::<SpheraVec3>()),
        ("sizeof(SpheraSample)", size_of::<SpheraSample>()),
        ("alignof(SpheraSample)", align_of::<SpheraSample>()),
        ("offsetof(SpheraSample, pdf)", offset_of!(SpheraSample, pdf)),
        ("sizeof(SpheraFrame)", size_of::<Frame>()),
        ("alignof(SpheraFrame)", align_of::<Frame>()),
        (
            "offsetof(SpheraFrame, bitangent)",
            offset_of!(Frame, bitangent),
        ),
        ("offsetof(SpheraFrame, normal)", offset_of!(Frame, normal)),
        (
            "sizeof(SpheraSolidAnglePolygon)",
            size_of::<SolidAnglePolygon>(),
        ),
        (
            "alignof(SpheraSolidAnglePolygon)",
            align_of::<SolidAnglePolygon>(),
        ),
        ("sizeof(SpheraSolidAngleQuad)", size_of::<SolidAngleQuad>()),
        (
            "alignof(SpheraSolidAngleQuad)",
            align_of::<SolidAngleQuad>(),
        ),
        (
            "sizeof(SpheraSolidAngleTriangle)",
            size_of::<SolidAngleTriangle>(),
        ),
        (
            "alignof(SpheraSolidAngleTriangle)",
            align_of::<SolidAngleTriangle>(),
        ),
        ("sizeof(SpheraTurkPolygon)", size_of::<TurkPolygon>()),
        ("alignof(SpheraTurkPolygon)", align_of::<TurkPolygon>()),
        ("sizeof(SpheraArvoPolygon)", size_of::<ArvoPolygon>()),
        ("alignof(SpheraArvoPolygon)", align_of::<ArvoPolygon>()),
        (
            "sizeof(SpheraHartBilinearPolygon)",
            size_of::<HartBilinearPolygon>(),
        ),
        (
            "alignof(SpheraHartBilinearPolygon)",
            align_of::<HartBilinearPolygon>(),
        ),
        (
            "sizeof(SpheraHartBiquadraticPolygon)",
            size_of::<HartBiquadraticPolygon>(),
        ),
        (
            "alignof(SpheraHartBiquadraticPolygon)",
            align_of::<HartBiquadraticPolygon>(),
        ),
        (
            "sizeof(SpheraClippedSolidAnglePolygon)",
            size_of::<ClippedSolidAnglePolygon>(),
        ),
        (
            "alignof(SpheraClippedSolidAnglePolygon)",
            align_of::<ClippedSolidAnglePolygon>(),
        ),
        (
            "sizeof(SpheraProjectedPolygon)",
            size_of::<ProjectedPolygon>(),
        ),
        (
            "alignof(SpheraProjectedPolygon)",
            align_of::<ProjectedPolygon>(),
        ),
        (
            "sizeof(SpheraArvoProjectedPolygon)",
            size_of::<ArvoProjectedPolygon>(),
        ),
        (
            "alignof(SpheraArvoProjectedPolygon)",
            align_of::<ArvoProjectedPolygon>(),
        ),
        ("sizeof(SpheraGgxBrdf)", size_of::<GgxBrdf>()),
        ("alignof(SpheraGgxBrdf)", align_of::<GgxBrdf>()),
        ("sizeof(SpheraLtc)", size_of::<Ltc>()),
        ("alignof(SpheraLtc)", align_of::<Ltc>()),
        ("sizeof(SpheraLtcPolygon)", size_of::<LtcPolygon>()),
        ("alignof(SpheraLtcPolygon)", align_of::<LtcPolygon>()),
        ("sizeof(SpheraPolygonLight)", size_of::<PolygonLight>()),
        ("alignof(SpheraPolygonLight)", align_of::<PolygonLight>()),
        ("sizeof(SpheraMaterial)", size_of::<Material>()),
        ("sizeof(SpheraLightSample)", size_of::<LightSample>()),
        ("sizeof(SpheraCap)", size_of::<Cap>()),
        ("alignof(SpheraCap)", align_of::<Cap>()),
        (
            "offsetof(SpheraCap, one_minus_cos)",
            offset_of!(Cap, one_minus_cos),
        ),
        (
            "offsetof(SpheraCap, one_plus_cos)",
            offset_of!(Cap, one_plus_cos),
        ),
        ("offsetof(SpheraCap, sin2)", offset_of!(Cap, sin2)),
        ("sizeof(SpheraSptdInCap)", size_of::<SptdInCap>()),
        ("alignof(SpheraSptdInCap)", align_of::<SptdInCap>()),
        (
            "sizeof(SpheraSolidAngleSphere)",
            size_of::<SolidAngleSphere>(),
        ),
        (
            "alignof(SpheraSolidAngleSphere)",
            align_of::<SolidAngleSphere>(),
        ),
        ("sizeof(SpheraCapUnion)", size_of::<CapUnion>()),
        ("alignof(SpheraCapUnion)", align_of::<CapUnion>()),
        ("sizeof(SpheraGgxPivot)", size_of::<GgxPivot>()),
        (
            "offsetof(SpheraGgxPivot, albedo)",
            offset_of!(GgxPivot, albedo),
        ),
        (
            "sizeof(SpheraSphereLightShading)",
            size_of::<SphereLightShading>(),
        ),
        (
            "sizeof(SpheraSphereLightSampler)",
            size_of::<SphereLightSampler>(),
        ),
        (
            "alignof(SpheraSphereLightSampler)",
            align_of::<SphereLightSampler>(),
        ),
        ("sizeof(SpheraSg)", size_of::<Sg>()),
        ("alignof(SpheraSg)", align_of::<Sg>()),
        ("offsetof(SpheraSg, sharpness)", offset_of!(Sg, sharpness)),
        (
            "offsetof(SpheraSg, log_amplitude)",
            offset_of!(Sg, log_amplitude),
        ),
        ("sizeof(SpheraVpl)", size_of::<Vpl>()),
        ("alignof(SpheraVpl)", align_of::<Vpl>()),
        ("offsetof(SpheraVpl, roughness)", offset_of!(Vpl, roughness)),
        ("sizeof(SpheraVsglTexel)", size_of::<VsglTexel>()),
        ("alignof(SpheraVsglTexel)", align_of::<VsglTexel>()),
        (
            "offsetof(SpheraVsglTexel, weight)",
            offset_of!(VsglTexel, weight),
        ),
        (
            "sizeof(SpheraVsglAccumulator)",
            size_of::<VsglAccumulator>(),
        ),
        (
            "offsetof(SpheraVsglAccumulator, origin)",
            offset_of!(VsglAccumulator, origin),
        ),
        ("sizeof(SpheraVsgl)", size_of::<Vsgl>()),
        ("alignof(SpheraVsgl)", align_of::<Vsgl>()),
        ("offsetof(SpheraVsgl, mean)", offset_of!(Vsgl, mean)),
        ("offsetof(SpheraVsgl, variance)", offset_of!(Vsgl, variance)),
        ("sizeof(SpheraAsg)", size_of::<Asg>()),
        ("alignof(SpheraAsg)", align_of::<Asg>()),
        ("offsetof(SpheraAsg, y)", offset_of!(Asg, y)),
        ("offsetof(SpheraAsg, z)", offset_of!(Asg, z)),
        ("offsetof(SpheraAsg, eta_y)", offset_of!(Asg, eta_y)),
        ("offsetof(SpheraAsg, amplitude)", offset_of!(Asg, amplitude)),
        ("sizeof(SpheraSgShadingPoint)", size_of::<SgShadingPoint>()),
        (
            "alignof(SpheraSgShadingPoint)",
            align_of::<SgShadingPoint>(),
        ),
        ("sizeof(SpheraSgShading)", size_of::<SgShading>()),
        (
            "offsetof(SpheraSgShading, specular)",
            offset_of!(SgShading, specular),
        ),
    ];
    let mut source =
        String::from("#include <stddef.h>\n#include <stdio.h>\n#include \"sphera.h\"\n");
    for name in [
        "SpheraVec3",
        "SpheraSample",
        "SpheraFrame",
        "SpheraSolidAnglePolygon",
        "SpheraSolidAngleQuad",
        "SpheraSolidAngleTriangle",
        "SpheraTurkPolygon",
        "SpheraArvoPolygon",
        "SpheraHartBilinearPolygon",
        "SpheraHartBiquadraticPolygon",
        "SpheraClippedSolidAnglePolygon",
        "SpheraProjectedPolygon",
        "SpheraArvoProjectedPolygon",
        "SpheraGgxBrdf",
        "SpheraLtc",
        "SpheraLtcPolygon",
        "SpheraPolygonLight",
        "SpheraCap",
        "SpheraSptdInCap",
        "SpheraSolidAngleSphere",
        "SpheraCapUnion",
        "SpheraSphereLightSampler",
        "SpheraVpl",
        "SpheraVsglTexel",
        "SpheraVsgl",
        "SpheraSg",
        "SpheraAsg",
        "SpheraSgShadingPoint",
    ] {
        source += &format!("struct align_{name} {{ char c; {name} t; }};\n");
    }
    source += "int main(void) {\n";
    for (expression, _) in &expected {
        let c_expression = match expression.strip_prefix("alignof(") {
            Some(rest) => format!("offsetof(struct align_{}, t)", rest.trim_end_matches(')')),
            None => expression.to_string(),
        };
        source +=
            &format!("  printf(\"%s %lu\\n\", \"{expression}\", (unsigned long){c_expression});\n");
    }
    source += "  return 0;\n}\n";

    let root = repository_root();
    let dir = output_dir();
    let source_path = dir.join("layout.c");
    let program = dir.join("layout");
    std::fs::write(&source_path, source).expect("write the layout program");
    if let Err(message) = run(compiler(false)
        .args(C_FLAGS)
        .arg("-I")
        .arg(root.join("include"))
        .arg(&source_path)
        .arg("-o")
        .arg(&program))
    {
        panic!("the layout program does not compile:\n{message}");
    }
    let output = run(&mut Command::new(&program)).unwrap_or_else(|message| panic!("{message}"));
    let mut mismatches = Vec::new();
    for ((expression, rust), line) in expected.iter().zip(output.lines()) {
        let c: usize = line
            .rsplit(' ')
            .next()
            .and_then(|value| value.parse().ok())
            .expect("a number");
        println!("{expression}: C {c}, Rust {rust}");
        if c != *rust {
            mismatches.push(format!("{expression}: C {c}, Rust {rust}"));
        }
    }
    assert_eq!(
        output.lines().count(),
        expected.len(),
        "unexpected output:\n{output}"
    );
    assert!(
        mismatches.is_empty(),
        "include/sphera.h disagrees with the Rust layout (regenerate it with \
         `cargo run -p sphera-tools --bin generate_header`): {mismatches:?}"
    );
}
