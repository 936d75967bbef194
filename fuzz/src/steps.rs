//! What the memory generators (`smem_agent.rs`, `epmem_agent.rs`) share: an agent's text
//! and the steps it is run by, and the run itself, which checks the kernel's invariants
//! after every step. The fuzz targets and the tests that include the generators include
//! this file too.

use rusoar::{Agent, RunUnit, StopReason};

/// What a step between invariant checks does.
#[derive(Debug, Clone, PartialEq)]
pub enum Step {
    Phase,
    Decision,
    /// A command that may fail.
    Command(String),
}

/// An agent: the text to source and the steps to run it by.
#[derive(Debug, Clone)]
pub struct Steps {
    pub source: String,
    pub steps: Vec<Step>,
}

impl std::fmt::Display for Steps {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        writeln!(f, "{}", self.source)?;
        for step in &self.steps {
            match step {
                Step::Phase => writeln!(f, "run 1 -p")?,
                Step::Decision => writeln!(f, "run 1")?,
                Step::Command(c) => writeln!(f, "{c}")?,
            }
        }
        Ok(())
    }
}

/// Sources `spec` into `agent` (under `name`) and runs its steps, checking the kernel's
/// invariants after each; the first failure is described, with the step it followed. A
/// command may fail with an error (an episode not stored, a removal of what is not there).
pub fn run_steps(agent: &mut Agent, name: &str, spec: &Steps) -> Result<(), String> {
    if let Err(e) = agent.source_text(name, &spec.source) {
        if !e.is_warning() {
            return Err(format!("the agent does not load: {}", e.render()));
        }
    }
    check(agent, "after loading")?;
    for (i, step) in spec.steps.iter().enumerate() {
        let mut interrupted = false;
        let done = match step {
            Step::Phase | Step::Decision => {
                let unit = if *step == Step::Phase {
                    RunUnit::Phases
                } else {
                    RunUnit::Decisions
                };
                agent.run(1, unit).map(|r| {
                    interrupted = r.stop == StopReason::Interrupted;
                })
            }
            Step::Command(c) => agent.execute(c).map(|_| ()),
        };
        if let Err(e) = done {
            // A command may fail for a plain reason (a rule excised twice); a run may not.
            if !e.is_warning() && !matches!(step, Step::Command(_)) {
                return Err(format!("step {} ({step:?}) failed: {}", i + 1, e.render()));
            }
        }
        let _ = agent.take_output();
        check(agent, &format!("after step {} ({step:?})", i + 1))?;
        // The embedder stopped it (a fuzz target's budget of events is spent).
        if interrupted {
            break;
        }
    }
    Ok(())
}

fn check(agent: &Agent, when: &str) -> Result<(), String> {
    agent.check_invariants().map_err(|broken| {
        format!(
            "{when}, the kernel's invariants do not hold:\n{}",
            broken.join("\n")
        )
    })
}
