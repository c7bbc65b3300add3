//! Fuzz target: `sphera_tools::invariants::abi_invariants::ltc_and_light_entry_points` on libFuzzer's bytes.
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    sphera_tools::invariants::abi_invariants::ltc_and_light_entry_points(data);
});
