//! The working-memory interface of semantic memory (Soar manual, Semantic Memory,
//! "Working Memory Interface").

/// Each state's record of its smem link.
#[derive(Debug, Default)]
pub struct Links {}
