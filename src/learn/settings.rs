//! The settings of `chunk` beyond when to learn (Soar manual, ch. 4, "Chunking", and ch. 9,
//! `chunk`): 9.6's defaults, and its singleton patterns.

/// What part of a WME a singleton pattern's element matches.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ElementType {
    Any,
    Constant,
    Identifier,
    Operator,
    State,
}

impl ElementType {
    /// The type named `word`, as `chunk singleton` takes it.
    pub fn from_word(word: &str) -> Option<Self> {
        Some(match word {
            "any" => ElementType::Any,
            "constant" => ElementType::Constant,
            "identifier" => ElementType::Identifier,
            "operator" => ElementType::Operator,
            "state" => ElementType::State,
            _ => return None,
        })
    }

    /// The type's word.
    pub fn word(self) -> &'static str {
        match self {
            ElementType::Any => "any",
            ElementType::Constant => "constant",
            ElementType::Identifier => "identifier",
            ElementType::Operator => "operator",
            ElementType::State => "state",
        }
    }
}

/// A user singleton: WMEs of this shape are unique in their superstate, so chunking may
/// unify conditions that match one (`chunk singleton ID-TYPE ATTRIBUTE VALUE-TYPE`).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Singleton {
    pub id: ElementType,
    pub attribute: String,
    pub value: ElementType,
}

/// How learned rules are named.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum NamingStyle {
    /// `chunk1`, `chunk3`, ...
    Numbered,
    /// `chunk*RULE*KIND*tDECISION-N`, the default.
    #[default]
    Rule,
}

/// `chunk`'s settings other than the learning mode and the per-phase limits.
#[derive(Debug, Clone, PartialEq)]
pub struct ChunkSettings {
    /// `bottom-only`: a state learns rules only while no state below it has learned one.
    pub bottom_only: bool,
    pub naming_style: NamingStyle,
    /// `interrupt`: a run stops after the phase in which a rule was learned.
    pub interrupt: bool,
    /// `explain-interrupt`: stop after learning a rule the explainer watches (rusoar has no
    /// explainer, so it never stops for this).
    pub explain_interrupt: bool,
    /// `warning-interrupt`: stop after a learning problem is detected.
    pub warning_interrupt: bool,
    pub automatically_create_singletons: bool,
    pub add_ltm_links: bool,
    /// `add-osk`: backtrace through the operator selection knowledge.
    pub add_osk: bool,
    pub allow_local_negations: bool,
    pub allow_opaque: bool,
    /// The user singletons, one per attribute, in the order they were added (9.6 lists them
    /// in the order of its hash table).
    pub singletons: Vec<Singleton>,
}

/// The user singletons 9.6 starts with: `(<any> ^ATTR <any>)` for each of these.
const DEFAULT_SINGLETONS: [&str; 11] = [
    "superstate",
    "io",
    "type",
    "input-link",
    "output-link",
    "reward-link",
    "epmem",
    "command",
    "result",
    "present-id",
    "smem",
];

impl Default for ChunkSettings {
    fn default() -> Self {
        ChunkSettings {
            bottom_only: false,
            naming_style: NamingStyle::Rule,
            interrupt: false,
            explain_interrupt: false,
            warning_interrupt: false,
            automatically_create_singletons: true,
            add_ltm_links: false,
            add_osk: true,
            allow_local_negations: true,
            allow_opaque: true,
            singletons: DEFAULT_SINGLETONS
                .iter()
                .map(|a| Singleton {
                    id: ElementType::Any,
                    attribute: a.to_string(),
                    value: ElementType::Any,
                })
                .collect(),
        }
    }
}

impl ChunkSettings {
    /// The on/off setting named `name`, as `chunk NAME [on|off]` reaches it.
    pub fn switch(&mut self, name: &str) -> Option<&mut bool> {
        Some(match name {
            "bottom-only" => &mut self.bottom_only,
            "interrupt" => &mut self.interrupt,
            "explain-interrupt" => &mut self.explain_interrupt,
            "warning-interrupt" => &mut self.warning_interrupt,
            "automatically-create-singletons" => &mut self.automatically_create_singletons,
            "add-ltm-links" => &mut self.add_ltm_links,
            "add-osk" => &mut self.add_osk,
            "allow-local-negations" => &mut self.allow_local_negations,
            "allow-opaque" => &mut self.allow_opaque,
            _ => return None,
        })
    }
}
