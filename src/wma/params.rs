//! The parameters of working-memory activation as `wm activation --get`/`--set` read and
//! write them (Soar manual, ch. 9, `wm`; ch. 8, "Working Memory Activation"): their names,
//! 9.6's defaults, the values each accepts, which cannot change while activation is on,
//! and the listing `wm activation` prints. Data only; the decay reads the typed fields.

use crate::rl::params::{number_text, stream_number};

/// Which WMEs are checked for forgetting, and how (`forgetting`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Forgetting {
    /// No forgetting.
    #[default]
    Off,
    /// Every WME with a decay history is checked at every decision.
    Naive,
    /// Each WME is checked at the decision a search predicts.
    Bsearch,
    /// As `bsearch`, with a cheap first estimate from each reference alone (`on`).
    Approx,
}

impl Forgetting {
    const WORDS: [(&'static str, Forgetting); 4] = [
        ("off", Forgetting::Off),
        ("naive", Forgetting::Naive),
        ("bsearch", Forgetting::Bsearch),
        ("on", Forgetting::Approx),
    ];

    /// Whether WMEs wait in the queue of predicted forgetting decisions.
    pub fn queued(self) -> bool {
        matches!(self, Forgetting::Bsearch | Forgetting::Approx)
    }
}

/// Why a `--set` was refused, as 9.6 words it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SetError {
    /// `Invalid activation setting.`
    Name,
    /// `Invalid value for activation setting.`
    Value,
    /// `ERROR: this parameter is protected while WMA is on.`
    Protected,
}

/// Every parameter of `wm activation`, with 9.6's defaults.
#[derive(Debug, Clone, PartialEq)]
pub struct WmaParams {
    pub activation: bool,
    /// The decay exponent, kept negative as 9.6 stores it (it is set as a positive number).
    pub decay_rate: f64,
    /// The forgetting threshold, a log value kept negative as 9.6 stores it.
    pub decay_thresh: f64,
    pub petrov_approx: bool,
    pub forgetting: Forgetting,
    /// `forget-wme lti`: only WMEs of long-term identifiers, all of an object's or none.
    pub forget_lti_only: bool,
    pub fake_forgetting: bool,
    pub timers: bool,
    /// The most memory the table of powers may take, in megabytes.
    pub max_pow_cache: i64,
}

impl Default for WmaParams {
    fn default() -> Self {
        WmaParams {
            activation: false,
            decay_rate: -0.5,
            decay_thresh: -2.0,
            petrov_approx: false,
            forgetting: Forgetting::Off,
            forget_lti_only: false,
            fake_forgetting: false,
            timers: false,
            max_pow_cache: 10,
        }
    }
}

/// A whole number read as a C++ stream reads an `int64_t`: the leading digits (with a
/// sign), 0 when there are none, the nearest limit when it overflows.
pub fn stream_integer(text: &str) -> i64 {
    let t = text.trim_start();
    let (neg, digits) = match t.as_bytes().first() {
        Some(b'-') => (true, &t[1..]),
        Some(b'+') => (false, &t[1..]),
        _ => (false, t),
    };
    let end = digits
        .bytes()
        .position(|b| !b.is_ascii_digit())
        .unwrap_or(digits.len());
    if end == 0 {
        return 0;
    }
    let mut v: i64 = 0;
    for b in digits[..end].bytes() {
        let d = i64::from(b - b'0');
        v = match v.checked_mul(10).and_then(|x| {
            if neg {
                x.checked_sub(d)
            } else {
                x.checked_add(d)
            }
        }) {
            Some(x) => x,
            None => return if neg { i64::MIN } else { i64::MAX },
        };
    }
    v
}

fn on_off(word: &str) -> Result<bool, SetError> {
    match word {
        "on" => Ok(true),
        "off" => Ok(false),
        _ => Err(SetError::Value),
    }
}

fn flag(b: bool) -> String {
    if b { "on" } else { "off" }.to_string()
}

/// The parameters 9.6 protects while activation is on: they shape the tables built when
/// it starts.
const PROTECTED: [&str; 7] = [
    "decay-rate",
    "decay-thresh",
    "petrov-approx",
    "forgetting",
    "forget-wme",
    "fake-forgetting",
    "max-pow-cache",
];

impl WmaParams {
    /// A parameter's value as `--get` prints it; `None` for an unknown name.
    pub fn get(&self, name: &str) -> Option<String> {
        Some(match name {
            "activation" => flag(self.activation),
            "decay-rate" => number_text(self.decay_rate),
            "decay-thresh" => number_text(self.decay_thresh),
            "petrov-approx" => flag(self.petrov_approx),
            "forgetting" => Forgetting::WORDS
                .iter()
                .find(|(_, f)| *f == self.forgetting)
                .map_or("off", |(w, _)| w)
                .to_string(),
            "forget-wme" => if self.forget_lti_only { "lti" } else { "all" }.to_string(),
            "fake-forgetting" => flag(self.fake_forgetting),
            "timers" => if self.timers { "one" } else { "off" }.to_string(),
            "max-pow-cache" => self.max_pow_cache.to_string(),
            _ => return None,
        })
    }

    /// Sets a parameter from its text with 9.6's checks: a decay rate between 0 and 1, a
    /// threshold and a cache size above 0, the listed words; the decay's shape cannot
    /// change while activation is on.
    pub fn set(&mut self, name: &str, word: &str) -> Result<(), SetError> {
        if self.get(name).is_none() {
            return Err(SetError::Name);
        }
        // 9.6 checks the value before the protection.
        let mut next = self.clone();
        match name {
            "activation" => next.activation = on_off(word)?,
            "decay-rate" => {
                let x = stream_number(word);
                if !(0.0..=1.0).contains(&x) {
                    return Err(SetError::Value);
                }
                next.decay_rate = -x;
            }
            "decay-thresh" => {
                let x = stream_number(word);
                if x <= 0.0 {
                    return Err(SetError::Value);
                }
                next.decay_thresh = -x;
            }
            "petrov-approx" => next.petrov_approx = on_off(word)?,
            "forgetting" => {
                next.forgetting = Forgetting::WORDS
                    .iter()
                    .find(|(w, _)| *w == word)
                    .map(|(_, f)| *f)
                    .ok_or(SetError::Value)?;
            }
            "forget-wme" => {
                next.forget_lti_only = match word {
                    "all" => false,
                    "lti" => true,
                    _ => return Err(SetError::Value),
                }
            }
            "fake-forgetting" => next.fake_forgetting = on_off(word)?,
            "timers" => {
                next.timers = match word {
                    "off" => false,
                    "one" => true,
                    _ => return Err(SetError::Value),
                }
            }
            _ => {
                let n = stream_integer(word);
                if n <= 0 {
                    return Err(SetError::Value);
                }
                next.max_pow_cache = n;
            }
        }
        if self.activation && PROTECTED.contains(&name) {
            return Err(SetError::Protected);
        }
        *self = next;
        Ok(())
    }

    /// The listing `wm activation` prints, in 9.6's layout.
    pub fn listing(&self) -> String {
        let g = |n: &str| self.get(n).unwrap_or_default();
        let mut s = format!("\nWMA activation: {}\n", g("activation"));
        let sections: [(&str, &[&str]); 3] = [
            ("Activation", &["decay-rate", "petrov-approx"]),
            (
                "Forgetting",
                &["decay-thresh", "forgetting", "forget-wme", "fake-forgetting"],
            ),
            ("Performance", &["timers", "max-pow-cache"]),
        ];
        for (title, names) in sections {
            s.push_str(&format!("\n{title}\n{}\n", "-".repeat(title.len())));
            for n in names {
                s.push_str(&format!("{n}: {}\n", g(n)));
            }
        }
        s.push('\n');
        s
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn integers_read_as_a_cpp_stream_reads_them() {
        assert_eq!(stream_integer("3.7"), 3);
        assert_eq!(stream_integer("1e3"), 1);
        assert_eq!(stream_integer("abc"), 0);
        assert_eq!(stream_integer("-5"), -5);
        assert_eq!(stream_integer("99999999999999999999"), i64::MAX);
    }

    #[test]
    fn values_are_checked_before_the_protection() {
        let mut p = WmaParams::default();
        assert_eq!(p.set("activation", "on"), Ok(()));
        assert_eq!(p.set("decay-rate", "2"), Err(SetError::Value));
        assert_eq!(p.set("decay-rate", "0.3"), Err(SetError::Protected));
        assert_eq!(p.set("timers", "one"), Ok(()));
        assert_eq!(p.set("bogus", "1"), Err(SetError::Name));
        assert_eq!(p.get("decay-rate").as_deref(), Some("-0.5"));
    }

    #[test]
    fn rates_and_thresholds_print_negated() {
        let mut p = WmaParams::default();
        p.set("decay-rate", "0").unwrap();
        assert_eq!(p.get("decay-rate").as_deref(), Some("-0"));
        p.set("decay-thresh", "3.5").unwrap();
        assert_eq!(p.get("decay-thresh").as_deref(), Some("-3.5"));
    }
}
