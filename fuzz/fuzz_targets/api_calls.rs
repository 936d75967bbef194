//! The embedding API driven by random call sequences (`rusoar_fuzz::api_calls`): no call
//! panics, and the kernel's invariants hold after each.
#![no_main]

use libfuzzer_sys::arbitrary::Unstructured;
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let mut agent = rusoar_fuzz::bounded_agent();
    if let Err(why) =
        rusoar_fuzz::api_calls::run_api_calls(&mut agent, &mut Unstructured::new(data))
    {
        panic!("{why}");
    }
});
