//! The decision phase (Soar manual, chapter 2, "How preferences are evaluated to decide an
//! operator", and 2.7.1 "Impasse Types"): from the top goal down, the first operator slot
//! without a selected operator whose preferences changed is decided; a winner is installed,
//! otherwise the goal impasses. With nothing to decide, the bottom goal has a no-change.

use super::procedure::{self, NumericMode, Outcome, Policy, Pref};
use crate::agent::Exploration;
use super::state::ImpasseKind;
use crate::learn::Osk;
use crate::agent::AgentCore;
use crate::symbols::Sym;
use crate::trace_events::TraceEvent;

impl AgentCore {
    /// The decision-line prefix: dc right-justified to 6, then 3 spaces per level below the
    /// top (as 9.6's trace prints it).
    pub(super) fn slot_prefs(&self, key: (Sym, Sym)) -> Vec<Pref> {
        let Some(slot) = self.decider.slots.get(&key) else {
            return Vec::new();
        };
        // Candidates come out oldest first: the reverse of Soar's head-inserted list.
        slot.prefs
            .iter()
            .map(|&pid| {
                let p = &self.decider.prefs[pid];
                Pref {
                    kind: p.kind,
                    value: p.value,
                    referent: p.referent,
                    number: p.number,
                }
            })
            .collect()
    }

    /// Decides the first operator slot without an installed operator, from the top; if
    /// every goal has one, the bottom goal has an operator no-change (decide.cpp
    /// `decide_context_slots`).
    pub(super) fn decide_context_slots(&mut self) {
        // The decision decides every changed slot anew.
        self.decider.consistency_pending.clear();
        if let Some(seed) = self.decider.predict_seed.take() {
            self.rng.seed(seed);
        }
        let op = self.operator_sym();
        let policy = self.exploration_policy();
        let numeric_mode = self.settings.numeric_mode;
        let n = self.decider.goals.len();
        for gi in 0..n {
            let g = &self.decider.goals[gi];
            // Decidable: no installed operator and the preferences changed (a selected
            // operator is not decided again while it stays consistent).
            if g.operator.is_some() || !g.slot_changed {
                continue;
            }
            // Copies: the decision changes the goal list.
            let (state, level) = (g.state, g.level);
            self.decider.goals[gi].slot_changed = false;
            let prefs = self.slot_prefs((state, op));
            let forced = self.take_forced_operator(&prefs);
            let outcome = match forced {
                Some(o) => Outcome::Winner(o),
                None => {
                    if self.settings.trace.indifferent {
                        self.trace_candidates(&prefs, policy, numeric_mode);
                    }
                    procedure::decide(&prefs, policy, numeric_mode, &mut self.rng)
                }
            };
            // A substate's choice keeps the knowledge it rests on, for chunking; a forced
            // choice rests on none, an impasse clears it.
            self.decider.goals[gi].osk = match outcome {
                Outcome::Winner(o) if forced.is_none() && level > 1 => {
                    self.selection_knowledge((state, op), &prefs, o)
                }
                _ => None,
            };
            let (kind, on_operator, items) = match outcome {
                Outcome::Winner(o) => {
                    let learning = self.rl_enabled();
                    let mut decided = None;
                    if learning {
                        // Soar manual, 5.3 "Updating RL Rule Values": the selection
                        // updates the RL rules of the state's previous RL operator.
                        let cands = procedure::candidates(&prefs).unwrap_or_else(|_| vec![o]);
                        let chosen = cands.iter().position(|c| *c == o).unwrap_or(0);
                        let values = self.rl_candidates(state, &prefs, &cands);
                        self.rl_tabulate_rewards();
                        self.rl_decided(state, &values, chosen, policy);
                        decided = Some((cands, values, chosen));
                    }
                    self.remove_goals_below(gi);
                    if let Some((cands, values, chosen)) = decided {
                        self.rl_store(state, o);
                        self.rl_trace_record(state, level, &cands, &values, chosen, policy);
                    }
                    self.mark_queued_matches();
                    let w = self.add_wme(state, op, o, false);
                    if let Some(wme) = self.wm.get(w).copied() {
                        self.trace_wme(true, &wme);
                    }
                    self.flush_impasse_item_updates();
                    self.classify_new_matches();
                    self.decider.wme_changes += 1;
                    self.decider.goals[gi].operator = Some((o, w));
                    if self.settings.trace.decisions {
                        let names = self.name_values(o);
                        self.emit(&TraceEvent::Operator {
                            cycle: self.decider.d_cycle_count,
                            level,
                            operator: o,
                            names: &names,
                        });
                    }
                    return;
                }
                Outcome::NoCandidates => (ImpasseKind::NoChange, false, Vec::new()),
                Outcome::Tie(items) => (ImpasseKind::Tie, true, items),
                Outcome::Conflict(items) => (ImpasseKind::Conflict, true, items),
                Outcome::ConstraintFailure(items) => (ImpasseKind::ConstraintFailure, true, items),
            };
            // The same impasse again keeps its substate, its items brought up to date (the
            // candidates of a tie may change while it lasts): look further down.
            let same = self
                .decider
                .goals
                .get(gi + 1)
                .is_some_and(|g| g.impasse == Some((kind, on_operator)));
            if same {
                // 9.6 brings the items up to date at each such decision, making their
                // instantiations anew (counted by `chunk stats`).
                let non_numeric = self.non_numeric_items(state, &items);
                self.learn.stats.item_instantiations += (items.len() + non_numeric.len()) as u64;
                if self.decider.goals[gi + 1].items != items {
                    self.update_impasse_items(gi + 1, items, non_numeric);
                }
                continue;
            }
            if gi + 1 < n || kind != ImpasseKind::NoChange || on_operator {
                self.impasse(gi, kind, on_operator, items);
                return;
            }
            self.impasse(gi, kind, on_operator, items);
            return;
        }
        self.flush_impasse_item_updates();
        // Nothing decidable: the bottom goal made no progress.
        if let Some(last) = n.checked_sub(1) {
            let on_operator = self.decider.goals[last].operator.is_some();
            self.impasse(last, ImpasseKind::NoChange, on_operator, Vec::new());
        }
    }


    /// The origins of the preferences of slot `key` that selected `winner` (`chunk
    /// add-osk`; with the setting off, its prohibit preferences alone, as in 9.6); `None`
    /// when there are none.
    fn selection_knowledge(&self, key: (Sym, Sym), prefs: &[Pref], winner: Sym) -> Option<Osk> {
        let slot = self.decider.slots.get(&key)?;
        let chosen = if self.settings.chunk.add_osk {
            super::osk::selection_knowledge(prefs, winner)
        } else {
            super::osk::prohibits(prefs)
        };
        let origins: Vec<_> = chosen
            .into_iter()
            .filter_map(|i| self.decider.prefs[*slot.prefs.get(i)?].origin.clone())
            .collect();
        (!origins.is_empty()).then(|| origins.into())
    }

    /// `decide select`: the forced operator when one of the slot's acceptable preferences
    /// proposes it, whatever the other preferences say; it is used up then (Soar manual,
    /// chapter 9, "decide").
    fn take_forced_operator(&mut self, prefs: &[Pref]) -> Option<Sym> {
        let forced = self.decider.forced_operator.as_deref()?;
        let o = prefs
            .iter()
            .filter(|p| p.kind == procedure::PrefType::Acceptable)
            .map(|p| p.value)
            .find(|&v| self.symbols.text(v) == forced)?;
        self.decider.forced_operator = None;
        Some(o)
    }

    /// `decide predict`: what the next decision will do, without doing it: the operator
    /// it selects, or `tie`, `conflict`, `constraint`, or `none` (no change). The
    /// generator is seeded with a number drawn from it, before the prediction and again
    /// at the decision, so that a random choice comes out as predicted. As in 9.6, a
    /// forced operator (`decide select`) is predicted and used up.
    pub(crate) fn predict_decision(&mut self) -> String {
        let seed = loop {
            let s = self.rng.next_u32();
            if s != 0 {
                break s;
            }
        };
        self.decider.predict_seed = Some(seed);
        self.rng.seed(seed);
        let op = self.operator_sym();
        let policy = self.exploration_policy();
        let numeric_mode = self.settings.numeric_mode;
        let decidable = self
            .decider
            .goals
            .iter()
            .find(|g| g.operator.is_none() && g.slot_changed)
            .map(|g| g.state);
        let Some(state) = decidable else {
            return "none".to_string();
        };
        let prefs = self.slot_prefs((state, op));
        let outcome = match self.take_forced_operator(&prefs) {
            Some(o) => Outcome::Winner(o),
            None => procedure::decide(&prefs, policy, numeric_mode, &mut self.rng),
        };
        match outcome {
            Outcome::Winner(o) => self.symbols.text(o),
            Outcome::NoCandidates => "none".to_string(),
            Outcome::Tie(_) => "tie".to_string(),
            Outcome::Conflict(_) => "conflict".to_string(),
            Outcome::ConstraintFailure(_) => "constraint".to_string(),
        }
    }

    /// `--auto-reduce`: after each decision phase, epsilon and the temperature go down by
    /// their reductions (observed on 9.6: the decision uses the values before).
    pub(super) fn reduce_exploration_parameters(&mut self) {
        let s = &mut self.settings;
        if s.auto_reduce {
            s.epsilon = s.epsilon_reduction.apply(s.epsilon);
            s.temperature = s.temperature_reduction.apply(s.temperature);
        }
    }

    /// The exploration policy of `indifferent-selection`, with its parameter.
    /// `trace --indifferent-selection`: before epsilon-greedy or Boltzmann exploration
    /// chooses among indifferent candidates, each candidate's value (and, for Boltzmann,
    /// its chance), as 9.6 lists them; the other policies list nothing.
    fn trace_candidates(&mut self, prefs: &[Pref], policy: Policy, mode: NumericMode) {
        let Ok(cands) = procedure::candidates(prefs) else {
            return;
        };
        if cands.len() < 2 {
            return;
        }
        let values: Vec<f64> = cands
            .iter()
            .map(|c| procedure::numeric_value(prefs, *c, mode))
            .collect();
        let chances = match policy {
            Policy::EpsilonGreedy { .. } => None,
            Policy::Boltzmann { temperature } => Some(procedure::boltzmann_chances(&values, temperature)),
            _ => return,
        };
        for (i, (&value, &sum)) in cands.iter().zip(&values).enumerate() {
            let probability = chances.as_ref().map(|c| c[i]);
            self.emit(&TraceEvent::Candidate {
                value,
                sum,
                probability,
            });
        }
    }

    fn exploration_policy(&self) -> Policy {
        match self.settings.exploration {
            Exploration::First => Policy::First,
            Exploration::Last => Policy::Last,
            Exploration::EpsilonGreedy => Policy::EpsilonGreedy {
                epsilon: self.settings.epsilon,
            },
            Exploration::Boltzmann => Policy::Boltzmann {
                temperature: self.settings.temperature,
            },
            Exploration::Softmax => Policy::Softmax,
        }
    }

    /// The `^name` values of an object (operators are printed with them).
    pub(crate) fn name_values(&self, o: Sym) -> Vec<String> {
        let Some(name) = self.symbols.find_str("name") else {
            return Vec::new();
        };
        self.wm
            .of_id(o)
            .filter_map(|w| self.wm.get(w))
            .filter(|w| w.attr == name && !w.acceptable)
            .map(|w| self.symbols.text(w.value))
            .collect()
    }

    /// An impasse that stays gets the current candidates as its items (decide.cpp
    /// `update_impasse_items`): for `^item` and then `^non-numeric`, its WMEs are walked
    /// newest first, a count that changed is replaced at once, an item no longer a
    /// candidate goes, then each new candidate is added in candidate order. The changes
    /// are traced and matched with the phase's others ([`Self::flush_impasse_item_updates`]).
    /// `non_numeric` is the items no numeric preference values.
    fn update_impasse_items(&mut self, sub: usize, items: Vec<Sym>, non_numeric: Vec<Sym>) {
        for (item, count, items) in [
            ("item", "item-count", &items),
            ("non-numeric", "non-numeric-count", &non_numeric),
        ] {
            let n = self.symbols.int(items.len() as i64);
            let item = self.symbols.str(item);
            let count = self.symbols.str(count);
            let state = self.decider.goals[sub].state;
            let mut kept = Vec::new();
            let wmes = self.decider.goals[sub].wmes.clone();
            for &w in wmes.iter().rev() {
                let Some(wme) = self.wm.get(w).copied() else {
                    continue;
                };
                let gone = if wme.attr == count {
                    if wme.value == n {
                        false
                    } else {
                        let added = self.wm.add(state, count, n, false);
                        self.decider.goals[sub].wmes.push(added);
                        self.decider.item_updates.0.push(added);
                        true
                    }
                } else if wme.attr == item {
                    if items.contains(&wme.value) {
                        kept.push(wme.value);
                        false
                    } else {
                        true
                    }
                } else {
                    false
                };
                if gone {
                    self.decider.goals[sub].wmes.retain(|&x| x != w);
                    self.decider.item_updates.1.push(w);
                }
            }
            for &it in items {
                if !kept.contains(&it) {
                    let added = self.wm.add(state, item, it, false);
                    self.decider.goals[sub].wmes.push(added);
                    self.decider.item_updates.0.push(added);
                }
            }
        }
        self.decider.goals[sub].items = items;
    }

    /// The impasse WMEs [`Self::update_impasse_items`] changed reach the trace and the
    /// matcher as 9.6's buffered changes do: after any newer addition of the phase, the
    /// additions newest first, then the removals, the last made first.
    pub(super) fn flush_impasse_item_updates(&mut self) {
        if self.decider.item_updates.0.is_empty() && self.decider.item_updates.1.is_empty() {
            return;
        }
        let (added, removed) = std::mem::take(&mut self.decider.item_updates);
        self.decider.wme_changes += (added.len() + removed.len()) as u64;
        for &w in added.iter().rev() {
            if let Some(wme) = self.wm.get(w).copied() {
                self.trace_wme(true, &wme);
                self.match_wme_now(w, (wme.id, wme.attr, wme.value), false);
            }
        }
        for &w in removed.iter().rev() {
            if let Some(wme) = self.wm.get(w).copied() {
                self.trace_wme(false, &wme);
                self.remove_wme(w);
            }
        }
    }
}
