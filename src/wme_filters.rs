//! `wm watch` filters (Soar manual, ch. 9, `wm`): with WME tracing on (`trace -w`), a
//! `=>WM:` or `<=WM:` line is printed only when some filter lets it through, once there
//! is any filter. A filter is an identifier, attribute and value pattern (`None` matches
//! anything) and whether it watches additions, removals or both.

use crate::symbols::Sym;
use crate::wm::Wme;

/// One filter.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct WmeFilter {
    pub id: Option<Sym>,
    pub attr: Option<Sym>,
    pub value: Option<Sym>,
    pub adds: bool,
    pub removes: bool,
}

impl WmeFilter {
    fn matches(&self, w: &Wme) -> bool {
        let fits = |pattern: Option<Sym>, s: Sym| pattern.is_none_or(|p| p == s);
        fits(self.id, w.id) && fits(self.attr, w.attr) && fits(self.value, w.value)
    }
}

/// The filters, newest first (as 9.6 lists them).
#[derive(Debug, Clone, Default)]
pub struct WmeFilters {
    pub list: Vec<WmeFilter>,
}

impl WmeFilters {
    /// Whether the trace shows the addition (`added`) or removal of `w`: yes with no
    /// filters, else when a filter of that kind matches it.
    pub fn passes(&self, w: &Wme, added: bool) -> bool {
        self.list.is_empty()
            || self
                .list
                .iter()
                .any(|f| (if added { f.adds } else { f.removes }) && f.matches(w))
    }
}
