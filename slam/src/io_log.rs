//! The input-link and output-link traffic of one SoarRobot run, as text lines, so that the
//! run can be replayed step by step in another kernel (the official 9.6 kernel, by
//! `scripts/slam_oracle.py`) and the two agents' choices compared.
//!
//! One line per event, words separated by spaces, in the order the loop did them:
//!
//! | line | when |
//! |---|---|
//! | `step N` | the input phase of loop step N begins |
//! | `init X Y TH R0 … R15` | step 1: `^currentrobotdata` is made (`^X ^Y ^Th`, then 16 `^sonar` objects with `^index i ^range Ri`), then `^wallData` |
//! | `update X V`, `update Y V`, `update Th V`, `update range I V` | a value of `^currentrobotdata` changed (unchanged values are not written) |
//! | `remove-wall K` | the input wall K (numbered from 1 as added) was removed |
//! | `wall K SX SY EX EY RX RY RTH LENGTH R TH TIME` | input wall K was added: `^Start ^X ^Y`, `^End ^X ^Y`, `^Ref ^X ^Y ^Th`, `^Length ^R ^Th ^Time`, in that order |
//! | `command NAME ATTR VALUE …` | the output phase carried out a new command and marked it `^status complete` |
//! | `decided FIRINGS OP …` | the step's decision ended: rule firings so far, then the operators selected in it (any goal level) |

use std::fmt::Write;

use super::pipeline::Wall;

/// The lines of one run's log (see the module documentation).
#[derive(Debug, Default, Clone)]
pub struct IoLog {
    pub lines: Vec<String>,
}

impl IoLog {
    pub fn step(&mut self, n: u64) {
        self.lines.push(format!("step {n}"));
    }

    pub fn init(&mut self, x: i64, y: i64, th: i64, ranges: &[i64]) {
        let mut l = format!("init {x} {y} {th}");
        for r in ranges {
            let _ = write!(l, " {r}");
        }
        self.lines.push(l);
    }

    /// `what` is `X`, `Y`, `Th` or `range I`.
    pub fn update(&mut self, what: &str, value: i64) {
        self.lines.push(format!("update {what} {value}"));
    }

    pub fn remove_wall(&mut self, serial: u64) {
        self.lines.push(format!("remove-wall {serial}"));
    }

    pub fn wall(&mut self, serial: u64, w: &Wall) {
        self.lines.push(format!(
            "wall {serial} {} {} {} {} {} {} {} {} {} {} {}",
            w.start.x,
            w.start.y,
            w.end.x,
            w.end.y,
            w.reference.x,
            w.reference.y,
            w.reference.th,
            w.length,
            w.r,
            w.th,
            w.time
        ));
    }

    pub fn command(&mut self, name: &str, params: &[(String, String)]) {
        let mut l = format!("command {name}");
        for (a, v) in params {
            let _ = write!(l, " {a} {v}");
        }
        self.lines.push(l);
    }

    pub fn decided(&mut self, firings: u64, operators: &[String]) {
        let mut l = format!("decided {firings}");
        for o in operators {
            let _ = write!(l, " {o}");
        }
        self.lines.push(l);
    }
}
