//! Working memory (spec §2): WMEs with timetags.
/// A working-memory element's handle.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct WmeId(pub u32);
