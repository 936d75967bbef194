//! `source` (`load file`), `pushd`, `popd`, `cd`, `dirs`, `ls` (Soar manual, ch. 9, "File
//! System I/O Commands").

use super::options::{self, opt};
use super::{CmdResult, Ctx, Interpreter};
use crate::source::Diagnostic;
use std::path::{Path, PathBuf};

/// The listings a `source` asked for, which its nested files follow too.
#[derive(Debug, Default, Clone, Copy)]
pub(super) struct SourceListing {
    /// `-a`: a summary line at the end of each file.
    pub per_file: bool,
    /// `-v`: `Sourcing FILE.` as each file starts, and the excised rules listed.
    pub verbose: bool,
}

/// `N productions sourced.`, with the excised and ignored counts when not 0, as 9.6 words
/// them.
fn counts_text(added: usize, excised: usize, ignored: usize) -> String {
    let plural = |n: usize| if n == 1 { "" } else { "s" };
    let mut text = format!("{added} production{} sourced.", plural(added));
    if excised > 0 {
        text.push_str(&format!(" {excised} production{} excised.", plural(excised)));
    }
    if ignored > 0 {
        text.push_str(&format!(" {ignored} production{} ignored.", plural(ignored)));
    }
    text
}

/// `Excised productions:` and a tab-indented line per name (nothing for none).
fn excised_listing(names: &[String]) -> String {
    if names.is_empty() {
        return String::new();
    }
    let mut text = "Excised productions:\n".to_string();
    for n in names {
        text.push_str(&format!("\t{n}\n"));
    }
    text
}

/// 9.6 refuses to nest `source` deeper than this.
const MAX_SOURCE_DEPTH: usize = 100;

impl Interpreter {
    pub(super) fn resolve(&self, p: &str) -> PathBuf {
        let path = Path::new(p);
        if path.is_absolute() {
            path.to_path_buf()
        } else {
            self.cwd.join(path)
        }
    }

    pub(super) fn cmd_load(&mut self, ctx: &Ctx, args: &[String]) -> CmdResult {
        let sub = args.first().map(String::as_str);
        match sub {
            Some("file") => self.cmd_source(ctx, &args[1..]),
            // 9.6 loads a C++ SML extension here; rusoar has no SML to extend.
            Some("library") => Err(Diagnostic::error(
                "load library: rusoar cannot load C++ shared libraries (SML extensions); a program registers its functions through rusoar's Rust API instead",
            )
            .at(ctx.cmd.span)
            .with_label("not applicable to rusoar")),
            Some("rete-network") => self.load_rete_network(ctx, &args[1..]),
            Some("percepts") => self.load_percepts(ctx, &args[1..]),
            Some(_) | None => Err(Diagnostic::error(
                "Invalid load command.  Use 'load ?' to see a list of valid settings.",
            )
            .at(ctx.cmd.span)
            .with_label("the sub-commands are file, library, percepts and rete-network")),
        }
    }

    /// `source [-a] [-d] [-v] FILE`: runs the file's commands in the file's directory when
    /// the path names one, stops at the first failing command, and reports the productions
    /// sourced (Soar manual, ch. 9, `load`): `-d` drops the summary, `-a` adds one per file
    /// sourced, `-v` names each file as it starts and lists the excised rules.
    fn cmd_source(&mut self, ctx: &Ctx, args: &[String]) -> CmdResult {
        let specs = [opt('a', "all"), opt('d', "disable"), opt('v', "verbose")];
        let parsed = options::parse(args, &specs).map_err(|m| ctx.error(m))?;
        let Some(name) = parsed.args.first() else {
            return Err(ctx.error("Syntax: load file [--all | --disable | --verbose] <filename>"));
        };
        let top_level = self.source_stack.is_empty();
        if top_level {
            self.report = super::LoadReport::default();
            // Nested files list as the outermost `source` asked.
            self.source_listing = SourceListing {
                per_file: parsed.has("all"),
                verbose: parsed.has("verbose"),
            };
        }
        // A nested file's `*` marks get a line of their own: 9.6 ends the line of marks
        // before it with " \n" and its own marks with a newline.
        if !top_level && self.after_star && !self.after_at_marks {
            self.events.push(super::Event::Text(" \n".into()));
            self.after_star = false;
        }
        let result = self.source_file(ctx, name);
        // A file that could not be read gets no summary (checked on 9.6).
        if self.source_listing.per_file && result.is_ok() {
            self.per_file_summary(name);
        }
        if !top_level {
            // A line of `smem --add`'s `@` marks goes on after the file (as in 9.6).
            if self.after_star && !self.after_at_marks {
                self.events.push(super::Event::Text("\n".into()));
                self.after_star = false;
            }
            return result.map(|_| String::new());
        }
        let summary = self.total_summary();
        match result {
            Ok(()) if parsed.has("disable") => Ok(String::new()),
            Ok(()) => Ok(summary),
            Err(d) => Err(d.with_note(summary)),
        }
    }

    /// `source -a`: at the end of each file, the rules added and excised since the last
    /// such line (9.6 counts from there, not from the file's start), the excised rules'
    /// names with `-v`, then the line of `*` marks ends.
    fn per_file_summary(&mut self, name: &str) {
        let r = &mut self.report;
        let added = std::mem::take(&mut r.added_since_summary);
        let excised = std::mem::take(&mut r.excised_since_summary);
        let path = self.cwd_path_of_source(name);
        let mut text = format!("{}: {}\n", path, counts_text(added, excised.len(), 0));
        if self.source_listing.verbose {
            text.push_str(&excised_listing(&excised));
        }
        if self.after_star {
            text.push('\n');
            self.after_star = false;
        }
        self.events.push(super::Event::Text(text));
    }

    /// The path `source -a` names a file by: absolute, as 9.6 prints it.
    fn cwd_path_of_source(&self, name: &str) -> String {
        if crate::stdlib::lookup(name).is_some() {
            return name.to_string();
        }
        self.last_sourced
            .as_ref()
            .map_or_else(|| name.to_string(), |p| p.display().to_string())
    }

    /// The outermost `source`'s result: `Total: ...`, with `-v` the excised rules.
    fn total_summary(&self) -> String {
        let r = &self.report;
        let mut summary = format!(
            "Total: {}",
            counts_text(r.added, r.excised, r.ignored)
        );
        if self.source_listing.verbose && !r.excised_names.is_empty() {
            summary.push('\n');
            summary.push_str(excised_listing(&r.excised_names).trim_end_matches('\n'));
        }
        summary
    }

    fn source_file(&mut self, ctx: &Ctx, name: &str) -> Result<(), Diagnostic> {
        if self.source_stack.len() >= MAX_SOURCE_DEPTH {
            return Err(ctx.error(format!(
                "source: nested more than {MAX_SOURCE_DEPTH} files deep"
            )));
        }
        // `<stdlib>/NAME`: the default rules embedded in the binary.
        if let Some(text) = crate::stdlib::lookup(name) {
            let file = self.sources.add(name.to_string(), text.to_string());
            let path = std::path::PathBuf::from(name);
            self.source_stack.push(path.clone());
            self.report.per_file.entry(path).or_insert(0);
            let result = self.run_file_id_at(file).map_err(|(d, _)| d);
            self.source_stack.pop();
            return result;
        }
        let path = self.resolve(name);
        let shown = path.display().to_string();
        let file = self.sources.read_file(shown, &path).map_err(|e| {
            Diagnostic::error(format!("Failed to open file for reading: {name}"))
                .at(ctx.arg_span(0))
                .with_label(format!("{e}"))
                .with_note(format!("looked for {}", path.display()))
        })?;
        // `source dir/f` runs in `dir`, as in 9.6: push it now, pop it afterwards, even on
        // error.
        let changes_dir = name.contains('/');
        if changes_dir {
            let dir = path
                .parent()
                .map(Path::to_path_buf)
                .unwrap_or_else(|| self.cwd.clone());
            self.dir_stack.push(std::mem::replace(&mut self.cwd, dir));
        }
        if self.source_listing.verbose {
            let base = path.file_name().map_or_else(
                || name.to_string(),
                |b| b.to_string_lossy().into_owned(),
            );
            self.events
                .push(super::Event::Text(format!("Sourcing {base}.\n")));
        }
        self.source_stack.push(path.clone());
        self.report.per_file.entry(path.clone()).or_insert(0);
        // An error in a nested file names each enclosing file and the line of its `source`
        // command, as Soar's "\t<path>:<line>" trail does.
        let result = self.run_file_id_at(file).map_err(|(d, at)| {
            if d.span.is_some_and(|s| s.file == file) {
                d
            } else {
                let (line, _) = self.sources.line_col(at.file, at.start);
                d.with_note(format!("while sourcing {}:{}", path.display(), line))
            }
        });
        self.source_stack.pop();
        self.last_sourced = Some(path);
        if changes_dir {
            if let Some(prev) = self.dir_stack.pop() {
                self.cwd = prev;
            }
        }
        result
    }

    pub(super) fn cmd_pushd(&mut self, ctx: &Ctx, args: &[String]) -> CmdResult {
        let Some(d) = args.first() else {
            return Err(ctx.error("pushd: expected a directory"));
        };
        let dir = self.resolve(d);
        if !dir.is_dir() {
            return Err(Diagnostic::error(format!("Error changing to {d}"))
                .at(ctx.arg_span(0))
                .with_label("no such directory")
                .with_note(format!("looked for {}", dir.display())));
        }
        let dir = dir.canonicalize().unwrap_or(dir);
        self.dir_stack.push(std::mem::replace(&mut self.cwd, dir));
        Ok(String::new())
    }

    pub(super) fn cmd_popd(&mut self, ctx: &Ctx) -> CmdResult {
        match self.dir_stack.pop() {
            Some(d) => {
                self.cwd = d;
                Ok(String::new())
            }
            None => Err(ctx.error("Directory stack is empty.")),
        }
    }

    pub(super) fn cmd_cd(&mut self, ctx: &Ctx, args: &[String]) -> CmdResult {
        let dir = match args.first() {
            None => self.home.clone(),
            Some(d) => self.resolve(d),
        };
        if !dir.is_dir() {
            return Err(Diagnostic::error(format!(
                "Error changing to {}",
                args.first().map(String::as_str).unwrap_or("")
            ))
            .at(ctx.arg_span(0))
            .with_label("no such directory"));
        }
        self.cwd = dir.canonicalize().unwrap_or(dir);
        Ok(String::new())
    }

    pub(super) fn cmd_dirs(&self) -> String {
        let mut s = self.cwd.display().to_string();
        for d in self.dir_stack.iter().rev() {
            s.push(' ');
            s.push_str(&d.display().to_string());
        }
        s
    }

    /// `ls`: the working directory's entries. 9.6 takes no argument (`ls DIR` is its
    /// "Syntax: ls" error, checked on soar-sml 9.6.5).
    pub(super) fn cmd_ls(&self, ctx: &Ctx) -> CmdResult {
        if ctx.cmd.words.len() > 1 {
            return Err(Diagnostic::error("Syntax: ls")
                .at(ctx.arg_span(0))
                .with_label("ls lists the working directory; `cd` there first"));
        }
        let mut names: Vec<String> = std::fs::read_dir(&self.cwd)
            .map_err(|e| ctx.error(format!("ls: {e}")))?
            .filter_map(|e| e.ok())
            .map(|e| e.file_name().to_string_lossy().into_owned())
            .collect();
        names.sort();
        Ok(names.join("\n"))
    }
}
