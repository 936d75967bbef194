//! The decision cycle's trace as typed events (Soar manual, chapter 9, "trace"): the
//! kernel says what happened, at the moment it happens and only when the trace setting
//! that shows it is on; a listener turns each event into text. The default listener,
//! `trace_text`, prints Soar 9.6's trace; another one (a debugger's view, a program's
//! callback) can read the same events without parsing that text.

use crate::decide::state::{ImpasseKind, Phase, Preference};
use crate::symbols::Sym;
use crate::wm::Wme;

/// One line (or header) of the decision cycle's trace.
#[derive(Debug, Clone, Copy)]
pub(crate) enum TraceEvent<'a> {
    /// A phase begins (`trace --phases`).
    PhaseBegin(Phase),
    /// A phase ends (`trace --phases`).
    PhaseEnd(Phase),
    /// The apply phase fires one elaboration cycle's productions: all o-supported (PE)
    /// or not (IE), at the goal of this depth (`trace --phases`).
    FiringProductions { o_support: bool, depth: u32 },
    /// The apply phase's elaboration cycle changes working memory (`trace --phases`).
    ChangeWorkingMemory { o_support: bool },
    /// The firings of one goal in an elaboration cycle begin (`trace --waterfall`); no
    /// goal when only the retractions of goals that are gone are pending.
    InnerElaboration { level: u32, goal: Option<Sym> },
    /// A match below the active goal waits: an action of it adds to `id`, at `level`, on
    /// or above the elaboration cycle's change level (`trace --waterfall`).
    WaterfallAbort { id: Sym, level: u32, change_level: u32 },
    /// A WME enters (`added`) or leaves working memory (`trace --wmes`).
    /// With working-memory activation on, the WME's activation (printed after it).
    Wme {
        added: bool,
        wme: &'a Wme,
        activation: Option<f64>,
    },
    /// A preference is asserted (`added`) or retracted (`trace --preferences`), at the
    /// level of the goal it was made for, with the rule or justification that made it.
    Preference {
        added: bool,
        pref: &'a Preference,
        level: u32,
        rule: Option<&'a str>,
    },
    /// A top-level o-supported acceptable preference not added because its value has one
    /// already (`trace --preferences`): `+ (S1 ^a b +  :O ) (rule) ALREADY SUPPORTED ON TOP
    /// LEVEL.  IGNORING.`
    IgnoredPreference {
        pref: &'a Preference,
        level: u32,
        rule: Option<&'a str>,
    },
    /// One of a traced firing's or retraction's preferences (`trace --timetags` or
    /// `--fullwmes`), at its identifier's level.
    InstantiationPreference { pref: &'a Preference, level: u32 },
    /// The matcher queues a new match of a rule for firing, o-supported (`ms_o_assertions`)
    /// or not (`trace --assertions`).
    MatchQueued { rule: &'a str, o_support: bool },
    /// An instantiation's preferences go into preference memory (`trace --assertions`).
    AssertingInstantiation { rule: &'a str },
    /// An instantiation's preferences are in preference memory (`trace --assertions`).
    InstantiationAsserted,
    /// A queued match fires: its instantiation is made, in `state` at `level`
    /// (`trace --assertions`).
    NewMatch {
        rule: &'a str,
        state: Option<Sym>,
        level: u32,
    },
    /// A traced rule fires (`trace --rules` and the other firing settings).
    Firing { rule: &'a str },
    /// A traced rule or justification retracts.
    Retraction { rule: &'a str },
    /// The WMEs a traced firing or retraction matched: timetags only, or in `full`
    /// (`trace --timetags`, `--fullwmes`).
    MatchWmes {
        wmes: &'a [Wme],
        full: bool,
        retracting: bool,
    },
    /// A selected operator leaves its slot because its proposal no longer matches
    /// (`trace --consistency`).
    /// Each WME with its activation when working-memory activation is on, as 9.6 prints a
    /// WME in every trace line.
    OperatorRemoval {
        wme: Option<&'a Wme>,
        activation: Option<f64>,
    },
    /// A substate goes because a WME of its goal dependency set changed (`trace --gds`).
    GdsRemoval {
        goal: Sym,
        wme: &'a Wme,
        activation: Option<f64>,
    },
    /// A WME joins a substate's goal dependency set (`trace --gds-wmes`).
    GdsAdd {
        goal: Sym,
        wme: &'a Wme,
        activation: Option<f64>,
    },
    /// An operator is selected for the goal at `level` in decision `cycle` (`trace
    /// --decisions`), with its `^name` values.
    Operator {
        cycle: u64,
        level: u32,
        operator: Sym,
        names: &'a [String],
    },
    /// A state in the goal stack (`trace --decisions`): a new substate with its impasse
    /// (on the operator slot when the flag says so), the bottom state again while it
    /// waits out a state no-change, or the top state, with no impasse, at creation and
    /// `init-soar` (cycle 0).
    State {
        cycle: u64,
        level: u32,
        state: Sym,
        impasse: Option<(ImpasseKind, bool)>,
    },
    /// The run stops because the agent halted or reached max-goal-depth.
    SystemHalted,
    /// An RL rule's value changes (`trace --rl`): its expected current reward, expected
    /// future reward and their sum, before and after.
    RlUpdate {
        rule: &'a str,
        before: [f64; 3],
        after: [f64; 3],
    },
    /// A gap in RL rule coverage starts or ends on a state (`trace --rl`).
    /// A candidate of an indifferent choice by epsilon-greedy or Boltzmann exploration,
    /// with its numeric value and, under Boltzmann, the chance it is chosen
    /// (`trace --indifferent-selection`).
    Candidate { value: Sym, sum: f64, probability: Option<f64> },
    /// The update log (`rl --set update-log-path`) could not take a line.
    RlLogError { path: &'a str, message: &'a str },
    RlGap { started: bool, goal: Sym },
    /// The substate below a goal goes with the operator that left its slot (`trace
    /// --consistency`).
    OperatorRemovalSubstate { state: Sym },
    /// The substates below `goal` go because its decision no longer agrees with the
    /// preferences (`trace --consistency`); `empty_slot` when no operator was selected.
    InconsistentDecision { goal: Sym, empty_slot: bool },
    /// A phase stopped at max-elaborations; the run goes on to the `next` phase
    /// (warnings on).
    MaxElaborations { next: Phase },
    /// A rule both elaborates and applies the operator, so it gets i-support (warnings
    /// on).
    MixedOperatorElaborations { rule: &'a str },
    /// A no-change impasse made a goal deeper than max-goal-depth: the run stops.
    GoalDepthExceeded { max_depth: i64 },
    /// The phase learned max-chunks rules already: a result gets no new rule
    /// (`trace --chunk-warnings`).
    MaxChunksReached,
    /// `chunk allow-local-negations off` kept a rule from being learned: its reasoning
    /// tested these negations about the substate (`trace --chunk-warnings`).
    LocalNegationRefused { conditions: &'a [String] },
    /// A firing in a substate that `chunk only` (not flagged by `force-learn`) or
    /// `chunk except` (flagged by `dont-learn`) keeps from learning
    /// (`trace --chunk-warnings`).
    NotLearning {
        rule: &'a str,
        state: &'a str,
        flagged: bool,
    },
    /// A rule or justification was learned (`trace --learning`): its name, and the rule's
    /// text when the setting prints rules.
    LearnedRule { name: &'a str, text: Option<&'a str> },
    /// `chunk interrupt`: a rule was learned, and the run stops after this phase.
    LearningInterrupt,
    /// A right-hand-side function failed, with its message; `fresh_line` when 9.6 starts
    /// the message on a line of its own.
    RhsError { message: &'a str, fresh_line: bool },
}
