//! The C ABI: thin wrappers over the safe core, one file per family, no logic.
