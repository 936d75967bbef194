//! The bridge from firing to RHS functions (Soar manual, chapter 3, "Right-hand side Functions"):
//! the agent's parts are lent to `crate::rhs` for one call; `halt` and errors come back to
//! the decision cycle.

use crate::agent::AgentCore;
use crate::symbols::Sym;
use crate::trace_events::TraceEvent;

pub fn call(agent: &mut AgentCore, name: &str, args: &[Sym]) -> Result<Option<Sym>, String> {
    let trace_level = agent.settings.trace.level_number();
    let ltm_exists = name == "link-stm-to-ltm"
        && match args.get(1).map(|&a| agent.symbols.get(a)) {
            Some(crate::symbols::SymData::Int(n)) => agent.smem.lti_exists(*n),
            _ => false,
        };
    let mut ctx = crate::rhs::RhsContext::new(
        &mut agent.symbols,
        &agent.wm,
        &mut agent.rng,
        &mut agent.rhs_registry,
        &mut agent.output,
        &agent.name,
    );
    ctx.decision_count = agent.decider.d_cycle_count;
    ctx.agent_writes = agent.settings.agent_writes;
    ctx.trace_flags = crate::rhs::trace_flags_for_level(trace_level);
    ctx.log_channels_off = agent.settings.log_channels_off;
    ctx.ltm_exists = ltm_exists;
    let result = crate::rhs::call(name, args, &mut ctx);
    let (halt, interrupt) = (ctx.halt, ctx.interrupt);
    let (dont_learn, force_learn) = (ctx.dont_learn, ctx.force_learn);
    let fresh_line = ctx.error_fresh_line;
    drop(ctx);
    // The states `chunk except` and `chunk only` go by (Soar manual, ch. 4, "Chunking is
    // not possible for some states").
    if let Some(s) = dont_learn {
        agent.learn.dont_learn.insert(s);
    }
    if let Some(s) = force_learn {
        agent.learn.force_learn.insert(s);
    }
    if halt {
        agent.decider.halted = true;
    }
    if interrupt {
        // `(interrupt)` stops the run after this phase; the agent goes on at the next run.
        agent.decider.rhs_interrupted = true;
    }
    if let Err(msg) = &result {
        if !msg.is_empty() {
            agent.emit(&TraceEvent::RhsError {
                message: msg,
                fresh_line,
            });
        }
    }
    result
}
