//! Seeded bytes for the tests that run the fuzz targets' generators without a fuzzer.

/// `len` bytes from a 64-bit xorshift generator: the same for a seed on every platform.
pub fn bytes(seed: u64, len: usize) -> Vec<u8> {
    let mut x = seed.wrapping_mul(0x9E37_79B9_7F4A_7C15) | 1;
    (0..len)
        .map(|_| {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            (x >> 24) as u8
        })
        .collect()
}
