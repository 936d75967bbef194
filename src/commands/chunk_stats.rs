//! `chunk stats` (Soar manual, ch. 9, `chunk`, "Chunking Statistics"): what learning did
//! since the last `init-soar`, laid out as 9.6 prints it (values from column 72).

use crate::agent::AgentCore;

const RULE: &str =
    "---------------------------------------------------------------------------\n";
const DOUBLE_RULE: &str =
    "===========================================================================\n";

fn row(out: &mut String, label: &str, value: u64) {
    out.push_str(&format!("{label:<71}{value}\n"));
}

fn heading(out: &mut String, title: &str) {
    out.push('\n');
    out.push_str(RULE);
    out.push_str(title);
    out.push('\n');
    out.push_str(RULE);
}

/// The statistics table.
pub fn chunk_stats(agent: &AgentCore) -> String {
    let l = &agent.learn;
    let s = &l.stats;
    let mut out = String::from(DOUBLE_RULE);
    out.push_str("                  Explanation-Based Chunking Statistics\n");
    out.push_str(DOUBLE_RULE);
    row(&mut out, "Rules learned", l.chunks_since_init);
    row(&mut out, "Justifications learned", l.justifications_since_init);
    heading(&mut out, "                               Work Performed");
    row(&mut out, "Sub-states analyzed", l.substates_analyzed);
    // 9.6 counts every instantiation here, wherever it matched: rule firings, learned
    // rules' instantiations, the impasse items' stand-ins and the memories' retrievals.
    let instantiations = agent.decider.firings
        + s.learned_instantiations
        + s.item_instantiations
        + s.retrieval_instantiations;
    row(&mut out, "Number of rules fired in substates analyzed", instantiations);
    row(
        &mut out,
        "Number of rule firings analyzed during backtracing",
        s.firings_backtraced,
    );
    out.push('\n');
    row(&mut out, "Conditions merged", s.conditions_merged);
    // rusoar keeps a rule's disjunctions as they are: it never merges two of them.
    row(&mut out, "Disjunction tests merged", 0);
    row(&mut out, "Operational constraints", s.operational_constraints);
    row(
        &mut out,
        "Non-operational constraints detected",
        s.constraints_collected,
    );
    row(
        &mut out,
        "Non-operational constraints enforced",
        s.constraints_enforced,
    );
    heading(&mut out, "                     Problem-Solving Characteristics");
    // rusoar never needs to repair a learned rule: its conditions are connected by
    // construction.
    row(
        &mut out,
        "Rules repaired that had unconnected conditions or actions",
        0,
    );
    row(
        &mut out,
        "Chunk used negated reasoning about sub-state",
        s.local_negation_chunks,
    );
    row(
        &mut out,
        "Chunk tested knowledge retrieved from long-term memory",
        s.ltm_chunks,
    );
    row(
        &mut out,
        "Justification used negated reasoning about sub-state",
        s.local_negation_justifications,
    );
    row(
        &mut out,
        "Justification tested knowledge retrieved from long-term memory",
        s.ltm_justifications,
    );
    heading(&mut out, "                           Identity Analysis");
    row(&mut out, "Identities created", s.identities_created);
    // 9.6 counts these only with its explainer recording the rule.
    row(&mut out, "Distinct identities in learned rules", 0);
    row(&mut out, "Identity propagations", s.identity_propagations);
    row(
        &mut out,
        "Identity propagations blocked",
        s.identity_propagations_blocked,
    );
    row(&mut out, "Identities joined", s.identities_joined);
    row(&mut out, "Identities literalized", 0);
    heading(&mut out, "                      Learning Skipped or Unsuccessful");
    row(&mut out, "Ignored duplicate of existing rule", s.duplicates);
    row(
        &mut out,
        "Skipped because problem-solving tested ^quiescence true",
        s.tested_quiescence,
    );
    row(
        &mut out,
        "Skipped because no super-state knowledge tested",
        s.no_grounds,
    );
    row(
        &mut out,
        "Skipped because MAX-CHUNKS exceeded in a decision cycle",
        s.max_chunks,
    );
    row(
        &mut out,
        "Skipped because MAX-DUPES exceeded for rule this decision cycle",
        s.max_dupes,
    );
    out
}
