//! The bridge from firing to RHS functions (spec §1f): `write` output goes to the agent's
//! trace, `halt` stops the run; everything else is evaluated by `crate::rhs`.

use crate::agent::Agent;
use crate::symbols::{Sym, SymData};

pub fn call(agent: &mut Agent, name: &str, args: &[Sym]) -> Result<Option<Sym>, String> {
    let num = |agent: &Agent, s: Sym| match agent.symbols.get(s) {
        SymData::Int(i) => Some(*i as f64),
        SymData::Float(f) => Some(*f),
        _ => None,
    };
    match name {
        "write" => {
            let text: String = args.iter().map(|a| agent.symbols.plain(*a)).collect();
            agent.output.push_str(&text);
            Ok(None)
        }
        "crlf" => Ok(Some(agent.symbols.str("\n"))),
        "halt" | "succeeded" | "failed" => {
            agent.decider.halted = true;
            Ok(None)
        }
        "+" | "*" => {
            let all_int = args
                .iter()
                .all(|a| matches!(agent.symbols.get(*a), SymData::Int(_)));
            if all_int {
                let mut acc: i64 = if name == "+" { 0 } else { 1 };
                for a in args {
                    if let SymData::Int(i) = agent.symbols.get(*a) {
                        acc = if name == "+" {
                            acc.wrapping_add(*i)
                        } else {
                            acc.wrapping_mul(*i)
                        };
                    }
                }
                return Ok(Some(agent.symbols.int(acc)));
            }
            let mut acc = if name == "+" { 0.0 } else { 1.0 };
            for a in args {
                let x = num(agent, *a).ok_or_else(|| {
                    format!(
                        "Error: non-number ({}) passed to {name} function",
                        agent.symbols.text(*a)
                    )
                })?;
                acc = if name == "+" { acc + x } else { acc * x };
            }
            Ok(Some(agent.symbols.float(acc)))
        }
        _ => Err(format!("Error: rhs function {name} is not available yet")),
    }
}
