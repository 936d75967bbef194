//! The numbers of SML's events and phases that the kernel thread reports (the values
//! `soar_sml` 9.6.5 gives its `smlEVENT_*` and `sml_*_PHASE` constants).

use rusoar::Phase;

/// `smlEVENT_PRINT`.
pub const PRINT: i32 = 47;
/// `smlEVENT_AFTER_PRODUCTION_FIRED`.
pub const AFTER_PRODUCTION_FIRED: i32 = 39;
/// `smlEVENT_BEFORE_PRODUCTION_RETRACTED`.
pub const BEFORE_PRODUCTION_RETRACTED: i32 = 40;
/// `smlEVENT_RHS_USER_FUNCTION`.
pub const RHS_USER_FUNCTION: i32 = 48;
/// `smlEVENT_CLIENT_MESSAGE`.
pub const CLIENT_MESSAGE: i32 = 50;
/// `smlEVENT_SYSTEM_START`.
pub const SYSTEM_START: i32 = 3;
/// `smlEVENT_SYSTEM_STOP`.
pub const SYSTEM_STOP: i32 = 5;
/// `smlEVENT_AFTER_ALL_OUTPUT_PHASES`.
pub const AFTER_ALL_OUTPUT_PHASES: i32 = 53;
/// `smlEVENT_AFTER_ALL_GENERATED_OUTPUT`.
pub const AFTER_ALL_GENERATED_OUTPUT: i32 = 54;
/// `smlEVENT_AFTER_AGENT_CREATED`.
pub const AFTER_AGENT_CREATED: i32 = 41;
/// `smlEVENT_BEFORE_AGENT_DESTROYED`.
pub const BEFORE_AGENT_DESTROYED: i32 = 42;
/// `smlEVENT_BEFORE_AGENT_REINITIALIZED`.
pub const BEFORE_AGENT_REINITIALIZED: i32 = 43;
/// `smlEVENT_AFTER_AGENT_REINITIALIZED`.
pub const AFTER_AGENT_REINITIALIZED: i32 = 44;
/// `sml_RUN_SELF`: the run flags of an update event during one agent's run.
pub const RUN_SELF: i32 = 1;
/// `sml_RUN_ALL`: the run flags of an update event during a run of all agents.
pub const RUN_ALL: i32 = 2;

/// The run events that come before a phase: SML's decision cycle starts with its input
/// phase.
pub fn before_phase(p: Phase) -> &'static [i32] {
    match p {
        Phase::Input => &[28, 13],
        Phase::Propose => &[14],
        Phase::Decide => &[15],
        Phase::Apply => &[16],
        Phase::Output => &[17],
    }
}

/// The run events that come after a phase: the decision cycle ends with the output phase.
pub fn after_phase(p: Phase) -> &'static [i32] {
    match p {
        Phase::Input => &[20],
        Phase::Propose => &[21],
        Phase::Decide => &[22],
        Phase::Apply => &[23],
        Phase::Output => &[24, 29],
    }
}

/// A phase as SML numbers it (`sml_INPUT_PHASE` is 0, ...).
pub fn phase_number(p: Phase) -> i32 {
    match p {
        Phase::Input => 0,
        Phase::Propose => 1,
        Phase::Decide => 2,
        Phase::Apply => 3,
        Phase::Output => 4,
    }
}

/// Whether `id` is a run event.
pub fn is_run_event(id: i32) -> bool {
    (8..=36).contains(&id)
}
