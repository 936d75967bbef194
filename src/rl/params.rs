//! The parameters of reinforcement learning as the `rl` command reads and sets them (Soar
//! manual, ch. 9, `rl`): their names, 9.6's defaults, the values each accepts, and how 9.6
//! prints them. Data only; the learning itself reads [`RlParams`].

use crate::printer::constants::c_general;

/// How the update's target is computed (`learning-policy`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Policy {
    /// The selected operator's value (on-policy).
    #[default]
    Sarsa,
    /// The highest value among the candidates (off-policy).
    QLearning,
    OnPolicyGq,
    OffPolicyGq,
}

impl Policy {
    /// The GQ(λ) policies, which weigh eligibility traces by an importance ratio.
    pub fn is_gq(self) -> bool {
        matches!(self, Policy::OnPolicyGq | Policy::OffPolicyGq)
    }

    /// Off-policy learners update toward the best candidate's value.
    pub fn is_off_policy(self) -> bool {
        matches!(self, Policy::QLearning | Policy::OffPolicyGq)
    }

    const WORDS: [(&'static str, Policy); 4] = [
        ("sarsa", Policy::Sarsa),
        ("q-learning", Policy::QLearning),
        ("on-policy-gq-lambda", Policy::OnPolicyGq),
        ("off-policy-gq-lambda", Policy::OffPolicyGq),
    ];
}

/// How the learning rate changes with a rule's updates (`decay-mode`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum DecayMode {
    /// The learning rate as set.
    #[default]
    Normal,
    /// 1 / (updates + 1).
    Exponential,
    /// 1 / (ln(updates + 1) + 1).
    Logarithmic,
    /// Each rule's own rate, tuned by the meta-learning rate.
    DeltaBarDelta,
}

impl DecayMode {
    const WORDS: [(&'static str, DecayMode); 4] = [
        ("normal", DecayMode::Normal),
        ("exp", DecayMode::Exponential),
        ("log", DecayMode::Logarithmic),
        ("delta-bar-delta", DecayMode::DeltaBarDelta),
    ];
}

/// Which learned rules apoptosis may remove (`apoptosis`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Apoptosis {
    #[default]
    None,
    Chunks,
    RlChunks,
}

impl Apoptosis {
    const WORDS: [(&'static str, Apoptosis); 3] = [
        ("none", Apoptosis::None),
        ("chunks", Apoptosis::Chunks),
        ("rl-chunks", Apoptosis::RlChunks),
    ];
}

/// Every parameter of `rl`, with 9.6's defaults.
#[derive(Debug, Clone, PartialEq)]
pub struct RlParams {
    pub learning: bool,
    pub temporal_extension: bool,
    pub discount_rate: f64,
    pub learning_policy: Policy,
    pub learning_rate: f64,
    pub hrl_discount: bool,
    pub step_size_parameter: f64,
    pub et_decay_rate: f64,
    pub et_tolerance: f64,
    pub chunk_stop: bool,
    pub decay_mode: DecayMode,
    pub meta: bool,
    pub meta_learning_rate: f64,
    pub update_log_path: String,
    pub apoptosis: Apoptosis,
    pub apoptosis_decay: f64,
    /// Kept negative, as 9.6 stores it (it is set as a positive number).
    pub apoptosis_thresh: f64,
    pub trace: bool,
    pub temporal_discount: bool,
}

impl Default for RlParams {
    fn default() -> Self {
        RlParams {
            learning: false,
            temporal_extension: true,
            discount_rate: 0.9,
            learning_policy: Policy::Sarsa,
            learning_rate: 0.3,
            hrl_discount: false,
            step_size_parameter: 1.0,
            et_decay_rate: 0.0,
            et_tolerance: 0.001,
            chunk_stop: true,
            decay_mode: DecayMode::Normal,
            meta: false,
            meta_learning_rate: 0.1,
            update_log_path: String::new(),
            apoptosis: Apoptosis::None,
            apoptosis_decay: 0.5,
            apoptosis_thresh: -2.0,
            trace: false,
            temporal_discount: true,
        }
    }
}

/// Why a `--set` was refused, as 9.6 words it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SetError {
    /// No parameter of that name: `Invalid setting.`
    Name,
    /// A value the parameter does not take: `Invalid value for setting.`
    Value,
    /// A parameter that cannot change now (apoptosis's decay and threshold while it is
    /// on): `Failed to set value.`
    Protected,
}

/// A number as 9.6 prints a parameter: 16 significant digits, C's `%g` form.
pub fn number_text(x: f64) -> String {
    c_general(x, 16)
}

/// A number read as a C++ stream reads a `double`: the longest prefix that is a decimal
/// number; 0 when there is none (as for `abc`, `nan` or `1e`); the largest double, with
/// its sign, when it overflows.
pub fn stream_number(text: &str) -> f64 {
    let b = text.as_bytes();
    let mut i = 0;
    if i < b.len() && (b[i] == b'+' || b[i] == b'-') {
        i += 1;
    }
    let digits = |i: &mut usize| {
        let start = *i;
        while *i < b.len() && b[*i].is_ascii_digit() {
            *i += 1;
        }
        *i - start
    };
    let mut n = digits(&mut i);
    if i < b.len() && b[i] == b'.' {
        i += 1;
        n += digits(&mut i);
    }
    if n == 0 {
        return 0.0;
    }
    if i < b.len() && (b[i] == b'e' || b[i] == b'E') {
        i += 1;
        if i < b.len() && (b[i] == b'+' || b[i] == b'-') {
            i += 1;
        }
        if digits(&mut i) == 0 {
            return 0.0;
        }
    }
    let x: f64 = text[..i].parse().unwrap_or(0.0);
    if x.is_infinite() {
        return f64::MAX.copysign(x);
    }
    x
}

fn on_off(word: &str) -> Result<bool, SetError> {
    match word {
        "on" => Ok(true),
        "off" => Ok(false),
        _ => Err(SetError::Value),
    }
}

fn word_of<T: Copy + PartialEq>(words: &[(&'static str, T)], v: T) -> &'static str {
    words.iter().find(|(_, x)| *x == v).map_or("", |(w, _)| w)
}

fn from_word<T: Copy>(words: &[(&'static str, T)], word: &str) -> Result<T, SetError> {
    words
        .iter()
        .find(|(w, _)| *w == word)
        .map(|(_, x)| *x)
        .ok_or(SetError::Value)
}

/// A rate between 0 and 1, both included.
fn unit(word: &str) -> Result<f64, SetError> {
    let x = stream_number(word);
    if (0.0..=1.0).contains(&x) {
        Ok(x)
    } else {
        Err(SetError::Value)
    }
}

/// A number above 0.
fn positive(word: &str) -> Result<f64, SetError> {
    let x = stream_number(word);
    if x > 0.0 {
        Ok(x)
    } else {
        Err(SetError::Value)
    }
}

impl RlParams {
    /// A parameter's value as `rl --get` prints it; `None` for an unknown name.
    pub fn get(&self, name: &str) -> Option<String> {
        let flag = |b: bool| if b { "on" } else { "off" }.to_string();
        Some(match name {
            "learning" => flag(self.learning),
            "temporal-extension" => flag(self.temporal_extension),
            "discount-rate" => number_text(self.discount_rate),
            "learning-policy" => word_of(&Policy::WORDS, self.learning_policy).to_string(),
            "learning-rate" => number_text(self.learning_rate),
            "hrl-discount" => flag(self.hrl_discount),
            "step-size-parameter" => number_text(self.step_size_parameter),
            "eligibility-trace-decay-rate" => number_text(self.et_decay_rate),
            "eligibility-trace-tolerance" => number_text(self.et_tolerance),
            "chunk-stop" => flag(self.chunk_stop),
            "decay-mode" => word_of(&DecayMode::WORDS, self.decay_mode).to_string(),
            "meta" => flag(self.meta),
            "meta-learning-rate" => number_text(self.meta_learning_rate),
            "update-log-path" => self.update_log_path.clone(),
            "apoptosis" => word_of(&Apoptosis::WORDS, self.apoptosis).to_string(),
            "apoptosis-decay" => number_text(self.apoptosis_decay),
            "apoptosis-thresh" => number_text(self.apoptosis_thresh),
            "trace" => flag(self.trace),
            "temporal-discount" => flag(self.temporal_discount),
            _ => return None,
        })
    }

    /// Sets a parameter from its text, with 9.6's checks: on/off flags, the listed words,
    /// rates between 0 and 1, a tolerance and a threshold above 0.
    pub fn set(&mut self, name: &str, word: &str) -> Result<(), SetError> {
        match name {
            "learning" => self.learning = on_off(word)?,
            "temporal-extension" => self.temporal_extension = on_off(word)?,
            "discount-rate" => self.discount_rate = unit(word)?,
            "learning-policy" => self.learning_policy = from_word(&Policy::WORDS, word)?,
            "learning-rate" => self.learning_rate = unit(word)?,
            "hrl-discount" => self.hrl_discount = on_off(word)?,
            "step-size-parameter" => self.step_size_parameter = unit(word)?,
            "eligibility-trace-decay-rate" => self.et_decay_rate = unit(word)?,
            "eligibility-trace-tolerance" => self.et_tolerance = positive(word)?,
            "chunk-stop" => self.chunk_stop = on_off(word)?,
            "decay-mode" => self.decay_mode = from_word(&DecayMode::WORDS, word)?,
            "meta" => self.meta = on_off(word)?,
            "meta-learning-rate" => self.meta_learning_rate = unit(word)?,
            "update-log-path" => self.update_log_path = word.to_string(),
            "apoptosis" => self.apoptosis = from_word(&Apoptosis::WORDS, word)?,
            "apoptosis-decay" => self.apoptosis_decay = unit(word)?,
            "apoptosis-thresh" => self.apoptosis_thresh = -positive(word)?,
            "trace" => self.trace = on_off(word)?,
            "temporal-discount" => self.temporal_discount = on_off(word)?,
            _ => return Err(SetError::Name),
        }
        Ok(())
    }

    /// The listing `rl` prints with no argument, in 9.6's layout.
    pub fn listing(&self) -> String {
        let g = |n: &str| self.get(n).unwrap_or_default();
        let mut s = String::new();
        s.push_str(&format!("\nSoar-RL learning: {}\n", g("learning")));
        s.push_str(&format!("temporal-extension: {}\n", g("temporal-extension")));
        let section = |s: &mut String, title: &str, names: &[&str]| {
            s.push_str(&format!("\n{title}\n{}\n", "-".repeat(title.len())));
            for n in names {
                s.push_str(&format!("{n}: {}\n", g(n)));
            }
        };
        section(&mut s, "Discount", &["discount-rate"]);
        section(
            &mut s,
            "Learning",
            &["learning-policy", "learning-rate", "hrl-discount", "step-size-parameter"],
        );
        section(
            &mut s,
            "Eligibility Traces",
            &["eligibility-trace-decay-rate", "eligibility-trace-tolerance"],
        );
        section(
            &mut s,
            "Experimental",
            &["chunk-stop", "decay-mode", "meta", "meta-learning-rate", "update-log-path"],
        );
        s.push('\n');
        for n in ["apoptosis", "apoptosis-decay", "apoptosis-thresh"] {
            s.push_str(&format!("{n}: {}\n", g(n)));
        }
        s.push_str(&format!("\ntrace: {}\n\n", g("trace")));
        s
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_read_as_a_cpp_stream_reads_them() {
        assert_eq!(stream_number("0.5x"), 0.5);
        assert_eq!(stream_number("abc"), 0.0);
        assert_eq!(stream_number("nan"), 0.0);
        assert_eq!(stream_number("1e"), 0.0);
        assert_eq!(stream_number(".5"), 0.5);
        assert_eq!(stream_number("+.25e0"), 0.25);
        assert_eq!(stream_number("1e400"), f64::MAX);
    }

    #[test]
    fn numbers_print_as_9_6_prints_them() {
        assert_eq!(number_text(0.3), "0.3");
        assert_eq!(number_text(1e-7), "1e-07");
        assert_eq!(number_text(0.123456789), "0.123456789");
        assert_eq!(number_text(f64::MAX), "1.797693134862316e+308");
        assert_eq!(number_text(-2.0), "-2");
    }

    #[test]
    fn bad_values_are_refused_and_leave_the_parameter() {
        let mut p = RlParams::default();
        assert_eq!(p.set("learning-rate", "1.5"), Err(SetError::Value));
        assert_eq!(p.set("learning", "yes"), Err(SetError::Value));
        assert_eq!(p.set("decay-mode", "exponential"), Err(SetError::Value));
        assert_eq!(p.set("apoptosis-thresh", "-5"), Err(SetError::Value));
        assert_eq!(p.set("nonsense", "1"), Err(SetError::Name));
        assert_eq!(p.learning_rate, 0.3);
        assert_eq!(p.set("apoptosis-thresh", "5"), Ok(()));
        assert_eq!(p.get("apoptosis-thresh").as_deref(), Some("-5"));
        assert_eq!(p.set("learning-rate", "abc"), Ok(()));
        assert_eq!(p.get("learning-rate").as_deref(), Some("0"));
    }
}
