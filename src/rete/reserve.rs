//! Room reserved ahead for rules about to be added (see `commands/load_forecast.rs`).

use super::Rete;

impl Rete {
    /// Reserves the node and alpha-memory tables' room for `rules` more rules, at the
    /// network's present count of each per rule and a quarter more. Room never written
    /// costs address space, not memory.
    pub(crate) fn reserve_for_rules(&mut self, rules: usize) {
        let present = self.prods.len();
        if present == 0 {
            return;
        }
        let room = |count: usize| rules.saturating_mul(count) / present / 4 * 5;
        let (nodes, amems) = (room(self.nodes.len()), room(self.amems.len()));
        // A forecast too large to reserve leaves the tables to grow as they go.
        let _ = self.nodes.try_reserve_exact(nodes);
        let _ = self.amems.try_reserve_exact(amems);
    }
}
