//! `output` (Soar manual, ch. 9, `output`): where the print stream goes (enabled, the
//! callbacks, a log file, one command's text to a file), what the agent may print (`write`,
//! the `log` channels, warnings) and `print`'s default depth, with the official kernel's
//! texts (soar-sml 9.6.5).

use super::{CmdResult, Ctx, Interpreter};
use crate::source::Diagnostic;
use std::io::Write;

/// 9.6's message for a bad on/off value.
const OUTPUT_INVALID: &str =
    "Invalid argument for output command. Use 'output ?' to see a list of valid sub-commands.";
/// 9.6's second line under a misused `log` or `command-to-file`.
const OUTPUT_HELP: &str = "Use 'output ?' and 'help output' to learn more about the output command.";

/// An open `output log` file.
#[derive(Debug)]
pub(crate) struct OutputLog {
    file: std::fs::File,
}

impl Interpreter {
    pub(super) fn cmd_output(&mut self, ctx: &Ctx, args: &[String]) -> CmdResult {
        let Some(sub) = args.first().map(String::as_str) else {
            return Ok(output_status(&self.agent.settings));
        };
        let value = args.get(1).map(String::as_str);
        let s = &mut self.agent.settings;
        match sub {
            "?" => Ok(output_usage(s)),
            "enabled" => on_off(ctx, "enabled", &mut s.output_enabled, value),
            "console" => on_off(ctx, "console", &mut s.output_console, value),
            "callbacks" => on_off(ctx, "callbacks", &mut s.output_callbacks, value),
            "echo-commands" => on_off(ctx, "echo-commands", &mut s.echo_commands, value),
            "warnings" => on_off(ctx, "warnings", &mut s.warnings, value),
            "agent-writes" => on_off(ctx, "agent-writes", &mut s.agent_writes, value),
            "agent-logs" => {
                let channel = match args.get(1) {
                    None => return Ok(log_channels_line(s.log_channels_off)),
                    Some(c) => c.parse::<u32>().ok().filter(|c| (1..=100).contains(c)),
                };
                let channel = channel.ok_or_else(|| {
                    ctx.error("Agent trace channel must be an integer between 1 and 100.")
                })?;
                let bit = 1u128 << channel;
                match args.get(2).map(String::as_str) {
                    Some("on") => s.log_channels_off &= !bit,
                    Some("off") => s.log_channels_off |= bit,
                    Some(_) => {
                        return Err(ctx.error(
                            "Agent trace channel setting must be 'on' or 'off'. Use 'output ?' to see a list of valid sub-commands.",
                        ))
                    }
                    None => {
                        return Err(
                            ctx.error("Wrong number of arguments to output agent-trace command.")
                        )
                    }
                }
                Ok(String::new())
            }
            "print-depth" => match value {
                None => Ok(format!("print-depth is {}\n", s.print_depth)),
                Some(v) => match v.parse::<usize>() {
                    Ok(n) if n > 0 => {
                        s.print_depth = n;
                        Ok(format!("print-depth is now {n}\n"))
                    }
                    _ => Err(ctx.error("Invalid value for print-depth.")),
                },
            },
            "log" => self.output_log(ctx, &args[1..]),
            "command-to-file" => self.command_to_file(ctx, &args[1..]),
            _ => Err(ctx.error(
                "Invalid output sub-command.  Use 'output ?' to see a list of valid sub-commands and settings.",
            )),
        }
    }

    /// `output log [-A|--append] FILE`, `--add TEXT`, `--close`: a copy of the session's
    /// commands and what they printed.
    fn output_log(&mut self, ctx: &Ctx, args: &[String]) -> CmdResult {
        let (append, rest) = match args.first().map(String::as_str) {
            Some("-A" | "--append" | "-a") => (true, &args[1..]),
            _ => (false, args),
        };
        match rest.first().map(String::as_str) {
            // 9.6 answers this way whether or not a log is open.
            None if !append => Ok("log is on\n".into()),
            Some("--close" | "-c") => match self.log.take() {
                Some(_) => Ok("Log file closed.\n".into()),
                None => Err(ctx
                    .error("Log is not open.")
                    .with_note(OUTPUT_HELP)),
            },
            Some("--add") => {
                let text = rest[1..].join(" ");
                if text.is_empty() {
                    return Err(ctx.error("Provide a string to add.").with_note(OUTPUT_HELP));
                }
                if let Some(log) = self.log.as_mut() {
                    let _ = writeln!(log.file, "{text}");
                }
                Ok(String::new())
            }
            Some(name) => {
                let path = self.resolve(name);
                let file = std::fs::OpenOptions::new()
                    .create(true)
                    .write(true)
                    .append(append)
                    .truncate(!append)
                    .open(&path)
                    .map_err(|e| {
                        // `args` follow `log`: the file name is the command's last word.
                        Diagnostic::error(format!("Failed to open log file {name}: {e}"))
                            .at(ctx.arg_span(args.len()))
                    })?;
                let opened = format!("Log file '{name}' open.\n");
                let mut log = OutputLog { file };
                let _ = log.file.write_all(opened.as_bytes());
                self.log = Some(log);
                Ok(opened)
            }
            None => Err(ctx.error("Syntax: output log [-A] <filename>").with_note(OUTPUT_HELP)),
        }
    }

    /// `output command-to-file [-a] FILE COMMAND ARGS...`: runs the command and writes
    /// what it printed to the file instead of the print stream.
    fn command_to_file(&mut self, ctx: &Ctx, args: &[String]) -> CmdResult {
        let (append, rest) = match args.first().map(String::as_str) {
            Some("-a" | "--append") => (true, &args[1..]),
            _ => (false, args),
        };
        if args.is_empty() {
            return Ok("command-to-file is on\n".into());
        }
        let [name, command @ ..] = rest else {
            return Err(self.ctf_syntax(ctx));
        };
        if command.is_empty() {
            return Err(self.ctf_syntax(ctx));
        }
        let path = self.resolve(name);
        let mut file = std::fs::OpenOptions::new()
            .create(true)
            .write(true)
            .append(append)
            .truncate(!append)
            .open(&path)
            .map_err(|e| ctx.error(format!("Failed to open file {name}: {e}")))?;
        let line = command
            .iter()
            .map(|w| quote_word(w))
            .collect::<Vec<_>>()
            .join(" ");
        let start = self.events.len();
        let result = self.run_text("command-to-file", &line);
        let events: Vec<_> = self.events.drain(start..).collect();
        let text = self.render_all(&events);
        let _ = file.write_all(text.as_bytes());
        let _ = file.write_all(b"\n");
        result.map(|()| String::new())
    }

    fn ctf_syntax(&self, ctx: &Ctx) -> Diagnostic {
        ctx.error("Syntax: output command-to-file [-a] <filename> command [args]")
            .with_note(OUTPUT_HELP)
    }

    /// Copies a top-level command and what it printed to the open log, as 9.6 writes it.
    pub(super) fn log_command(&mut self, command: &str, printed: &str) {
        if let Some(log) = self.log.as_mut() {
            let _ = write!(log.file, "soar> {command}\n{printed}\n");
            if !printed.is_empty() && !printed.ends_with('\n') {
                let _ = log.file.write_all(b"\n");
            }
        }
    }
}

/// A word as the tokenizer reads it back: braced when it holds spaces.
fn quote_word(w: &str) -> String {
    if w.is_empty() || w.contains(char::is_whitespace) {
        format!("{{{w}}}")
    } else {
        w.to_string()
    }
}

/// A setting 9.6 reports as `NAME is on` and sets with `NAME is now off`.
fn on_off(ctx: &Ctx, name: &str, slot: &mut bool, value: Option<&str>) -> CmdResult {
    let word = |b: bool| if b { "on" } else { "off" };
    match value {
        None => Ok(format!("{name} is {}\n", word(*slot))),
        Some("on") => {
            *slot = true;
            Ok(format!("{name} is now on\n"))
        }
        Some("off") => {
            *slot = false;
            Ok(format!("{name} is now off\n"))
        }
        Some(_) => Err(ctx.error(OUTPUT_INVALID)),
    }
}

/// `All agent log channels enabled.`, or the ones that are not.
fn log_channels_line(off: u128) -> String {
    if off == 0 {
        return "All agent log channels enabled.\n".into();
    }
    let list: Vec<String> = (1..=100u32)
        .filter(|c| off & (1u128 << c) != 0)
        .map(|c| c.to_string())
        .collect();
    format!("All agent log channels enabled except {}.\n", list.join(", "))
}

fn word(b: bool) -> &'static str {
    if b {
        "on"
    } else {
        "off"
    }
}

/// `output` with no arguments.
fn output_status(s: &crate::agent::Settings) -> String {
    let rule = "=".repeat(55);
    let line = "-".repeat(55);
    let enabled = if s.output_enabled { "Yes" } else { "No" };
    format!(
        "{rule}\n-                   Output Status                     -\n{rule}\n\
         Printing enabled {enabled:>38}   \n{line}\n\
         Agent RHS write output {:>32}   \n{}{line}\n\
         Warnings {:>46}   \n{line}\n\n\
         To enable specific types of trace messages, use the 'trace' command.\n\
         Use 'output ?' for a command overview or 'help output' for the manual page.",
        word(s.agent_writes),
        log_channels_line(s.log_channels_off),
        word(s.warnings),
    )
}

/// `output ?`: the sub-commands, with the current values.
fn output_usage(s: &crate::agent::Settings) -> String {
    let rule = "=".repeat(55);
    let line = "-".repeat(55);
    let row = |left: &str, value: &str, what: &str| format!("{left:<50}{value:>5}   {what}\n");
    let mut out = format!(
        "{rule}\n-           Output Sub-Commands and Options           -\n{rule}\noutput ?                                                  \n{line}\n"
    );
    out += &row("output enabled", word(s.output_enabled), "Globally turn off all output");
    out += &row("output console", word(s.output_console), "Send output to std::out for debugging");
    out += &row(
        "output callbacks",
        word(s.output_callbacks),
        "Send output to standard agent print callback",
    );
    out += &format!("{line}\n");
    out += "output agent-logs           <channel-number> [on | off]   Controls whether agent trace channel prints\n";
    out += &row(
        "output agent-writes",
        word(s.agent_writes),
        "Print output from RHS (write) function",
    );
    out += &format!("{line}\n");
    out += "output log                   [--append | -A] <filename>   Log all output to file\n";
    out += "output log                               --add <string>   \n";
    out += "output log                                    [--close]   \n";
    out += &format!("{line}\n");
    out += "output command-to-file         [-a] <file> <cmd> [args]   Log execution of single command\n";
    out += &format!("{line}\n");
    out += &row(
        "output echo-commands",
        word(s.echo_commands),
        "Echo commands to debugger",
    );
    out += &row(
        "output print-depth",
        &s.print_depth.to_string(),
        "Default print depth for 'print'",
    );
    out += &row("output warnings", word(s.warnings), "Print all warnings");
    out += &format!(
        "{line}\n\nTo view/change a setting:                                 output <setting> [<value>]\nFor a detailed explanation of these settings:             help output\n"
    );
    out
}
