//! The client's copy of an agent's input and output links, as an SML client keeps one: the
//! WMEs the program made (with client timetags, negative as SML's are) and the WMEs the
//! rules put on the output-link (with the kernel's timetags). Python reads it without
//! reaching the kernel; the program's changes wait in a queue that the kernel thread applies
//! at the next input phase, which is when SML's kernel applies a client's changes too.

use rusoar::{InputWme, Symbol, Value};
use std::collections::HashMap;

/// An identifier the client knows: the input-link, one the program made, or one on the
/// output-link.
#[derive(Debug)]
pub struct Obj {
    /// Its name as the client shows it (`I2`, `p3`, `M1`).
    pub name: String,
    /// The kernel's identifier, once known.
    pub sym: Option<Symbol>,
    /// Its WMEs, in the order the client lists them.
    pub children: Vec<usize>,
}

/// A WME's value in the client's copy.
#[derive(Debug, Clone, PartialEq)]
pub enum CValue {
    /// An integer.
    Int(i64),
    /// A float.
    Float(f64),
    /// A string.
    Str(String),
    /// An identifier (an index into [`Mirror::objs`]).
    Id(usize),
}

/// One WME of the client's copy.
#[derive(Debug)]
pub struct CWme {
    /// The identifier it hangs from (an index into [`Mirror::objs`]).
    pub parent: usize,
    /// Its attribute.
    pub attr: String,
    /// Its value.
    pub value: CValue,
    /// Its timetag: the client's (negative) for the program's WMEs, the kernel's for the
    /// output-link's.
    pub timetag: i64,
    /// The kernel's handle of a WME the program made, once the kernel has it.
    pub handle: Option<InputWme>,
    /// False once destroyed (by the program, or gone from the output-link).
    pub alive: bool,
    /// Added since the last `ClearOutputLinkChanges`.
    pub just_added: bool,
}

/// A change the program made, waiting for the kernel.
#[derive(Debug, Clone, Copy)]
pub enum Op {
    /// Add a WME the program made.
    Add(usize),
    /// Give a WME its value in the copy.
    Update(usize),
    /// Remove a WME.
    Remove(usize),
}

/// The client's copy of one agent's links.
#[derive(Debug)]
pub struct Mirror {
    /// The identifiers.
    pub objs: Vec<Obj>,
    /// The WMEs; destroyed ones stay, marked, so that stale handles can be told apart.
    pub wmes: Vec<CWme>,
    /// Changes waiting for the kernel.
    pub queue: Vec<Op>,
    /// The input-link's WME (`I1 ^input-link I2`).
    pub input_link: usize,
    /// The output-link's WME, once the rules have put something on it.
    pub output_link: Option<usize>,
    /// Output-link WMEs by kernel timetag.
    out_by_tag: HashMap<u64, usize>,
    /// Identifiers of the output side by kernel symbol.
    out_objs: HashMap<Symbol, usize>,
    /// Kernel timetags of the program's own WMEs seen at the last output phase.
    own_tags: std::collections::HashSet<u64>,
    /// Changes made since the last commit (for `IsCommitRequired`).
    pub uncommitted: bool,
    /// How many queued changes were committed (they count when auto-commit is off).
    pub committed: usize,
    /// Whether the last output phase changed the output-link.
    pub output_changed: bool,
    /// A run started and has not changed the output-link yet.
    pub new_run: bool,
}

impl Mirror {
    /// A copy holding only the input-link, whose WME has client timetag `timetag`.
    pub fn new(timetag: i64) -> Self {
        let mut m = Mirror {
            objs: Vec::new(),
            wmes: Vec::new(),
            queue: Vec::new(),
            input_link: 0,
            output_link: None,
            out_by_tag: HashMap::new(),
            out_objs: HashMap::new(),
            own_tags: std::collections::HashSet::new(),
            uncommitted: false,
            committed: 0,
            output_changed: false,
            new_run: false,
        };
        let io = m.new_obj("I1".to_string(), None);
        let il = m.new_obj("I2".to_string(), None);
        m.input_link = m.push_wme(io, "input-link", CValue::Id(il), timetag);
        m
    }

    fn new_obj(&mut self, name: String, sym: Option<Symbol>) -> usize {
        self.objs.push(Obj {
            name,
            sym,
            children: Vec::new(),
        });
        self.objs.len() - 1
    }

    fn push_wme(&mut self, parent: usize, attr: &str, value: CValue, timetag: i64) -> usize {
        self.wmes.push(CWme {
            parent,
            attr: attr.to_string(),
            value,
            timetag,
            handle: None,
            alive: true,
            just_added: true,
        });
        let k = self.wmes.len() - 1;
        self.objs[parent].children.push(k);
        k
    }

    /// The identifier a WME's value names, if it is one.
    pub fn value_obj(&self, w: usize) -> Option<usize> {
        match self.wmes[w].value {
            CValue::Id(o) => Some(o),
            _ => None,
        }
    }

    /// Adds a WME the program made; `value` may be [`CValue::Id`] of an existing identifier
    /// (a shared identifier). A new identifier is made with [`Mirror::add_object`].
    pub fn add(&mut self, parent: usize, attr: &str, value: CValue, timetag: i64) -> usize {
        let w = self.push_wme(parent, attr, value, timetag);
        self.queue.push(Op::Add(w));
        self.uncommitted = true;
        w
    }

    /// Adds a WME whose value is a new identifier named `name`.
    pub fn add_object(&mut self, parent: usize, attr: &str, name: String, timetag: i64) -> usize {
        let o = self.new_obj(name, None);
        self.add(parent, attr, CValue::Id(o), timetag)
    }

    /// Gives a WME of the program's a new value (and a new timetag, as SML does).
    pub fn update(&mut self, w: usize, value: CValue, timetag: i64) {
        let wme = &mut self.wmes[w];
        wme.value = value;
        wme.timetag = timetag;
        self.queue.push(Op::Update(w));
        self.uncommitted = true;
    }

    /// Destroys a WME and, with it, the WMEs below an identifier it held that nothing else
    /// holds.
    pub fn destroy(&mut self, w: usize) {
        self.queue.push(Op::Remove(w));
        self.uncommitted = true;
        self.forget(w);
    }

    /// Marks a WME and what hangs below it gone, in the copy only.
    fn forget(&mut self, w: usize) {
        if !self.wmes[w].alive {
            return;
        }
        self.wmes[w].alive = false;
        let parent = self.wmes[w].parent;
        self.objs[parent].children.retain(|&c| c != w);
        if let Some(o) = self.value_obj(w) {
            let held = self
                .wmes
                .iter()
                .any(|x| x.alive && x.value == CValue::Id(o));
            if !held {
                for c in std::mem::take(&mut self.objs[o].children) {
                    self.forget(c);
                }
            }
        }
    }

    /// The WMEs of identifier `o` with attribute `attr`.
    pub fn find<'a>(&'a self, o: usize, attr: &'a str) -> impl Iterator<Item = usize> + 'a {
        self.objs[o]
            .children
            .iter()
            .copied()
            .filter(move |&c| self.wmes[c].attr == attr)
    }

    /// A WME's value as SML's `GetValueAsString` gives it.
    pub fn value_text(&self, w: usize) -> String {
        match &self.wmes[w].value {
            CValue::Int(i) => i.to_string(),
            CValue::Float(f) => float_text(*f),
            CValue::Str(s) => s.clone(),
            CValue::Id(o) => self.objs[*o].name.clone(),
        }
    }

    /// The output-link's identifier-valued WMEs that came with the last output that changed
    /// the output-link: the commands, as SML's client counts them.
    pub fn commands(&self) -> Vec<usize> {
        let Some(ol) = self.output_link.and_then(|w| self.value_obj(w)) else {
            return Vec::new();
        };
        self.objs[ol]
            .children
            .iter()
            .copied()
            .filter(|&c| self.value_obj(c).is_some() && self.wmes[c].just_added)
            .collect()
    }

    /// Brings the output side up to date with `seen`, what the kernel's output-link holds
    /// now, each identifier's WMEs in the kernel's order, at the output phase
    /// (`at_output`) or after a command. Returns the commands (WMEs on the output-link
    /// itself with identifier values) that were not there before.
    pub fn sync_output(
        &mut self,
        ol: Symbol,
        ol_name: &str,
        seen: &[(Symbol, OutWme)],
        at_output: bool,
    ) -> Vec<usize> {
        let ol_obj = match self.out_objs.get(&ol) {
            Some(&o) => o,
            None => {
                let o = self.new_obj(String::new(), Some(ol));
                self.out_objs.insert(ol, o);
                o
            }
        };
        let mut live: HashMap<u64, ()> = HashMap::new();
        let mut new_cmds = Vec::new();
        // SML's client starts a new list of changes with each output that changes the
        // output-link: what came before is no longer just added.
        // SML's client keeps one list of the output-link's changes per run: the first change
        // a run brings starts it again. The program's own WMEs (a command's `^status`) count
        // once the kernel has them (checked on soar_sml 9.6.5).
        let own = |m: &Self, id: &Symbol, w: &OutWme| {
            m.out_objs
                .get(id)
                .is_some_and(|&p| m.is_own(p, &w.attr, &w.value))
        };
        let mut own_now = std::collections::HashSet::new();
        let mut added = false;
        for (id, w) in seen {
            if self.out_by_tag.contains_key(&w.timetag) {
                continue;
            }
            if own(self, id, w) {
                own_now.insert(w.timetag);
                added |= !self.own_tags.contains(&w.timetag);
            } else {
                added = true;
            }
        }
        let kept = seen
            .iter()
            .filter(|(_, w)| self.out_by_tag.contains_key(&w.timetag))
            .count();
        let changed = added || kept != self.out_by_tag.len();
        self.own_tags = own_now;
        self.output_changed = changed && at_output;
        let changed = changed && std::mem::take(&mut self.new_run);
        if changed {
            for &k in self.out_by_tag.values() {
                self.wmes[k].just_added = false;
            }
        }
        for (id, w) in seen {
            live.insert(w.timetag, ());
            if self.out_by_tag.contains_key(&w.timetag) {
                continue;
            }
            let Some(&parent) = self.out_objs.get(id) else {
                continue;
            };
            // A WME the program itself made (a command's `^status`) is already in the copy.
            if self.is_own(parent, &w.attr, &w.value) {
                continue;
            }
            let value = match &w.value {
                OutValue::Plain(v) => v.clone(),
                OutValue::Id(sym, name) => CValue::Id(match self.out_objs.get(sym) {
                    Some(&o) => o,
                    None => {
                        let o = self.new_obj(name.clone(), Some(*sym));
                        self.out_objs.insert(*sym, o);
                        o
                    }
                }),
            };
            let is_id = matches!(value, CValue::Id(_));
            self.wmes.push(CWme {
                parent,
                attr: w.attr.clone(),
                value,
                timetag: w.timetag as i64,
                handle: None,
                alive: true,
                just_added: true,
            });
            let k = self.wmes.len() - 1;
            // SML lists an output identifier's WMEs newest first.
            self.objs[parent].children.insert(0, k);
            self.out_by_tag.insert(w.timetag, k);
            if parent == ol_obj && is_id {
                new_cmds.push(k);
            }
        }
        let gone: Vec<u64> = self
            .out_by_tag
            .keys()
            .filter(|t| !live.contains_key(t))
            .copied()
            .collect();
        for t in gone {
            if let Some(w) = self.out_by_tag.remove(&t) {
                self.wmes[w].alive = false;
                let p = self.wmes[w].parent;
                self.objs[p].children.retain(|&c| c != w);
            }
        }
        self.objs[ol_obj].name = ol_name.to_string();
        if self.output_link.is_none() && !self.objs[ol_obj].children.is_empty() {
            let io = self.wmes[self.input_link].parent;
            self.wmes.push(CWme {
                parent: io,
                attr: "output-link".to_string(),
                value: CValue::Id(ol_obj),
                timetag: 0,
                handle: None,
                alive: true,
                just_added: true,
            });
            self.output_link = Some(self.wmes.len() - 1);
        }
        if let Some(w) = self.output_link {
            self.wmes[w].value = CValue::Id(ol_obj);
        }
        new_cmds
    }

    /// Whether the program made `(parent ^attr value)` itself.
    fn is_own(&self, parent: usize, attr: &str, value: &OutValue) -> bool {
        self.objs[parent].children.iter().any(|&c| {
            let w = &self.wmes[c];
            w.timetag < 0
                && w.attr == attr
                && match value {
                    OutValue::Plain(v) => *v == w.value,
                    OutValue::Id(s, _) => {
                        matches!(w.value, CValue::Id(o) if self.objs[o].sym == Some(*s))
                    }
                }
        })
    }
}

/// A WME on the kernel's output side, as the kernel thread reads it for the copy.
#[derive(Debug, Clone)]
pub struct OutWme {
    /// Its attribute.
    pub attr: String,
    /// Its value.
    pub value: OutValue,
    /// Its kernel timetag.
    pub timetag: u64,
}

/// An output WME's value.
#[derive(Debug, Clone)]
pub enum OutValue {
    /// A constant.
    Plain(CValue),
    /// An identifier, and its name.
    Id(Symbol, String),
}

/// A kernel value made into the copy's constant (identifiers are handled by the caller).
pub fn plain(v: &Value) -> Option<CValue> {
    match v {
        Value::Int(i) => Some(CValue::Int(*i)),
        Value::Float(f) => Some(CValue::Float(*f)),
        Value::Str(s) => Some(CValue::Str(s.clone())),
        Value::Id(_) => None,
    }
}

/// A float as SML's client prints it: the shortest text that reads back as the same
/// number, without a trailing `.0`, and with a two-digit exponent (`1e-07`).
pub fn float_text(f: f64) -> String {
    if f.is_finite() && f == f.trunc() && f.abs() < 1e15 {
        return format!("{}", f as i64);
    }
    let plain = format!("{f}");
    let exp = format!("{f:e}");
    // `{:e}` gives `1e-7`; C's `%g` style, which SML's client follows, gives `1e-07`.
    let exp = match exp.split_once('e') {
        Some((m, e)) => {
            let (sign, digits) = match e.strip_prefix('-') {
                Some(d) => ("-", d),
                None => ("+", e),
            };
            format!("{m}e{sign}{digits:0>2}")
        }
        None => exp,
    };
    let magnitude = f.abs();
    if magnitude != 0.0 && !(1e-4..1e16).contains(&magnitude) {
        exp
    } else {
        plain
    }
}
