//! Controls and ablations of the thesis rules, each selectable from the command line and none
//! of them the default (`rules/README.md`, section 6).
//!
//! - [`Drift`]: the odometry model, Stage 2's drift (the default) or none at all, the control
//!   that shows the error the rules inject on their own;
//! - [`Variant`]: one change to the rules or to the functions they call; the Soar ones live in
//!   `rules/variants/<name>.soar`, sourced after `robotagent.soar` (they excise a thesis rule
//!   and put a changed copy beside it, so the thesis files stay as they are);
//! - [`Constants`]: the three constants the thesis does not give (`^r-tolerance`,
//!   `^th-tolerance`, `^overlap-factor`), overridden by a rule sourced the same way;
//! - [`Ablation`]: all of them together, as [`super::soar_loop::LoopConfig`] carries them.

use std::fmt;
use std::path::Path;
use std::str::FromStr;

use super::odometry::DriftParams;

/// The odometry model of a run.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Serialize, serde::Deserialize)]
pub enum Drift {
    /// Stage 2.0.x's drift: biases drawn once per run plus noise.
    #[default]
    Stage,
    /// Perfect odometry: the believed pose follows the true one until a rule moves it.
    None,
}

impl Drift {
    /// The names `--drift` takes.
    pub const NAMES: [&'static str; 2] = ["stage", "none"];

    /// The drift parameters.
    pub fn params(self) -> DriftParams {
        match self {
            Drift::Stage => DriftParams::STAGE2,
            Drift::None => DriftParams::NONE,
        }
    }

    /// The command-line name.
    pub fn name(self) -> &'static str {
        match self {
            Drift::Stage => "stage",
            Drift::None => "none",
        }
    }
}

impl FromStr for Drift {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        match s {
            "stage" => Ok(Drift::Stage),
            "none" => Ok(Drift::None),
            _ => Err(format!(
                "unknown drift `{s}` (expected one of: {})",
                Drift::NAMES.join(", ")
            )),
        }
    }
}

impl fmt::Display for Drift {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// One change to the thesis rules or to the functions they call.
#[derive(
    Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash, serde::Serialize, serde::Deserialize,
)]
pub enum Variant {
    /// Hypothesis 2 is the only rule that corrects the odometry.
    H2Only,
    /// ChangeRobotPosition2 is the only rule that corrects the odometry.
    Crp2Only,
    /// ChangeRobotPosition2 compares a sonar only with the nearest wall its ray meets.
    NearestWall,
    /// `getwalldistance` returns the nearest hit among the sonar model's cone rays.
    Cone,
    /// Wall angles compare modulo 360°.
    Wrap,
    /// The believed heading reaches the agent in tenths of a degree.
    Tenths,
}

impl Variant {
    /// Every variant, in the order of the table in `rules/README.md`.
    pub const ALL: [Variant; 6] = [
        Variant::H2Only,
        Variant::Crp2Only,
        Variant::NearestWall,
        Variant::Cone,
        Variant::Wrap,
        Variant::Tenths,
    ];

    /// The command-line name (and, for the Soar ones, the file stem in `rules/variants/`).
    pub fn name(self) -> &'static str {
        match self {
            Variant::H2Only => "h2-only",
            Variant::Crp2Only => "crp2-only",
            Variant::NearestWall => "nearest-wall",
            Variant::Cone => "cone",
            Variant::Wrap => "wrap",
            Variant::Tenths => "tenths",
        }
    }

    /// Whether the variant is a Soar file in `rules/variants/` (the others change the host).
    pub fn is_rules(self) -> bool {
        matches!(
            self,
            Variant::H2Only | Variant::Crp2Only | Variant::NearestWall | Variant::Wrap
        )
    }

    /// One line saying what it changes.
    pub fn describe(self) -> &'static str {
        match self {
            Variant::H2Only => "only hypothesis 2 corrects the odometry",
            Variant::Crp2Only => "only ChangeRobotPosition2 corrects the odometry",
            Variant::NearestWall => "ChangeRobotPosition2 against the nearest wall only",
            Variant::Cone => "getwalldistance over the sonar's cone, not its central ray",
            Variant::Wrap => "wall angles compared modulo 360°",
            Variant::Tenths => "the believed heading in tenths of a degree",
        }
    }
}

impl FromStr for Variant {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        Variant::ALL
            .into_iter()
            .find(|v| v.name() == s)
            .ok_or_else(|| {
                let names: Vec<&str> = Variant::ALL.iter().map(|v| v.name()).collect();
                format!(
                    "unknown variant `{s}` (expected one of: {})",
                    names.join(", ")
                )
            })
    }
}

impl fmt::Display for Variant {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// Overrides of the constants the thesis does not give (`None`: the value in `Elaborate.soar`).
#[derive(Debug, Clone, Copy, PartialEq, Default, serde::Serialize, serde::Deserialize)]
pub struct Constants {
    /// `^r-tolerance`, mm (500 in `Elaborate.soar`).
    pub r_tolerance: Option<f64>,
    /// `^th-tolerance`, degrees (15).
    pub th_tolerance: Option<f64>,
    /// `^overlap-factor`, percent (50).
    pub overlap: Option<f64>,
}

impl Constants {
    /// The values of `Elaborate.soar`.
    pub const THESIS: (f64, f64, f64) = (500.0, 15.0, 50.0);

    /// Whether any constant is overridden.
    pub fn any(&self) -> bool {
        self.r_tolerance.is_some() || self.th_tolerance.is_some() || self.overlap.is_some()
    }

    /// The values in force: (r-tolerance, th-tolerance, overlap-factor).
    pub fn values(&self) -> (f64, f64, f64) {
        let (r, th, o) = Constants::THESIS;
        (
            self.r_tolerance.unwrap_or(r),
            self.th_tolerance.unwrap_or(th),
            self.overlap.unwrap_or(o),
        )
    }

    /// The rule that replaces `slam*elaborate*constants`, with the values in force.
    pub fn rule(&self) -> String {
        let (r, th, o) = self.values();
        format!(
            "excise slam*elaborate*constants\n\
             sp {{slam*elaborate*constants*override\n\
             \x20  (state <s> ^superstate <ss>)\n\
             -->\n\
             \x20  (<s> ^r-tolerance {}\n\
             \x20       ^th-tolerance {}\n\
             \x20       ^overlap-factor {}\n\
             \x20       ^min-position-error 100\n\
             \x20       ^max-position-error 1000\n\
             \x20       ^sonar-max-range 5000)}}\n",
            soar_number(r),
            soar_number(th),
            soar_number(o)
        )
    }
}

/// A number as a Soar constant: an integer when it is one, else a float.
fn soar_number(v: f64) -> String {
    if v.fract() == 0.0 && v.abs() < 1e15 {
        format!("{}", v as i64)
    } else {
        format!("{v}")
    }
}

/// Parses a constant given on the command line: a finite number in `lo..=hi`.
pub fn parse_constant(s: &str, what: &str, lo: f64, hi: f64) -> Result<f64, String> {
    let v: f64 = s
        .trim()
        .parse()
        .map_err(|_| format!("{what}: `{s}` is not a number"))?;
    if v.is_finite() && (lo..=hi).contains(&v) {
        Ok(v)
    } else {
        Err(format!("{what} must be between {lo} and {hi}, not {s}"))
    }
}

/// Every control and ablation of a run. The default is the thesis's setup.
#[derive(Debug, Clone, PartialEq, Default, serde::Serialize, serde::Deserialize)]
pub struct Ablation {
    pub drift: Drift,
    /// Sorted, no duplicates.
    pub variants: Vec<Variant>,
    pub constants: Constants,
}

impl Ablation {
    /// Checks and sorts a set of variants: `h2-only` and `crp2-only` together would leave no
    /// correction at all, so they are refused.
    pub fn new(drift: Drift, variants: &[Variant], constants: Constants) -> Result<Self, String> {
        let mut v = variants.to_vec();
        v.sort();
        v.dedup();
        if v.contains(&Variant::H2Only) && v.contains(&Variant::Crp2Only) {
            return Err(
                "the variants h2-only and crp2-only exclude each other (together no rule would \
                 correct the odometry; use --slam off for that)"
                    .into(),
            );
        }
        Ok(Ablation {
            drift,
            variants: v,
            constants,
        })
    }

    /// Whether `v` is selected.
    pub fn has(&self, v: Variant) -> bool {
        self.variants.contains(&v)
    }

    /// Whether this is the thesis's setup (no variant, no override, Stage drift).
    pub fn is_thesis(&self) -> bool {
        self.variants.is_empty() && !self.constants.any() && self.drift == Drift::Stage
    }

    /// A short label: `thesis`, or the variants and overrides joined by `+`.
    pub fn label(&self) -> String {
        let mut parts: Vec<String> = self.variants.iter().map(|v| v.name().into()).collect();
        let (r, th, o) = self.constants.values();
        if self.constants.r_tolerance.is_some() {
            parts.push(format!("r-tolerance={}", soar_number(r)));
        }
        if self.constants.th_tolerance.is_some() {
            parts.push(format!("th-tolerance={}", soar_number(th)));
        }
        if self.constants.overlap.is_some() {
            parts.push(format!("overlap={}", soar_number(o)));
        }
        if parts.is_empty() {
            "thesis".into()
        } else {
            parts.join("+")
        }
    }

    /// The Soar text to source after `robotagent.soar` when the SLAM rules are loaded: the
    /// files of the Soar variants from `rules_dir/variants/`, then the constants rule.
    pub fn rules_text(&self, rules_dir: &Path) -> Result<String, String> {
        let mut text = String::new();
        for v in self.variants.iter().filter(|v| v.is_rules()) {
            let path = rules_dir
                .join("variants")
                .join(format!("{}.soar", v.name()));
            let body = std::fs::read_to_string(&path).map_err(|e| {
                format!(
                    "variant {v} needs {}, which cannot be read: {e}",
                    path.display()
                )
            })?;
            text.push_str(&body);
            text.push('\n');
        }
        if self.constants.any() {
            text.push_str(&self.constants.rule());
        }
        Ok(text)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_round_trip_and_bad_names_say_what_is_expected() {
        for v in Variant::ALL {
            assert_eq!(v.name().parse::<Variant>(), Ok(v));
        }
        let e = "nearest".parse::<Variant>().unwrap_err();
        assert!(e.contains("nearest-wall") && e.contains("`nearest`"), "{e}");
        assert_eq!("none".parse::<Drift>(), Ok(Drift::None));
        assert!("zero".parse::<Drift>().unwrap_err().contains("stage, none"));
    }

    #[test]
    fn exclusive_variants_are_refused_and_sets_are_sorted() {
        let c = Constants::default();
        assert!(Ablation::new(Drift::Stage, &[Variant::Crp2Only, Variant::H2Only], c).is_err());
        let a = Ablation::new(
            Drift::None,
            &[Variant::Wrap, Variant::Cone, Variant::Wrap],
            c,
        )
        .unwrap();
        assert_eq!(a.variants, vec![Variant::Cone, Variant::Wrap]);
        assert_eq!(a.label(), "cone+wrap");
        assert!(!a.is_thesis());
        assert!(Ablation::default().is_thesis());
        assert_eq!(Ablation::default().label(), "thesis");
    }

    #[test]
    fn constants_rule_carries_the_values() {
        let c = Constants {
            r_tolerance: Some(250.0),
            th_tolerance: None,
            overlap: Some(62.5),
        };
        let rule = c.rule();
        assert!(rule.starts_with("excise slam*elaborate*constants\n"));
        assert!(rule.contains("^r-tolerance 250\n"));
        assert!(rule.contains("^th-tolerance 15\n"));
        assert!(rule.contains("^overlap-factor 62.5\n"));
        assert!(parse_constant("-1", "r-tolerance", 0.0, 1e4).is_err());
        assert!(parse_constant("x", "r-tolerance", 0.0, 1e4).is_err());
        assert_eq!(parse_constant(" 300 ", "r", 0.0, 1e4), Ok(300.0));
    }

    #[test]
    fn rules_text_reads_the_variant_files() {
        let dir = super::super::soar_loop::default_rules_dir();
        for v in Variant::ALL.into_iter().filter(|v| v.is_rules()) {
            let a = Ablation::new(Drift::Stage, &[v], Constants::default()).unwrap();
            let text = a.rules_text(&dir).unwrap();
            assert!(text.contains("excise") || text.contains("sp {"), "{v}");
        }
        let a = Ablation::new(Drift::Stage, &[Variant::Wrap], Constants::default()).unwrap();
        let e = a.rules_text(Path::new("/nonexistent")).unwrap_err();
        assert!(e.contains("wrap.soar"), "{e}");
    }
}
