//! A small deterministic, seeded pseudo-random number generator for the simulator.
//!
//! The project has no `rand` dependency, and the experiment must be exactly reproducible
//! from one run seed, so that runs with and without SLAM pair up seed by seed. So this
//! module provides:
//!
//! - SplitMix64, used only to expand a 64-bit seed into generator state;
//! - xoshiro256** (Blackman & Vigna), the generator itself: fast, 256 bits of state, and
//!   statistically good enough for Monte Carlo noise;
//! - uniform reals in `[0, 1)` from the top 53 bits, and standard Gaussians by the Box–Muller
//!   transform (the second value of each pair is cached, so draws come in a fixed order);
//! - [`Streams`]: independent streams for odometry drift, sonar sensing and the wander
//!   behaviour, derived from one run seed. Keeping them apart means that what the SLAM rules
//!   do (for example `setOdometry`) can never change the random numbers the true path uses.

/// One step of SplitMix64: advances `state` and returns a well-mixed 64-bit value.
pub fn splitmix64(state: &mut u64) -> u64 {
    *state = state.wrapping_add(0x9E37_79B9_7F4A_7C15);
    let mut z = *state;
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^ (z >> 31)
}

/// A xoshiro256** generator with a cached Box–Muller spare.
#[derive(Debug, Clone, PartialEq)]
pub struct Rng {
    s: [u64; 4],
    spare: Option<f64>,
}

impl Rng {
    /// A generator whose 256-bit state is expanded from `seed` by SplitMix64
    /// (never all zero, which xoshiro forbids).
    pub fn seed_from_u64(seed: u64) -> Self {
        let mut sm = seed;
        let mut s = [0u64; 4];
        for word in &mut s {
            *word = splitmix64(&mut sm);
        }
        if s == [0; 4] {
            s[0] = 1;
        }
        Rng { s, spare: None }
    }

    /// The generator for stream number `stream` of run seed `seed`. Different streams of the
    /// same seed, and the same stream of different seeds, start from unrelated states.
    pub fn stream(seed: u64, stream: u64) -> Self {
        let mut mix = seed ^ stream.wrapping_mul(0xD1B5_4A32_D192_ED03);
        let key = splitmix64(&mut mix);
        Rng::seed_from_u64(key ^ stream)
    }

    /// The next 64 random bits (xoshiro256**).
    pub fn next_u64(&mut self) -> u64 {
        let result = self.s[1].wrapping_mul(5).rotate_left(7).wrapping_mul(9);
        let t = self.s[1] << 17;
        self.s[2] ^= self.s[0];
        self.s[3] ^= self.s[1];
        self.s[1] ^= self.s[2];
        self.s[0] ^= self.s[3];
        self.s[2] ^= t;
        self.s[3] = self.s[3].rotate_left(45);
        result
    }

    /// A uniform real in `[0, 1)` with 53 random bits.
    pub fn uniform(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 * (1.0 / (1u64 << 53) as f64)
    }

    /// A uniform real in `[lo, hi)` (or exactly `lo` when the interval is empty).
    pub fn range(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.uniform()
    }

    /// `true` with probability `p` (clamped to `[0, 1]`). Always draws one number.
    pub fn chance(&mut self, p: f64) -> bool {
        self.uniform() < p
    }

    /// A uniform integer in `0..n` (0 when `n` is 0).
    pub fn below(&mut self, n: u64) -> u64 {
        if n == 0 {
            return 0;
        }
        // Lemire's multiply-shift; the tiny bias (< 2^-64 * n) is irrelevant here.
        ((u128::from(self.next_u64()) * u128::from(n)) >> 64) as u64
    }

    /// A standard normal deviate (mean 0, standard deviation 1), Box–Muller.
    pub fn gaussian(&mut self) -> f64 {
        if let Some(z) = self.spare.take() {
            return z;
        }
        // u1 in (0, 1] so that ln(u1) is finite.
        let u1 = 1.0 - self.uniform();
        let u2 = self.uniform();
        let radius = (-2.0 * u1.ln()).sqrt();
        let angle = std::f64::consts::TAU * u2;
        self.spare = Some(radius * angle.sin());
        radius * angle.cos()
    }

    /// A normal deviate with the given mean and standard deviation.
    pub fn normal(&mut self, mean: f64, sd: f64) -> f64 {
        mean + sd * self.gaussian()
    }
}

/// Stream numbers used by [`Streams::from_seed`].
pub mod stream_id {
    /// Odometry biases and odometry noise.
    pub const DRIFT: u64 = 1;
    /// Sonar noise, specular and outlier draws.
    pub const SENSING: u64 = 2;
    /// The wander behaviour (random turn choices).
    pub const BEHAVIOUR: u64 = 3;
}

/// The three independent random streams of one simulated run.
#[derive(Debug, Clone, PartialEq)]
pub struct Streams {
    /// Odometry drift: biases drawn once per run, then per-step noise.
    pub drift: Rng,
    /// Sonar sensing noise.
    pub sensing: Rng,
    /// The robot's behaviour (wander decisions).
    pub behaviour: Rng,
}

impl Streams {
    /// Derives the three streams from one run seed.
    pub fn from_seed(seed: u64) -> Self {
        Streams {
            drift: Rng::stream(seed, stream_id::DRIFT),
            sensing: Rng::stream(seed, stream_id::SENSING),
            behaviour: Rng::stream(seed, stream_id::BEHAVIOUR),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn same_seed_same_sequence() {
        let mut a = Rng::seed_from_u64(42);
        let mut b = Rng::seed_from_u64(42);
        for _ in 0..100 {
            assert_eq!(a.next_u64(), b.next_u64());
        }
    }

    #[test]
    fn splitmix_reference_values() {
        // Reference output of SplitMix64 seeded with 0 (Vigna's splitmix64.c).
        let mut s = 0u64;
        assert_eq!(splitmix64(&mut s), 0xE220_A839_7B1D_CDAF);
        assert_eq!(splitmix64(&mut s), 0x6E78_9E6A_A1B9_65F4);
    }

    #[test]
    fn streams_differ() {
        let mut st = Streams::from_seed(7);
        let d = st.drift.next_u64();
        let s = st.sensing.next_u64();
        let b = st.behaviour.next_u64();
        assert!(d != s && s != b && d != b);
        let mut other = Streams::from_seed(8);
        assert_ne!(other.drift.next_u64(), d);
    }

    #[test]
    fn uniform_moments() {
        let mut r = Rng::seed_from_u64(1);
        let n = 100_000;
        let (mut sum, mut sq) = (0.0, 0.0);
        for _ in 0..n {
            let u = r.uniform();
            assert!((0.0..1.0).contains(&u));
            sum += u;
            sq += u * u;
        }
        let mean = sum / n as f64;
        let var = sq / n as f64 - mean * mean;
        assert!((mean - 0.5).abs() < 0.005, "mean {mean}");
        assert!((var - 1.0 / 12.0).abs() < 0.002, "var {var}");
    }

    #[test]
    fn gaussian_moments() {
        let mut r = Rng::seed_from_u64(2);
        let n = 100_000;
        let (mut sum, mut sq, mut within1) = (0.0, 0.0, 0usize);
        for _ in 0..n {
            let z = r.gaussian();
            assert!(z.is_finite());
            sum += z;
            sq += z * z;
            if z.abs() < 1.0 {
                within1 += 1;
            }
        }
        let mean = sum / n as f64;
        let var = sq / n as f64 - mean * mean;
        assert!(mean.abs() < 0.01, "mean {mean}");
        assert!((var - 1.0).abs() < 0.02, "var {var}");
        let frac = within1 as f64 / n as f64;
        assert!((frac - 0.6827).abs() < 0.01, "P(|z|<1) = {frac}");
    }

    #[test]
    fn below_is_in_range() {
        let mut r = Rng::seed_from_u64(3);
        let mut seen = [0usize; 5];
        for _ in 0..10_000 {
            seen[r.below(5) as usize] += 1;
        }
        assert!(seen.iter().all(|&c| c > 1800 && c < 2200), "{seen:?}");
        assert_eq!(r.below(0), 0);
    }
}
