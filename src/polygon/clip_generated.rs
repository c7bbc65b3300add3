// STUB: replaced by the output of tools/src/bin/generate_clipping.rs
