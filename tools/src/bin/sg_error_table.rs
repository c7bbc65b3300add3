//! Writes `docs/sg-error.md`: the error of every SG closed form and approximation of
//! `sphera::sg` against f64 numerical integration (`tools/src/measurements/sg_error.rs`).
//! Run with `cargo run --release -p sphera-tools --bin sg_error_table`.
use std::time::Instant;

fn main() {
    let start = Instant::now();
    let samples = sphera_tools::measurements::sg_error::measure(false);
    let mut md = sphera_tools::measurements::sg_error::render(&samples);
    md += &format!("\n({} measurements.)\n", samples.len());
    let path = sphera_tools::repository_root().join("docs/sg-error.md");
    std::fs::create_dir_all(path.parent().unwrap()).expect("create docs/");
    std::fs::write(&path, md).expect("write docs/sg-error.md");
    println!(
        "wrote {} in {:.1} s",
        path.display(),
        start.elapsed().as_secs_f64()
    );
}
