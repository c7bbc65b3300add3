//! Generation of the C header `include/sphera.h` with cbindgen, used as a library.

use std::path::PathBuf;

use crate::repository_root;

/// Where the committed header lives.
pub fn header_path() -> PathBuf {
    repository_root().join("include").join("sphera.h")
}

/// The header that cbindgen generates from the core crate with `cbindgen.toml`.
///
/// Panics when the configuration cannot be read or the crate cannot be parsed; this is
/// a development tool, and the panic message says what went wrong.
pub fn generate() -> String {
    let root = repository_root();
    let config_path = root.join("cbindgen.toml");
    let mut config = cbindgen::Config::from_file(&config_path)
        .unwrap_or_else(|error| panic!("cannot read {}: {error}", config_path.display()));
    // The version macros follow the includes (after anything `after_includes` of
    // cbindgen.toml adds), from the version in the core's Cargo.toml.
    let version = version_macros(&package_version());
    config.after_includes = Some(match config.after_includes.take() {
        Some(text) => format!("{text}\n{version}"),
        None => version,
    });
    let bindings = cbindgen::Builder::new()
        .with_crate(&root)
        .with_config(config)
        .generate()
        .unwrap_or_else(|error| panic!("cbindgen failed on {}: {error}", root.display()));
    let mut bytes = Vec::new();
    bindings.write(&mut bytes);
    for_c_users(&String::from_utf8(bytes).expect("cbindgen writes UTF-8"))
}

/// A prepared value of the C ABI that the header shows as opaque storage: its C name,
/// size and alignment (from the Rust type, so the two cannot disagree).
struct Opaque {
    name: &'static str,
    size: usize,
    align: usize,
    /// The doc comment of a type that cbindgen does not define, which the header then
    /// defines here: the three sizes of the solid angle sampler are aliases of one
    /// const-generic struct (`SolidAngleFan<N, T>`), which cbindgen leaves undefined.
    defined_here: Option<&'static str>,
}

fn opaque<T>(name: &'static str) -> Opaque {
    Opaque {
        name,
        size: std::mem::size_of::<T>(),
        align: std::mem::align_of::<T>(),
        defined_here: None,
    }
}

/// [`opaque`] for a type that the header defines itself, with its doc comment.
fn opaque_defined_here<T>(name: &'static str, doc: &'static str) -> Opaque {
    Opaque {
        defined_here: Some(doc),
        ..opaque::<T>(name)
    }
}

/// The prepared values: the caller owns their storage (on the stack, in an array) but
/// fills them only through the functions that prepare them (issue 19, 3). The header
/// shows each as `uint32_t opaque[n]` of the Rust type's size: every prepared value is
/// made of 4-byte words (`f32`, `u32`) with 4-byte alignment (asserted here), so the C
/// type has the same size and alignment, and `tools/tests/c_abi.rs` compares both as C
/// compiles them. Data that callers read or build (vectors, samples, caps, SGs, VPLs,
/// texels and the VSGL accumulator whose sums are a texel, materials, frames) keep their
/// fields.
fn opaque_types() -> Vec<Opaque> {
    use sphera::brdf::{GgxBrdf, Ltc};
    use sphera::polygon::baselines::{
        ArvoPolygon, ArvoProjectedPolygon, HartBilinearPolygon, HartBiquadraticPolygon, TurkPolygon,
    };
    use sphera::polygon::light::PolygonLight;
    use sphera::polygon::{
        ClippedSolidAnglePolygon, LtcPolygon, ProjectedPolygon, SolidAnglePolygon, SolidAngleQuad,
        SolidAngleTriangle,
    };
    use sphera::sg::SgShadingPoint;
    use sphera::sphere::CapUnion;
    use sphera::sphere::light::{SphereLightSampler, SphereLightShading};
    use sphera::sphere::solid_angle_sphere::SolidAngleSphere;
    use sphera::sphere::sptd::SptdInCap;
    vec![
        opaque_defined_here::<SolidAnglePolygon>(
            "SpheraSolidAnglePolygon",
            "A convex polygon of 3 to SPHERA_MAX_POLYGON_VERTICES vertices prepared for solid angle sampling (Peters 2021, supplement C, Algorithm 5).",
        ),
        opaque_defined_here::<SolidAngleQuad>(
            "SpheraSolidAngleQuad",
            "A convex quad prepared for solid angle sampling: SpheraSolidAnglePolygon in the storage of 4 vertices.",
        ),
        opaque_defined_here::<SolidAngleTriangle>(
            "SpheraSolidAngleTriangle",
            "A triangle prepared for solid angle sampling: SpheraSolidAnglePolygon in the storage of 3 vertices.",
        ),
        opaque::<TurkPolygon>("SpheraTurkPolygon"),
        opaque::<ArvoPolygon>("SpheraArvoPolygon"),
        opaque::<HartBilinearPolygon>("SpheraHartBilinearPolygon"),
        opaque::<HartBiquadraticPolygon>("SpheraHartBiquadraticPolygon"),
        opaque::<ClippedSolidAnglePolygon>("SpheraClippedSolidAnglePolygon"),
        opaque::<ProjectedPolygon>("SpheraProjectedPolygon"),
        opaque::<ArvoProjectedPolygon>("SpheraArvoProjectedPolygon"),
        opaque::<GgxBrdf>("SpheraGgxBrdf"),
        opaque::<Ltc>("SpheraLtc"),
        opaque::<LtcPolygon>("SpheraLtcPolygon"),
        opaque::<PolygonLight>("SpheraPolygonLight"),
        opaque::<SptdInCap>("SpheraSptdInCap"),
        opaque::<SolidAngleSphere>("SpheraSolidAngleSphere"),
        opaque::<CapUnion>("SpheraCapUnion"),
        opaque::<SphereLightShading>("SpheraSphereLightShading"),
        opaque::<SphereLightSampler>("SpheraSphereLightSampler"),
        opaque::<SgShadingPoint>("SpheraSgShadingPoint"),
    ]
}

/// Types that only opaque values contain: their definitions leave the header.
const INTERNAL_TYPES: [&str; 7] = [
    "SpheraEllipseSector",
    "SpheraCentralSectors",
    "SpheraCentralPieces",
    "SpheraEdgeNormalRows",
    "SpheraSmallPolygonCosineSampler",
    "SpheraProjectedPieces",
    "SpheraCapIntersection",
];

/// The header as C users read it: prepared values as opaque storage, the types only
/// they contain removed, and rustdoc's links (`[`x`](path)`, `[`x`]`) as plain code.
fn for_c_users(header: &str) -> String {
    let lines: Vec<&str> = header.lines().collect();
    let mut out: Vec<String> = Vec::with_capacity(lines.len());
    let opaque = opaque_types();
    let mut i = 0;
    while i < lines.len() {
        let line = lines[i];
        let typedef_name = ["typedef struct ", "typedef union "]
            .iter()
            .find_map(|prefix| line.strip_prefix(prefix))
            .and_then(|rest| rest.strip_suffix(" {"));
        let Some(name) = typedef_name else {
            out.push(line.to_string());
            i += 1;
            continue;
        };
        let end = (i..lines.len())
            .find(|&j| lines[j] == format!("}} {name};"))
            .unwrap_or_else(|| panic!("no end of {name} in the generated header"));
        if INTERNAL_TYPES.contains(&name) {
            // The definition and the doc comment right above it leave; so does the blank
            // line after it.
            if out.last().is_some_and(|l| l == " */") {
                while let Some(l) = out.pop() {
                    if l == "/**" {
                        break;
                    }
                }
            }
            i = end + 1;
            if lines.get(i) == Some(&"") {
                i += 1;
            }
            continue;
        }
        if let Some(o) = opaque.iter().find(|o| o.name == name) {
            assert!(
                o.align == 4 && o.size % 4 == 0,
                "{name}: opaque storage needs 4-byte words and alignment ({} B, align {})",
                o.size,
                o.align
            );
            out.push(line.to_string());
            out.push(format!(
                "  uint32_t opaque[{}]; /* {} bytes, private: see the preamble */",
                o.size / 4,
                o.size
            ));
            out.push(lines[end].to_string());
            i = end + 1;
            continue;
        }
        out.extend(lines[i..=end].iter().map(|l| l.to_string()));
        i = end + 1;
        // The types that cbindgen leaves undefined, after the first definition (of
        // `SpheraVec3`, which nothing precedes): they hold only `uint32_t`s.
        if lines[end] == "} SpheraVec3;" {
            for o in opaque.iter().filter(|o| o.defined_here.is_some()) {
                assert!(
                    !header.contains(&format!("typedef struct {} {{", o.name)),
                    "{} is defined twice",
                    o.name
                );
                out.push(String::new());
                out.push("/**".to_string());
                out.push(format!(" * {}", o.defined_here.unwrap_or_default()));
                out.push(" */".to_string());
                out.push(format!("typedef struct {} {{", o.name));
                out.push(format!(
                    "  uint32_t opaque[{}]; /* {} bytes, private: see the preamble */",
                    o.size / 4,
                    o.size
                ));
                out.push(format!("}} {};", o.name));
            }
        }
    }
    for o in &opaque {
        assert!(
            o.align == 4 && o.size % 4 == 0,
            "{}: opaque storage needs 4-byte words and alignment",
            o.name
        );
        assert!(
            out.contains(&format!("typedef struct {} {{", o.name)),
            "{} is not in the generated header",
            o.name
        );
    }
    let mut text = out.join("\n");
    text.push('\n');
    compact(&plain_links(&text))
}

/// The width to which the header's doc comments are reflowed, and within which
/// declarations are packed.
const WIDTH: usize = 100;

/// The header in compact form: each doc comment (`/** … */`) reflowed to [`WIDTH`]
/// columns as `/* … */` with its text from the first line, paragraphs on new lines
/// without blank lines between them, and rustdoc's `# Safety` heading as a `Safety:`
/// lead-in; a struct field's one-line comment after the field when both fit; no blank line
/// between one macro and the next (their comments separate them); a function's
/// parameters packed onto as few lines as fit.
fn compact(header: &str) -> String {
    let lines: Vec<&str> = header.lines().collect();
    let mut out: Vec<String> = Vec::with_capacity(lines.len());
    let mut i = 0;
    while i < lines.len() {
        let line = lines[i];
        if line.trim_start() == "/**" {
            let indent = &line[..line.len() - 3];
            let end = (i..lines.len())
                .find(|&j| lines[j].trim_start() == "*/")
                .expect("an unterminated doc comment in the generated header");
            let body: Vec<&str> = lines[i + 1..end]
                .iter()
                .map(|l| {
                    let l = l.strip_prefix(indent).unwrap_or(l).trim_start();
                    let l = l.strip_prefix('*').unwrap_or(l);
                    l.strip_prefix(' ').unwrap_or(l)
                })
                .collect();
            let comment = reflow_comment(indent, &body);
            i = end + 1;
            // A field with a one-line comment: the comment follows the field.
            let next = lines.get(i).copied().unwrap_or("");
            let is_field = !indent.is_empty()
                && next.starts_with(indent)
                && next.ends_with(';')
                && !next.contains('(');
            if is_field && comment.len() == 1 {
                let trailing = format!("{next} {}", comment[0].trim_start());
                if trailing.chars().count() <= WIDTH {
                    out.push(trailing);
                    i += 1;
                    continue;
                }
            }
            out.extend(comment);
            continue;
        }
        if line.ends_with(',') && line.contains('(') && !line.starts_with(' ') {
            // A declaration whose parameters cbindgen put one per line.
            let end = (i..lines.len())
                .find(|&j| lines[j].ends_with(");"))
                .expect("an unterminated declaration in the generated header");
            out.extend(pack_parameters(&lines[i..=end]));
            i = end + 1;
            continue;
        }
        // A blank line between a macro and the next macro's comment goes.
        let next_is_macro = || {
            (i + 1..lines.len())
                .find(|&j| !lines[j].starts_with("/*") && !lines[j].starts_with(" *"))
                .is_some_and(|j| j > i + 1 && lines[j].starts_with("#define "))
        };
        if line.is_empty()
            && out.last().is_some_and(|l| l.starts_with("#define "))
            && next_is_macro()
        {
            i += 1;
            continue;
        }
        out.push(line.to_string());
        i += 1;
    }
    let mut text = out.join("\n");
    text.push('\n');
    text
}

/// A function's `# Safety` section that says only that its pointers follow the conventions
/// of `sphera::ffi`: the header leaves it out, since its preamble states those conventions
/// (cbindgen.toml, `header`).
const CONVENTIONAL_SAFETY: &str =
    "Safety: Pointers as in the conventions of the C ABI (`crate::ffi`).";

/// A doc comment's lines (without their ` * `) as a compact `/* … */` comment at
/// `indent`: paragraphs reflowed to [`WIDTH`] columns, each on a new line.
fn reflow_comment(indent: &str, body: &[&str]) -> Vec<String> {
    let mut paragraphs: Vec<String> = Vec::new();
    let mut current = String::new();
    let mut lead_in = String::new();
    for line in body.iter().map(|l| l.trim()) {
        if line.is_empty() {
            if !current.is_empty() {
                paragraphs.push(std::mem::take(&mut current));
            }
        } else if let Some(heading) = line.strip_prefix("# ") {
            if !current.is_empty() {
                paragraphs.push(std::mem::take(&mut current));
            }
            lead_in = format!("{heading}:");
        } else {
            if current.is_empty() {
                current = std::mem::take(&mut lead_in);
            }
            if !current.is_empty() {
                current.push(' ');
            }
            current.push_str(line);
        }
    }
    if !current.is_empty() {
        paragraphs.push(current);
    }
    paragraphs.retain(|p| p != CONVENTIONAL_SAFETY);
    let first = format!("{indent}/* ");
    let rest = format!("{indent} * ");
    let mut out: Vec<String> = Vec::new();
    for paragraph in &paragraphs {
        let mut line = if out.is_empty() {
            first.clone()
        } else {
            rest.clone()
        };
        let mut empty = true;
        for word in words(paragraph) {
            // Room for the closing ` */` on every line keeps the last one within WIDTH.
            if !empty && line.chars().count() + 1 + word.chars().count() + 3 > WIDTH {
                out.push(std::mem::replace(&mut line, rest.clone()));
                empty = true;
            }
            if !empty {
                line.push(' ');
            }
            line.push_str(&word);
            empty = false;
        }
        out.push(line);
    }
    match out.last_mut() {
        Some(last) => last.push_str(" */"),
        None => out.push(format!("{indent}/* */")),
    }
    out
}

/// The words of a paragraph, a code span (`` `…` ``) with its spaces being one word.
fn words(paragraph: &str) -> Vec<String> {
    let mut words: Vec<String> = Vec::new();
    let mut in_code = false;
    for piece in paragraph.split(' ').filter(|w| !w.is_empty()) {
        match words.last_mut() {
            Some(last) if in_code => {
                last.push(' ');
                last.push_str(piece);
            }
            _ => words.push(piece.to_string()),
        }
        if piece.matches('`').count() % 2 == 1 {
            in_code = !in_code;
        }
    }
    words
}

/// A declaration that cbindgen wrote with one parameter per line, with the parameters
/// packed onto as few lines as fit in [`WIDTH`] columns (aligned after the `(`).
fn pack_parameters(lines: &[&str]) -> Vec<String> {
    let head = lines[0];
    let open = head.find('(').expect("a declaration has a '('") + 1;
    let align = " ".repeat(open);
    let mut out = vec![head.to_string()];
    for parameter in lines[1..].iter().map(|l| l.trim()) {
        let last = out.last_mut().expect("the head is there");
        if last.chars().count() + 1 + parameter.chars().count() <= WIDTH {
            last.push(' ');
            last.push_str(parameter);
        } else {
            out.push(format!("{align}{parameter}"));
        }
    }
    out
}

/// Rustdoc's intra-doc links as plain text: `[`x`](target)` and `[x](target)` become
/// `` `x` `` and `x`, `[`x`]` becomes `` `x` ``; markdown links to web pages (`http`)
/// stay.
fn plain_links(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    let mut rest = text;
    while let Some(open) = rest.find('[') {
        out.push_str(&rest[..open]);
        let after = &rest[open + 1..];
        let Some(close) = after.find(']') else {
            out.push_str(&rest[open..]);
            rest = "";
            break;
        };
        let label = &after[..close];
        let tail = &after[close + 1..];
        let is_code = label.starts_with('`') && label.ends_with('`') && label.len() >= 2;
        if label.contains('\n') || label.is_empty() {
            out.push('[');
            rest = after;
        } else if let Some(target) = tail.strip_prefix('(').and_then(|t| t.split_once(')')) {
            if target.0.starts_with("http") || target.0.contains(' ') {
                out.push('[');
                rest = after;
            } else {
                out.push_str(label);
                rest = target.1;
            }
        } else if is_code {
            out.push_str(label);
            rest = tail;
        } else {
            out.push('[');
            rest = after;
        }
    }
    out.push_str(rest);
    out
}

/// The `version` of the `[package]` section of the core's `Cargo.toml` (the repository
/// root's), e.g. `"0.1.0"`.
///
/// Panics when the file cannot be read or has no such line.
pub fn package_version() -> String {
    let path = repository_root().join("Cargo.toml");
    let text = std::fs::read_to_string(&path)
        .unwrap_or_else(|error| panic!("cannot read {}: {error}", path.display()));
    let mut in_package = false;
    for line in text.lines().map(str::trim) {
        if line.starts_with('[') {
            in_package = line == "[package]";
            continue;
        }
        let value = line
            .strip_prefix("version")
            .map(str::trim_start)
            .and_then(|rest| rest.strip_prefix('='));
        if let (true, Some(value)) = (in_package, value) {
            return value.trim().trim_matches('"').to_string();
        }
    }
    panic!("{} has no version in [package]", path.display());
}

/// The header's version macros for `version` (`MAJOR.MINOR.PATCH`, optionally with a
/// pre-release or build suffix, which only the string keeps).
///
/// Panics when `version` does not start with three dot-separated numbers.
pub fn version_macros(version: &str) -> String {
    let core = version.split(['-', '+']).next().unwrap_or_default();
    let numbers: Vec<u32> = core
        .split('.')
        .map(|part| {
            part.parse()
                .unwrap_or_else(|_| panic!("version {version:?} is not MAJOR.MINOR.PATCH"))
        })
        .collect();
    let [major, minor, patch] = numbers[..] else {
        panic!("version {version:?} is not MAJOR.MINOR.PATCH");
    };
    format!(
        "
/* The header's version (the library's Cargo.toml); check at start-up that the library agrees
 * with sphera_check_version(SPHERA_VERSION_MAJOR, SPHERA_VERSION_MINOR). */
#define SPHERA_VERSION_MAJOR {major}
#define SPHERA_VERSION_MINOR {minor}
#define SPHERA_VERSION_PATCH {patch}
#define SPHERA_VERSION_STRING \"{version}\""
    )
}
