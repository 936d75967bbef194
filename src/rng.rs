//! Soar's random numbers (`shared/soar_rand.cpp` in the kernel's sources): MT19937 seeded
//! by `srand n` (`init_genrand(n)`), `randInt()` the 32-bit output, `randInt(n)` a value in
//! `0..=n` by masking to the next power of two minus one and rejecting larger values, and
//! `rand()` in `[0, 1]`.

const N: usize = 624;
const M: usize = 397;

#[derive(Clone)]
pub struct Mt19937 {
    state: [u32; N],
    index: usize,
}

impl std::fmt::Debug for Mt19937 {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "Mt19937 {{ index: {} }}", self.index)
    }
}

impl Mt19937 {
    pub fn new(seed: u32) -> Self {
        let mut m = Mt19937 {
            state: [0; N],
            index: N,
        };
        m.seed(seed);
        m
    }

    /// `init_genrand(seed)`.
    pub fn seed(&mut self, seed: u32) {
        self.state[0] = seed;
        for i in 1..N {
            let prev = self.state[i - 1];
            self.state[i] = 1_812_433_253u32
                .wrapping_mul(prev ^ (prev >> 30))
                .wrapping_add(i as u32);
        }
        self.index = N;
    }

    /// `genrand_int32()`.
    pub fn next_u32(&mut self) -> u32 {
        if self.index >= N {
            for i in 0..N {
                let y = (self.state[i] & 0x8000_0000) | (self.state[(i + 1) % N] & 0x7fff_ffff);
                let mag = if y & 1 == 1 { 0x9908_b0df } else { 0 };
                self.state[i] = self.state[(i + M) % N] ^ (y >> 1) ^ mag;
            }
            self.index = 0;
        }
        let mut y = self.state[self.index];
        self.index += 1;
        y ^= y >> 11;
        y ^= (y << 7) & 0x9d2c_5680;
        y ^= (y << 15) & 0xefc6_0000;
        y ^= y >> 18;
        y
    }

    /// `randInt(n)`: uniform in `0..=n`.
    pub fn rand_int(&mut self, n: u32) -> u32 {
        let mut used = n;
        for s in [1, 2, 4, 8, 16] {
            used |= used >> s;
        }
        loop {
            let i = self.next_u32() & used;
            if i <= n {
                return i;
            }
        }
    }

    /// `rand()`: `randInt() * (1.0 / 4294967295.0)`, in `[0, 1]`.
    pub fn rand_float(&mut self) -> f64 {
        f64::from(self.next_u32()) * (1.0 / 4_294_967_295.0)
    }
}

impl Default for Mt19937 {
    /// Seeded from the clock, as Soar seeds itself when `srand` is never called.
    fn default() -> Self {
        let t = std::time::SystemTime::now()
            .duration_since(std::time::UNIX_EPOCH)
            .map(|d| d.as_nanos() as u32)
            .unwrap_or(5489);
        Mt19937::new(t)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// As on the official 9.6 kernel: with 4 tied candidates, `srand` 1/2/3/4 picks 1/0/2/2.
    #[test]
    fn matches_the_official_kernel_choices() {
        let picks: Vec<u32> = (1..=4).map(|s| Mt19937::new(s).rand_int(3)).collect();
        assert_eq!(picks, vec![1, 0, 2, 2]);
    }

    #[test]
    fn reference_mt19937_output() {
        // The reference implementation's first output for init_genrand(5489).
        assert_eq!(Mt19937::new(5489).next_u32(), 3_499_211_612);
    }
}
