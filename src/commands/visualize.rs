//! `visualize` (Soar manual, ch. 9, `visualize`): working memory, semantic memory or one
//! episode written as a Graphviz file, then, as the settings ask, drawn by `dot`, opened in
//! a viewer or an editor, or printed. The settings, their listing and the messages are
//! soar-sml 9.6.5's. The explainer's graphs (`identity_graph`, `ebc_analysis`) need the
//! explainer, which rusoar does not have.

use super::on_off;
use super::visualize_graph::{graph_text, smem_objects, wm_objects, MemoryFormat, WmView};
use super::prefs_support::Origin;
use super::{CmdResult, Ctx, Interpreter};
use crate::wm::{Wme, WmeId};
use crate::source::Diagnostic;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};

/// The settings `visualize ?` lists.
#[derive(Debug, Clone)]
pub struct VizSettings {
    rule_format_full: bool,
    memory_format: MemoryFormat,
    line_style: String,
    separate_states: bool,
    architectural_wmes: bool,
    color_identities: bool,
    use_joined_identities: bool,
    file_name: String,
    use_same_file: bool,
    generate_image: bool,
    image_type: String,
    viewer_launch: bool,
    editor_launch: bool,
    print_debug: bool,
    /// The number the last new file took (`soar_viz1.gv`, `soar_viz2.gv`, ...).
    last_file_number: u32,
}

impl Default for VizSettings {
    fn default() -> Self {
        VizSettings {
            rule_format_full: true,
            memory_format: MemoryFormat::Record,
            line_style: "polyline".into(),
            separate_states: true,
            architectural_wmes: false,
            color_identities: false,
            use_joined_identities: true,
            file_name: "soar_viz".into(),
            use_same_file: false,
            generate_image: true,
            image_type: "svg".into(),
            viewer_launch: true,
            editor_launch: false,
            print_debug: false,
            last_file_number: 0,
        }
    }
}

/// The sub-commands and settings, by the names 9.6 matches a word's prefix against.
const NAMES: [&str; 21] = [
    "architectural-wmes",
    "color-identities",
    "ebc_analysis",
    "editor-launch",
    "epmem",
    "file-name",
    "generate-image",
    "identity_graph",
    "image-type",
    "instantiations",
    "last-item-printed",
    "line-style",
    "memory-format",
    "print",
    "rule-format",
    "separate_states",
    "smem",
    "use-joined-identities",
    "use-same-file",
    "viewer-launch",
    "wm",
];

const SUMMARY: &str = "Visualize creates graphical representations of Soar's memory systems and past learning events.\n\nUse 'visualize ?' and 'help visualize' to learn more about the visualize command.\n";
const BAD_VALUE: &str =
    "Invalid argument for visualize command. Use 'visualize ?' to see a list of valid sub-commands.";
const NO_CHUNK: &str = "Please first specify the chunk you want to visualize with the command 'explain [chunk-name]' or 'explain chunk [chunk ID]'.";
const EPMEM_TITLE: &str = "========================================\n    Visualization of Episodic Memory    \n========================================\n";

/// The word's sub-command or setting: an exact name, or the prefix of just one. The
/// listing's spellings `separate-states` and `print-debug` are taken too (9.6 refuses them).
fn resolve(word: &str) -> Result<&'static str, Vec<&'static str>> {
    match word {
        "separate-states" => return Ok("separate_states"),
        "print-debug" => return Ok("print"),
        _ => {}
    }
    super::resolve_prefix(&NAMES, word)
}

impl Interpreter {
    pub(super) fn cmd_visualize(&mut self, ctx: &Ctx, args: &[String]) -> CmdResult {
        let Some(first) = args.first() else {
            return Ok(SUMMARY.into());
        };
        if args.len() > 3 {
            return Err(ctx.error("Too many arguments for the 'visualize' command."));
        }
        if first == "?" {
            return Ok(listing(&self.viz));
        }
        let name = resolve(first).map_err(|candidates| {
            let d = Diagnostic::error(
                "Invalid visualize sub-command.  Use 'soar ?' to see a list of valid sub-commands and settings.",
            )
            .at(ctx.arg_span(0))
            .with_label("not a sub-command or setting");
            if candidates.is_empty() {
                d.with_note("`visualize ?` lists them")
            } else {
                d.with_note(format!("did you mean: {}", candidates.join(", ")))
            }
        })?;
        let rest = &args[1..];
        match name {
            "wm" => self.visualize_wm(ctx, rest),
            "smem" => self.visualize_smem(ctx, rest),
            "epmem" => self.visualize_epmem(ctx, rest),
            "identity_graph" | "ebc_analysis" | "instantiations" | "last-item-printed" => Err(ctx
                .error(NO_CHUNK)
                .with_note("rusoar has no explainer yet, so no chunk can be chosen for it")),
            setting => self.visualize_setting(ctx, setting, rest.first().map(String::as_str)),
        }
    }

    /// `visualize SETTING [VALUE]`: shows or sets one setting.
    fn visualize_setting(&mut self, ctx: &Ctx, name: &str, value: Option<&str>) -> CmdResult {
        let v = &mut self.viz;
        let Some(value) = value else {
            let now = match name {
                "rule-format" => (if v.rule_format_full { "full" } else { "name" }).to_string(),
                "memory-format" => format_word(v.memory_format).to_string(),
                "line-style" => v.line_style.clone(),
                "file-name" => v.file_name.clone(),
                "image-type" => v.image_type.clone(),
                _ => on_off(*switch(v, name)).to_string(),
            };
            return Ok(format!("{name} is {now}"));
        };
        let bad = || {
            Diagnostic::error(BAD_VALUE)
                .at(ctx.arg_span(1))
                .with_label("not a value of this setting")
        };
        match name {
            "rule-format" => {
                v.rule_format_full = match value {
                    "full" => true,
                    "name" => false,
                    _ => return Err(bad().with_note("rule-format is `name` or `full`")),
                }
            }
            "memory-format" => {
                v.memory_format = match value {
                    "node" => MemoryFormat::Node,
                    "record" => MemoryFormat::Record,
                    _ => return Err(bad().with_note("memory-format is `node` or `record`")),
                }
            }
            "line-style" => v.line_style = value.to_string(),
            "file-name" => v.file_name = value.to_string(),
            "image-type" => v.image_type = value.to_string(),
            _ => {
                *switch(v, name) = match value {
                    "on" => true,
                    "off" => false,
                    _ => return Err(bad().with_note("this setting is `on` or `off`")),
                }
            }
        }
        Ok(format!("{name} is now {value}"))
    }

    /// `visualize wm [ID [DEPTH]]`: all of working memory, or an identifier's objects to
    /// DEPTH levels (1: the object alone).
    fn visualize_wm(&mut self, ctx: &Ctx, args: &[String]) -> CmdResult {
        let root = match args.first() {
            None => None,
            Some(word) => Some(self.agent.live_id(word).ok_or_else(|| {
                Diagnostic::error("Invalid identifier specified to visualize")
                    .at(ctx.arg_span(1))
                    .with_label("no identifier of this name in working memory")
            })?),
        };
        let depth = self.depth_arg(ctx, args.get(1), 2)?;
        // Without `architectural-wmes`, what rules, decisions and the memories' retrievals
        // made: 9.6 leaves out the WMEs that no preference holds (a state's links, its
        // impasse's WMEs but `^item` and `^non-numeric`, input).
        let all = self.viz.architectural_wmes;
        let shown = |w: WmeId, wme: &Wme| {
            all || matches!(
                self.origin_of(w, wme),
                Origin::Preference | Origin::ArchWithPreference
            ) || self.agent.epmem.made(w).is_some()
        };
        let view = WmView {
            root,
            depth,
            shown: &shown,
            separate_states: self.viz.separate_states,
        };
        let objects = wm_objects(&self.agent, &view);
        let text = graph_text(&objects, self.viz.memory_format, &self.viz.line_style);
        self.visualization(ctx, "", &text)
    }

    /// `visualize smem [LTI [DEPTH]]`: every long-term identifier, or one (`@N` or `N`)
    /// with its objects to DEPTH levels. Always as records, as in 9.6.
    fn visualize_smem(&mut self, ctx: &Ctx, args: &[String]) -> CmdResult {
        let db = |e: String| ctx.error(e);
        let root = match args.first() {
            None => None,
            Some(word) => {
                let n = word.strip_prefix('@').unwrap_or(word).parse::<i64>().ok();
                let exists = match n {
                    Some(n) => self.agent.smem.store().map_err(db)?.lti_exists(n).map_err(db)?,
                    None => false,
                };
                if !exists {
                    return Err(Diagnostic::error("Invalid long-term identifier for visualize command.")
                        .at(ctx.arg_span(1))
                        .with_label("no long-term identifier of this number"));
                }
                n
            }
        };
        let depth = self.depth_arg(ctx, args.get(1), 2)?;
        let store = self.agent.smem.store().map_err(db)?;
        let objects = smem_objects(store, root, depth).map_err(db)?;
        let text = graph_text(&objects, MemoryFormat::Record, &self.viz.line_style);
        self.visualization(ctx, "", &text)
    }

    /// `visualize epmem EPISODE`: the episode as `epmem --viz` writes it.
    fn visualize_epmem(&mut self, ctx: &Ctx, args: &[String]) -> CmdResult {
        let Some(t) = args.first().and_then(|w| w.parse::<i64>().ok()) else {
            return Err(ctx.error("Please specify a valid episode id."));
        };
        let text = match self.agent.epmem.store() {
            Some(store) if store.valid(t) => store.visualize_episode(t),
            _ => {
                return Err(ctx
                    .error("Visualization produced nothing.")
                    .with_note(format!("episode {t} is not in episodic memory")));
            }
        };
        self.visualization(ctx, EPMEM_TITLE, &text)
    }

    /// A depth argument (word `i` of the command): a whole number of at least 1, or 1.
    fn depth_arg(&self, ctx: &Ctx, word: Option<&String>, i: usize) -> Result<usize, Diagnostic> {
        match word {
            None => Ok(1),
            Some(w) => w.parse::<usize>().ok().filter(|&d| d >= 1).ok_or_else(|| {
                Diagnostic::error("Invalid depth specified to visualize")
                    .at(ctx.arg_span(i))
                    .with_label("a depth is a whole number of at least 1")
            }),
        }
    }

    /// Writes `text` to the next file, draws and opens it as the settings ask, and
    /// answers `title`, 9.6's line, and with `print-debug` the file's text.
    fn visualization(&mut self, ctx: &Ctx, title: &str, text: &str) -> CmdResult {
        let path = self.next_viz_file();
        std::fs::write(&path, text).map_err(|e| {
            ctx.error(format!(
                "Could not write the visualization to {}: {e}",
                path.display()
            ))
        })?;
        let v = &self.viz;
        if v.generate_image || v.viewer_launch {
            let image = path.with_extension(&v.image_type);
            let drawn = Command::new("dot")
                .arg(format!("-T{}", v.image_type))
                .arg(&path)
                .arg("-o")
                .arg(&image)
                .stdout(Stdio::null())
                .stderr(Stdio::null())
                .status()
                .is_ok_and(|s| s.success());
            if !drawn {
                return Err(ctx
                    .error("Could not generate visualization image because `dot` command failed. Do you have GraphViz installed?!")
                    .with_note(format!(
                        "the graph is in {}; turn `generate-image` and `viewer-launch` off to write only that file",
                        path.display()
                    )));
            }
            if v.viewer_launch {
                open_in_desktop(&image);
            }
        }
        if v.editor_launch {
            open_in_desktop(&path);
        }
        let mut out = format!("{title}Generating visualization...\n");
        if v.print_debug {
            out.push_str(text);
            out.push('\n');
        }
        Ok(out)
    }

    /// `FILE-NAME.gv` with `use-same-file`, else `FILE-NAMEN.gv` for the next N whose file
    /// does not exist yet; relative to the current directory (`cd`).
    fn next_viz_file(&mut self) -> PathBuf {
        let v = &mut self.viz;
        if v.use_same_file {
            return self.cwd.join(format!("{}.gv", v.file_name));
        }
        loop {
            v.last_file_number += 1;
            let path = self
                .cwd
                .join(format!("{}{}.gv", v.file_name, v.last_file_number));
            if !path.exists() {
                return path;
            }
        }
    }
}

/// Opens a file with the desktop's program for it, without waiting for it to close.
fn open_in_desktop(path: &Path) {
    let opener = if cfg!(target_os = "macos") {
        "open"
    } else {
        "xdg-open"
    };
    let child = Command::new(opener)
        .arg(path)
        .stdin(Stdio::null())
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .spawn();
    if let Ok(mut child) = child {
        // Reaped in the background, so no finished viewer lingers as a zombie.
        std::thread::spawn(move || child.wait());
    }
}

fn switch<'a>(v: &'a mut VizSettings, name: &str) -> &'a mut bool {
    match name {
        "separate_states" => &mut v.separate_states,
        "architectural-wmes" => &mut v.architectural_wmes,
        "color-identities" => &mut v.color_identities,
        "use-joined-identities" => &mut v.use_joined_identities,
        "use-same-file" => &mut v.use_same_file,
        "generate-image" => &mut v.generate_image,
        "viewer-launch" => &mut v.viewer_launch,
        "editor-launch" => &mut v.editor_launch,
        _ => &mut v.print_debug,
    }
}


fn format_word(f: MemoryFormat) -> &'static str {
    match f {
        MemoryFormat::Node => "node",
        MemoryFormat::Record => "record",
    }
}

/// `visualize ?`: 9.6's listing, each choice with the current one in capitals.
fn listing(v: &VizSettings) -> String {
    let line = |name: &str, value: &str, what: &str| {
        format!("{name}{value:>w$}   {what}\n", w = 51usize.saturating_sub(name.len()))
    };
    let pick = |a: &str, b: &str, first: bool, close: &str| {
        if first {
            format!("[ {} | {b}{close}]", a.to_uppercase())
        } else {
            format!("[ {a} | {}{close}]", b.to_uppercase())
        }
    };
    let switch_line = |name: &str, on: bool, what: &str| line(name, &pick("on", "off", on, " "), what);
    let mut s = String::from("======= Visualization Commands and Settings =======\n");
    s += "visualize ?                                           Print this help listing\n";
    s += "visualize [wm | smem | epmem] [id] [depth]            Visualize contents of memory system\n";
    s += "visualize [ identity_graph | ebc_analysis]            Visualize EBC explainer analysis\n";
    s += "------------------ Presentation -------------------\n";
    s += &line(
        "rule-format",
        &pick("name", "full", !v.rule_format_full, ""),
        "Print all conditions and actions or just the rule name",
    );
    s += &line(
        "memory-format",
        &pick("node", "record", v.memory_format == MemoryFormat::Node, ""),
        "Print memories as records or just simple nodes",
    );
    s += &line("line-style", &v.line_style, "GraphViz line style that will be used");
    s += &switch_line("separate-states", v.separate_states, "Create links between different goal states");
    s += &switch_line("architectural-wmes", v.architectural_wmes, "Include WMEs created by the Soar architecture");
    s += &switch_line("color-identities", v.color_identities, "Color identities differently");
    s += &switch_line("use-joined-identities", v.use_joined_identities, "Color using final joined identities");
    s += "------------------ File Handling ------------------\n";
    s += &line("file-name", &v.file_name, "");
    s += &switch_line("use-same-file", v.use_same_file, "Whether to create new files each time");
    s += &switch_line("generate-image", v.generate_image, "Whether an image should be created");
    s += &line("image-type", &v.image_type, "Image type that will be generated");
    s += "------------------ Post Actions -------------------\n";
    s += &switch_line("viewer-launch", v.viewer_launch, "Launch image in viewer");
    s += &switch_line("editor-launch", v.editor_launch, "Open data file in editor");
    s += &switch_line("print-debug", v.print_debug, "Print data file to screen for debugging");
    s += "\nTo change a setting:                                  visualize <setting> [<value>]\n";
    s += "For a detailed explanation of these settings:         help visualize\n";
    s
}
