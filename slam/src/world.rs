//! World descriptions: wall segments, the robot's start pose and the run's settings, read
//! from TOML.
//!
//! ```toml
//! name = "empty room"        # optional
//!
//! [robot]                    # true start pose; the believed pose starts equal to it
//! x = 0.0                    # m
//! y = 0.0                    # m
//! heading = 0.0              # degrees, counter-clockwise from +x (optional, default 0)
//!
//! [run]                      # optional
//! dt = 0.1                   # s, simulator time step
//! noise = "ideal"            # ideal | realistic | pessimistic
//!
//! [pipeline]                 # optional; any field of pipeline::Settings, e.g.
//! vote_mode = "arcs"         # arcs | points
//! k = 30
//! r_bin_mm = 50.0
//!
//! [[wall]]                   # one table per wall segment, metres
//! x1 = -4.0
//! y1 = -3.0
//! x2 = 4.0
//! y2 = -3.0
//! ```
//!
//! Built-in worlds: [`World::empty_room`], the experiment's empty 8 m × 6 m room, and
//! [`World::box_partition`], the partition box of the thesis's Figures 11 and 14, sized so
//! that a robot at its origin reads the sonar values the thesis lists for Figure 14.
//!
//! A bad file gives a [`WorldError`] naming the field (`wall[2].x1`, `pipeline.k`, …) and, when
//! known, its line and column. Loading never panics.

use std::fmt;
use std::path::{Path, PathBuf};

use serde::Deserialize;
use toml::Spanned;

use super::geom::{clearance, Pose, Segment};
use super::pioneer::{DEFAULT_DT_S, RADIUS_M};
use super::pipeline::Settings;
use super::sonar::NoisePreset;

/// Run settings of a world.
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct RunSettings {
    /// Simulator time step, s.
    pub dt: f64,
    /// Sonar noise preset.
    pub noise: NoisePreset,
}

impl Default for RunSettings {
    fn default() -> Self {
        RunSettings {
            dt: DEFAULT_DT_S,
            noise: NoisePreset::Ideal,
        }
    }
}

/// A simulated world.
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct World {
    /// A short name for reports.
    pub name: String,
    /// Wall segments, m.
    pub walls: Vec<Segment>,
    /// The robot's true start pose.
    pub start: Pose,
    /// Time step and noise preset.
    pub run: RunSettings,
    /// Pipeline settings.
    pub pipeline: Settings,
}

/// Names accepted by [`World::builtin`].
pub const BUILTIN_WORLDS: [&str; 4] = ["empty-room", "box-partition", "l-room", "box-room"];

fn rectangle(x0: f64, y0: f64, x1: f64, y1: f64) -> Vec<Segment> {
    vec![
        Segment::new(x0, y0, x1, y0),
        Segment::new(x1, y0, x1, y1),
        Segment::new(x1, y1, x0, y1),
        Segment::new(x0, y1, x0, y0),
    ]
}

impl World {
    /// The experiment's empty 8 m × 6 m room, centred on the origin (Stage worlds are centred
    /// too), the robot starting at the centre facing +x.
    pub fn empty_room() -> Self {
        World {
            name: "empty-room".into(),
            walls: rectangle(-4.0, -3.0, 4.0, 3.0),
            start: Pose::default(),
            run: RunSettings::default(),
            pipeline: Settings::default(),
        }
    }

    /// The partition box of the thesis's Figures 11 and 14: a 4.1 m × 3.45 m box with the robot
    /// at the origin facing +x, 1.35 m from the left partition, 2.1 m from the right one,
    /// 2.6 m from the front and 1.5 m from the back, which is where the Figure 14 sonar values
    /// (1215, 1510, 2249, 2464, 2464, 2741, 2426, 1965, …) put the walls.
    pub fn box_partition() -> Self {
        World {
            name: "box-partition".into(),
            walls: rectangle(-1.5, -2.1, 2.6, 1.35),
            start: Pose::default(),
            run: RunSettings::default(),
            pipeline: Settings::default(),
        }
    }

    /// An L-shaped room: the 8 m × 6 m room without its 3 m × 2 m corner at x > 1, y > 1, so
    /// that six walls meet at right angles, one corner pointing into the room. The robot starts
    /// at the origin facing +x, as in the empty room.
    pub fn l_room() -> Self {
        let corners = [
            (-4.0, -3.0),
            (4.0, -3.0),
            (4.0, 1.0),
            (1.0, 1.0),
            (1.0, 3.0),
            (-4.0, 3.0),
        ];
        let walls = (0..corners.len())
            .map(|i| {
                let (a, b) = (corners[i], corners[(i + 1) % corners.len()]);
                Segment::new(a.0, a.1, b.0, b.1)
            })
            .collect();
        World {
            name: "l-room".into(),
            walls,
            start: Pose::default(),
            run: RunSettings::default(),
            pipeline: Settings::default(),
        }
    }

    /// The 8 m × 6 m room with a 1 m × 1 m box standing in it at x 2–3 m, y −0.5–0.5 m, across
    /// the robot's first run along +x (the wander follows the room's walls once it reaches
    /// one, so a box in the middle would never be met): four short walls parallel to the
    /// room's, which a map must tell from the room's walls.
    pub fn box_room() -> Self {
        let mut walls = rectangle(-4.0, -3.0, 4.0, 3.0);
        walls.extend(rectangle(2.0, -0.5, 3.0, 0.5));
        World {
            name: "box-room".into(),
            walls,
            start: Pose::default(),
            run: RunSettings::default(),
            pipeline: Settings::default(),
        }
    }

    /// A built-in world by name (see [`BUILTIN_WORLDS`]).
    pub fn builtin(name: &str) -> Option<Self> {
        match name {
            "empty-room" => Some(World::empty_room()),
            "box-partition" => Some(World::box_partition()),
            "l-room" => Some(World::l_room()),
            "box-room" => Some(World::box_room()),
            _ => None,
        }
    }

    /// Reads and validates a world file.
    pub fn load(path: &Path) -> Result<Self, WorldError> {
        let text = std::fs::read_to_string(path).map_err(|source| WorldError::Io {
            path: path.to_path_buf(),
            source,
        })?;
        World::from_toml_str(&text).map_err(|e| e.in_file(path))
    }

    /// Parses and validates a world from TOML text.
    pub fn from_toml_str(text: &str) -> Result<Self, WorldError> {
        let raw: RawWorld = toml::from_str(text).map_err(|e| serde_error(text, &e))?;
        raw.validate(text)
    }

    /// The world as TOML text that [`World::from_toml_str`] reads back.
    pub fn to_toml_string(&self) -> String {
        use std::fmt::Write;
        let p = &self.pipeline;
        let mut s = String::new();
        let _ = writeln!(s, "name = {}", toml_string(&self.name));
        let _ = writeln!(s, "\n[robot]");
        let _ = writeln!(s, "x = {:?}\ny = {:?}", self.start.x, self.start.y);
        let _ = writeln!(s, "heading = {:?}", self.start.th.to_degrees());
        let _ = writeln!(
            s,
            "\n[run]\ndt = {:?}\nnoise = \"{}\"",
            self.run.dt, self.run.noise
        );
        let _ = writeln!(s, "\n[pipeline]");
        let _ = writeln!(s, "vote_mode = \"{}\"", p.vote_mode);
        let _ = writeln!(s, "k = {}\nr_bin_mm = {:?}", p.k, p.r_bin_mm);
        let _ = writeln!(s, "theta_step_deg = {}", p.theta_step_deg);
        let _ = writeln!(s, "scan_window = {}", p.scan_window);
        let _ = writeln!(s, "extract_every = {}", p.extract_every);
        let _ = writeln!(s, "filter_k = {}", p.filter_k);
        let _ = writeln!(s, "filter_cell_mm = {:?}", p.filter_cell_mm);
        let _ = writeln!(s, "beam_deg = {:?}", p.beam_deg);
        let _ = writeln!(s, "min_range_mm = {:?}", p.min_range_mm);
        let _ = writeln!(s, "max_range_mm = {:?}", p.max_range_mm);
        let _ = writeln!(s, "support_mm = {:?}", p.support_mm);
        let _ = writeln!(s, "gap_mm = {:?}", p.gap_mm);
        let _ = writeln!(s, "min_points = {}", p.min_points);
        let _ = writeln!(s, "min_length_mm = {:?}", p.min_length_mm);
        let _ = writeln!(s, "refine = {}", p.refine);
        for w in &self.walls {
            let _ = writeln!(
                s,
                "\n[[wall]]\nx1 = {:?}\ny1 = {:?}\nx2 = {:?}\ny2 = {:?}",
                w.a.x, w.a.y, w.b.x, w.b.y
            );
        }
        s
    }
}

fn toml_string(s: &str) -> String {
    let mut out = String::from("\"");
    for c in s.chars() {
        match c {
            '"' => out.push_str("\\\""),
            '\\' => out.push_str("\\\\"),
            c if c.is_control() => out.push_str(&format!("\\u{:04X}", c as u32)),
            c => out.push(c),
        }
    }
    out.push('"');
    out
}

/// Why a world file was rejected.
#[derive(Debug, thiserror::Error)]
pub enum WorldError {
    /// The file could not be read.
    #[error("cannot read world file `{}`: {source}", path.display())]
    Io {
        /// The file.
        path: PathBuf,
        /// The I/O error.
        source: std::io::Error,
    },
    /// The file is not valid TOML or not a valid world.
    #[error("{}", self.describe())]
    Invalid {
        /// The file, when read from one.
        path: Option<PathBuf>,
        /// The offending field as a path (`wall[2].x1`), when known.
        field: Option<String>,
        /// 1-based line, when known.
        line: Option<usize>,
        /// 1-based column, when known.
        column: Option<usize>,
        /// What is wrong.
        message: String,
    },
}

impl WorldError {
    /// The offending field's path, when known.
    pub fn field(&self) -> Option<&str> {
        match self {
            WorldError::Invalid { field, .. } => field.as_deref(),
            WorldError::Io { .. } => None,
        }
    }

    /// The 1-based line and column, when known.
    pub fn position(&self) -> Option<(usize, usize)> {
        match self {
            WorldError::Invalid {
                line: Some(l),
                column: Some(c),
                ..
            } => Some((*l, *c)),
            _ => None,
        }
    }

    fn in_file(self, file: &Path) -> Self {
        match self {
            WorldError::Invalid {
                field,
                line,
                column,
                message,
                ..
            } => WorldError::Invalid {
                path: Some(file.to_path_buf()),
                field,
                line,
                column,
                message,
            },
            other => other,
        }
    }

    fn describe(&self) -> String {
        let WorldError::Invalid {
            path,
            field,
            line,
            column,
            message,
        } = self
        else {
            return String::new();
        };
        let mut s = match path {
            Some(p) => format!("world file `{}`", p.display()),
            None => "world file".to_string(),
        };
        if let Some(f) = field {
            s.push_str(&format!(", field `{f}`"));
        }
        match (line, column) {
            (Some(l), Some(c)) => s.push_str(&format!(" (line {l}, column {c})")),
            (Some(l), None) => s.push_str(&format!(" (line {l})")),
            _ => {}
        }
        s.push_str(": ");
        s.push_str(message);
        s
    }
}

/// A location in the source: byte span → 1-based line and column.
fn line_col(text: &str, offset: usize) -> (usize, usize) {
    let offset = offset.min(text.len());
    let before = text.get(..offset).unwrap_or(text);
    let line = before.matches('\n').count() + 1;
    let line_start = before.rfind('\n').map_or(0, |i| i + 1);
    let column = text
        .get(line_start..offset)
        .map_or(1, |s| s.chars().count() + 1);
    (line, column)
}

fn invalid(
    text: &str,
    field: impl Into<String>,
    span: Option<std::ops::Range<usize>>,
    message: impl Into<String>,
) -> WorldError {
    let (line, column) = match span {
        Some(s) => {
            let (l, c) = line_col(text, s.start);
            (Some(l), Some(c))
        }
        None => (None, None),
    };
    WorldError::Invalid {
        path: None,
        field: Some(field.into()),
        line,
        column,
        message: message.into(),
    }
}

/// Turns a toml/serde error into a [`WorldError`], recovering the field's path from the span.
fn serde_error(text: &str, e: &toml::de::Error) -> WorldError {
    let message = friendly(e.message());
    let span = e.span();
    let (line, column) = match &span {
        Some(s) => {
            let (l, c) = line_col(text, s.start);
            (Some(l), Some(c))
        }
        None => (None, None),
    };
    let field = span.and_then(|s| field_at(text, s, e.message()));
    WorldError::Invalid {
        path: None,
        field,
        line,
        column,
        message,
    }
}

/// Rewords serde's type names for people writing world files.
fn friendly(message: &str) -> String {
    let mut m = message.trim().to_string();
    for (from, to) in [
        ("expected f64", "expected a number"),
        ("expected u32", "expected a whole number ≥ 0"),
        ("expected usize", "expected a whole number ≥ 0"),
        ("expected a string", "expected a string"),
        ("expected a boolean", "expected true or false"),
    ] {
        m = m.replace(from, to);
    }
    if let Some(i) = m.find("expected struct ") {
        m.truncate(i);
        m.push_str("expected a table");
    }
    if let Some(i) = m.find("expected a sequence") {
        m.truncate(i);
        m.push_str("expected an array of tables ([[wall]])");
    }
    m
}

fn is_key_char(c: char) -> bool {
    c.is_ascii_alphanumeric() || c == '_' || c == '-'
}

/// The bare key that ends `s` (after trimming), if any.
fn trailing_key(s: &str) -> Option<&str> {
    let s = s.trim_end();
    let start = s
        .char_indices()
        .rev()
        .take_while(|(_, c)| is_key_char(*c))
        .last()
        .map(|(i, _)| i)?;
    Some(&s[start..])
}

/// The heading, in radians, of a heading typed in degrees: one that is written back as
/// degrees that read back as the same radians. The plain conversion does not promise it
/// (3° is 0.05235987755982989 rad, written 3.0000000000000004°, read back
/// 0.0523598775598299 rad), so reading and writing are repeated until they agree; should
/// they settle on a cycle instead, its smallest member is taken, which every member of the
/// cycle leads to.
fn heading_radians(degrees: f64) -> f64 {
    let read = |d: f64| super::geom::normalize_angle(d.to_radians());
    let mut seen = vec![read(degrees)];
    loop {
        let last = seen[seen.len() - 1];
        let next = read(last.to_degrees());
        if next == last || !next.is_finite() {
            return last;
        }
        if let Some(i) = seen.iter().position(|&x| x == next) {
            return seen[i..].iter().copied().fold(f64::INFINITY, f64::min);
        }
        seen.push(next);
    }
}

/// Best-effort dotted path (`wall[1].x1`, `robot.heading`) of the field a toml error points at.
fn field_at(text: &str, span: std::ops::Range<usize>, raw_message: &str) -> Option<String> {
    let start = span.start.min(text.len());
    // The table: the last header at or before the error's line.
    let mut table: Option<String> = None;
    let mut counts: Vec<(String, usize)> = Vec::new();
    let mut line_start = 0usize;
    for line in text.split_inclusive('\n') {
        if line_start > start {
            break;
        }
        let t = line.split('#').next().unwrap_or("").trim();
        if let Some(inner) = t.strip_prefix("[[").and_then(|r| r.strip_suffix("]]")) {
            let name = inner.trim().to_string();
            let n = match counts.iter_mut().find(|(k, _)| *k == name) {
                Some((_, n)) => {
                    *n += 1;
                    *n
                }
                None => {
                    counts.push((name.clone(), 0));
                    0
                }
            };
            table = Some(format!("{name}[{n}]"));
        } else if let Some(inner) = t.strip_prefix('[').and_then(|r| r.strip_suffix(']')) {
            table = Some(inner.trim().to_string());
        }
        line_start += line.len();
    }
    let this_line_start = text.get(..start)?.rfind('\n').map_or(0, |i| i + 1);
    let before = text.get(this_line_start..start)?;
    let at = text.get(start..)?;
    let mut parts: Vec<String> = table.into_iter().collect();
    // An inline table `name = { … }` opened earlier on this line.
    if let Some(brace) = before.rfind('{') {
        if !before[brace..].contains('}') {
            if let Some(parent) = before[..brace]
                .trim_end()
                .strip_suffix('=')
                .and_then(trailing_key)
            {
                parts.push(parent.to_string());
            }
        }
    }
    // Is the span a key (`foo = …`) or a value (`foo = <span>`)?
    let span_key: String = at.chars().take_while(|c| is_key_char(*c)).collect();
    let after_key = &at[span_key.len()..];
    if !span_key.is_empty() && after_key.trim_start().starts_with('=') {
        parts.push(span_key);
    } else if let Some(key) = before.trim_end().strip_suffix('=').and_then(trailing_key) {
        parts.push(key.to_string());
    }
    // `missing field `x`` names the field directly.
    if let Some(rest) = raw_message.strip_prefix("missing field `") {
        if let Some(name) = rest.split('`').next() {
            parts.push(name.to_string());
        }
    }
    (!parts.is_empty()).then(|| parts.join("."))
}

// ---------------------------------------------------------------------------------------------
// Raw, spanned form of the file, validated into `World`.

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawWorld {
    name: Option<String>,
    robot: Option<RawRobot>,
    run: Option<RawRun>,
    pipeline: Option<RawPipeline>,
    #[serde(default)]
    wall: Vec<Spanned<RawWall>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawRobot {
    x: Spanned<f64>,
    y: Spanned<f64>,
    heading: Option<Spanned<f64>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawRun {
    dt: Option<Spanned<f64>>,
    noise: Option<Spanned<String>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawWall {
    x1: Spanned<f64>,
    y1: Spanned<f64>,
    x2: Spanned<f64>,
    y2: Spanned<f64>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawPipeline {
    vote_mode: Option<Spanned<String>>,
    k: Option<Spanned<u32>>,
    r_bin_mm: Option<Spanned<f64>>,
    theta_step_deg: Option<Spanned<u32>>,
    scan_window: Option<Spanned<usize>>,
    extract_every: Option<Spanned<usize>>,
    filter_k: Option<Spanned<u32>>,
    filter_cell_mm: Option<Spanned<f64>>,
    beam_deg: Option<Spanned<f64>>,
    min_range_mm: Option<Spanned<f64>>,
    max_range_mm: Option<Spanned<f64>>,
    support_mm: Option<Spanned<f64>>,
    gap_mm: Option<Spanned<f64>>,
    min_points: Option<Spanned<usize>>,
    min_length_mm: Option<Spanned<f64>>,
    refine: Option<bool>,
}

/// Checks one optional number against a range.
struct Checker<'a> {
    text: &'a str,
}

impl Checker<'_> {
    fn finite(&self, field: &str, v: &Spanned<f64>) -> Result<f64, WorldError> {
        let x = *v.get_ref();
        if x.is_finite() {
            Ok(x)
        } else {
            Err(invalid(
                self.text,
                field,
                Some(v.span()),
                "must be a finite number",
            ))
        }
    }

    fn real(
        &self,
        field: &str,
        v: Option<&Spanned<f64>>,
        default: f64,
        ok: impl Fn(f64) -> bool,
        expect: &str,
    ) -> Result<f64, WorldError> {
        let Some(v) = v else { return Ok(default) };
        let x = self.finite(field, v)?;
        if ok(x) {
            Ok(x)
        } else {
            Err(invalid(
                self.text,
                field,
                Some(v.span()),
                format!("is {x}, must be {expect}"),
            ))
        }
    }

    fn whole<T: Copy + fmt::Display>(
        &self,
        field: &str,
        v: Option<&Spanned<T>>,
        default: T,
        ok: impl Fn(T) -> bool,
        expect: &str,
    ) -> Result<T, WorldError> {
        let Some(v) = v else { return Ok(default) };
        let x = *v.get_ref();
        if ok(x) {
            Ok(x)
        } else {
            Err(invalid(
                self.text,
                field,
                Some(v.span()),
                format!("is {x}, must be {expect}"),
            ))
        }
    }
}

impl RawWorld {
    fn validate(self, text: &str) -> Result<World, WorldError> {
        let c = Checker { text };
        // Walls.
        if self.wall.is_empty() {
            return Err(invalid(
                text,
                "wall",
                None,
                "a world needs at least one wall segment ([[wall]] with x1, y1, x2, y2 in metres)",
            ));
        }
        let mut walls = Vec::with_capacity(self.wall.len());
        for (i, w) in self.wall.iter().enumerate() {
            let raw = w.get_ref();
            let f = |name: &str| format!("wall[{i}].{name}");
            let seg = Segment::new(
                c.finite(&f("x1"), &raw.x1)?,
                c.finite(&f("y1"), &raw.y1)?,
                c.finite(&f("x2"), &raw.x2)?,
                c.finite(&f("y2"), &raw.y2)?,
            );
            if seg.length() < 1e-3 {
                return Err(invalid(
                    text,
                    format!("wall[{i}]"),
                    Some(w.span()),
                    "the wall's two end points coincide (length under 1 mm)",
                ));
            }
            walls.push(seg);
        }
        // Robot.
        let Some(robot) = self.robot else {
            return Err(invalid(
                text,
                "robot",
                None,
                "missing table [robot] with the start pose (x and y in metres, heading in degrees)",
            ));
        };
        let x = c.finite("robot.x", &robot.x)?;
        let y = c.finite("robot.y", &robot.y)?;
        let heading = match &robot.heading {
            Some(h) => c.finite("robot.heading", h)?,
            None => 0.0,
        };
        let start = Pose::new(x, y, heading_radians(heading));
        let gap = clearance(start.position(), &walls);
        if gap < RADIUS_M {
            return Err(invalid(
                text,
                "robot",
                Some(robot.x.span()),
                format!(
                    "the robot (radius {RADIUS_M} m) at ({x}, {y}) is {gap:.3} m from a wall; \
                     start it at least {RADIUS_M} m away"
                ),
            ));
        }
        // Run.
        let mut run = RunSettings::default();
        if let Some(r) = &self.run {
            run.dt = c.real(
                "run.dt",
                r.dt.as_ref(),
                run.dt,
                |v| v > 0.0 && v <= 1.0,
                "in (0, 1] s",
            )?;
            if let Some(n) = &r.noise {
                run.noise = n
                    .get_ref()
                    .parse()
                    .map_err(|e: super::sonar::UnknownPreset| {
                        invalid(text, "run.noise", Some(n.span()), e.to_string())
                    })?;
            }
        }
        // Pipeline.
        let d = Settings::default();
        let pipeline = match &self.pipeline {
            None => d,
            Some(p) => {
                let min_range_mm = c.real(
                    "pipeline.min_range_mm",
                    p.min_range_mm.as_ref(),
                    d.min_range_mm,
                    |v| v >= 0.0,
                    "≥ 0",
                )?;
                let vote_mode = match &p.vote_mode {
                    None => d.vote_mode,
                    Some(v) => v.get_ref().parse().map_err(|e: String| {
                        invalid(text, "pipeline.vote_mode", Some(v.span()), e)
                    })?,
                };
                Settings {
                    vote_mode,
                    k: c.whole("pipeline.k", p.k.as_ref(), d.k, |_| true, "≥ 0")?,
                    r_bin_mm: c.real(
                        "pipeline.r_bin_mm",
                        p.r_bin_mm.as_ref(),
                        d.r_bin_mm,
                        |v| (1.0..=1000.0).contains(&v),
                        "between 1 and 1000 mm",
                    )?,
                    theta_step_deg: c.whole(
                        "pipeline.theta_step_deg",
                        p.theta_step_deg.as_ref(),
                        d.theta_step_deg,
                        |v| (1..=90).contains(&v) && 360 % v == 0,
                        "a divisor of 360 between 1 and 90 degrees",
                    )?,
                    scan_window: c.whole(
                        "pipeline.scan_window",
                        p.scan_window.as_ref(),
                        d.scan_window,
                        |v| (1..=100_000).contains(&v),
                        "between 1 and 100000 scans",
                    )?,
                    extract_every: c.whole(
                        "pipeline.extract_every",
                        p.extract_every.as_ref(),
                        d.extract_every,
                        |v| (1..=1_000_000).contains(&v),
                        "between 1 and 1000000 steps",
                    )?,
                    filter_k: c.whole(
                        "pipeline.filter_k",
                        p.filter_k.as_ref(),
                        d.filter_k,
                        |_| true,
                        "≥ 0",
                    )?,
                    filter_cell_mm: c.real(
                        "pipeline.filter_cell_mm",
                        p.filter_cell_mm.as_ref(),
                        d.filter_cell_mm,
                        |v| (1.0..=5000.0).contains(&v),
                        "between 1 and 5000 mm",
                    )?,
                    beam_deg: c.real(
                        "pipeline.beam_deg",
                        p.beam_deg.as_ref(),
                        d.beam_deg,
                        |v| v > 0.0 && v <= 180.0,
                        "in (0, 180] degrees",
                    )?,
                    min_range_mm,
                    max_range_mm: c.real(
                        "pipeline.max_range_mm",
                        p.max_range_mm.as_ref(),
                        d.max_range_mm,
                        |v| v > min_range_mm,
                        "greater than min_range_mm",
                    )?,
                    support_mm: c.real(
                        "pipeline.support_mm",
                        p.support_mm.as_ref(),
                        d.support_mm,
                        |v| v > 0.0 && v <= 10_000.0,
                        "in (0, 10000] mm",
                    )?,
                    gap_mm: c.real(
                        "pipeline.gap_mm",
                        p.gap_mm.as_ref(),
                        d.gap_mm,
                        |v| v > 0.0,
                        "> 0 mm",
                    )?,
                    min_points: c.whole(
                        "pipeline.min_points",
                        p.min_points.as_ref(),
                        d.min_points,
                        |v| (2..=1_000_000).contains(&v),
                        "at least 2",
                    )?,
                    min_length_mm: c.real(
                        "pipeline.min_length_mm",
                        p.min_length_mm.as_ref(),
                        d.min_length_mm,
                        |v| v >= 0.0,
                        "≥ 0 mm",
                    )?,
                    refine: p.refine.unwrap_or(d.refine),
                }
            }
        };
        Ok(World {
            name: self.name.unwrap_or_else(|| "world".into()),
            walls,
            start,
            run,
            pipeline,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const GOOD: &str = r#"
name = "test room"

[robot]
x = 1
y = 0.5
heading = 90

[run]
dt = 0.05
noise = "realistic"

[pipeline]
k = 20
r_bin_mm = 40.0

[[wall]]
x1 = -4.0
y1 = -3.0
x2 = 4.0
y2 = -3.0

[[wall]]
x1 = 4.0
y1 = -3.0
x2 = 4.0
y2 = 3.0
"#;

    fn err(text: &str) -> WorldError {
        match World::from_toml_str(text) {
            Ok(w) => panic!("accepted: {w:?}"),
            Err(e) => e,
        }
    }

    #[test]
    fn parses_a_good_file() {
        let w = World::from_toml_str(GOOD).expect("valid");
        assert_eq!(w.name, "test room");
        assert_eq!(w.walls.len(), 2);
        assert_eq!(w.walls[1], Segment::new(4.0, -3.0, 4.0, 3.0));
        assert_eq!(w.start.x, 1.0);
        assert!((w.start.th - std::f64::consts::FRAC_PI_2).abs() < 1e-12);
        assert_eq!(w.run.dt, 0.05);
        assert_eq!(w.run.noise, NoisePreset::Realistic);
        assert_eq!(w.pipeline.k, 20);
        assert_eq!(w.pipeline.r_bin_mm, 40.0);
        assert_eq!(
            w.pipeline.theta_step_deg, 1,
            "unset fields keep their defaults"
        );
    }

    #[test]
    fn builtins_round_trip_through_toml() {
        for name in BUILTIN_WORLDS {
            let w = World::builtin(name).expect("builtin");
            let back = World::from_toml_str(&w.to_toml_string()).expect("round trip");
            assert_eq!(back, w, "{name}");
        }
        assert!(World::builtin("nowhere").is_none());
    }

    #[test]
    fn type_error_names_field_and_position() {
        let text = GOOD.replace(
            "y1 = -3.0\nx2 = 4.0\ny2 = 3.0",
            "y1 = \"low\"\nx2 = 4.0\ny2 = 3.0",
        );
        let e = err(&text);
        assert_eq!(e.field(), Some("wall[1].y1"));
        let msg = e.to_string();
        assert!(
            msg.contains("wall[1].y1") && msg.contains("expected a number"),
            "{msg}"
        );
        let (line, col) = e.position().expect("position");
        assert_eq!(text.lines().nth(line - 1), Some("y1 = \"low\""));
        assert_eq!(col, 6);
    }

    #[test]
    fn missing_field_is_named() {
        let e = err(&GOOD.replace("x2 = 4.0\ny2 = -3.0\n", "y2 = -3.0\n"));
        assert_eq!(e.field(), Some("wall[0].x2"), "{e}");
        assert!(e.to_string().contains("missing field"));
        let e = err("[[wall]]\nx1 = 0\ny1 = 0\nx2 = 1\ny2 = 0\n[robot]\nx = 0.5\n");
        assert_eq!(e.field(), Some("robot.y"), "{e}");
    }

    #[test]
    fn unknown_fields_are_named() {
        let e = err(&GOOD.replace("k = 20", "kk = 20"));
        assert_eq!(e.field(), Some("pipeline.kk"), "{e}");
        assert!(e.to_string().contains("unknown field"));
        let e = err(&GOOD.replace(
            "[robot]\nx = 1\ny = 0.5\nheading = 90",
            "robot = { x = 1, y = 0.5, z = 3 }",
        ));
        assert_eq!(e.field(), Some("robot.z"), "{e}");
    }

    #[test]
    fn range_errors_name_field() {
        let cases = [
            (GOOD.replace("dt = 0.05", "dt = 0"), "run.dt"),
            (GOOD.replace("dt = 0.05", "dt = nan"), "run.dt"),
            (
                GOOD.replace("noise = \"realistic\"", "noise = \"loud\""),
                "run.noise",
            ),
            (GOOD.replace("k = 20", "k = -1"), "pipeline.k"),
            (
                GOOD.replace("k = 20", "vote_mode = \"pixels\""),
                "pipeline.vote_mode",
            ),
            (
                GOOD.replace("r_bin_mm = 40.0", "r_bin_mm = 0.0"),
                "pipeline.r_bin_mm",
            ),
            (
                GOOD.replace("k = 20", "theta_step_deg = 7"),
                "pipeline.theta_step_deg",
            ),
            (GOOD.replace("x1 = -4.0", "x1 = inf"), "wall[0].x1"),
            (GOOD.replace("y = 0.5", "y = -2.9"), "robot"),
            (GOOD.replace("x = 1\n", "x = \"one\"\n"), "robot.x"),
        ];
        for (text, field) in cases {
            let e = err(&text);
            assert_eq!(e.field(), Some(field), "{e}");
            assert!(e.to_string().contains(field), "{e}");
            assert!(e.position().is_some(), "{e}");
        }
        let e = err(&GOOD.replace("noise = \"realistic\"", "noise = \"loud\""));
        assert!(e.to_string().contains("unknown noise preset `loud`"), "{e}");
    }

    #[test]
    fn structural_errors() {
        let e = err("[robot]\nx = 0\ny = 0\n");
        assert_eq!(e.field(), Some("wall"));
        let e = err("[[wall]]\nx1 = 0\ny1 = 0\nx2 = 1\ny2 = 0\n");
        assert_eq!(e.field(), Some("robot"));
        let e = err("[[wall]]\nx1 = 0\ny1 = 0\nx2 = 0\ny2 = 0\n[robot]\nx = 3\ny = 3\n");
        assert_eq!(e.field(), Some("wall[0]"));
        let e = err("[robot\nx = 1");
        assert!(e.position().is_some(), "{e}");
        let e = err("wall = 3\n");
        assert_eq!(e.field(), Some("wall"), "{e}");
    }

    #[test]
    fn unreadable_file() {
        let e = World::load(Path::new("/nonexistent/world.toml")).expect_err("no file");
        assert!(e.to_string().contains("/nonexistent/world.toml"));
    }

    proptest::proptest! {
        #![proptest_config(proptest::prelude::ProptestConfig::with_cases(256))]

        /// Arbitrary text, and the good file with one character changed, never panic.
        #[test]
        fn mangled_files_never_panic(text in "\\PC{0,200}", at in 0usize..400, c in proptest::prelude::any::<char>()) {
            let _ = World::from_toml_str(&text);
            let mut good: Vec<char> = GOOD.chars().collect();
            let i = at % good.len();
            good[i] = c;
            let _ = World::from_toml_str(&good.into_iter().collect::<String>());
        }
    }

    #[test]
    fn arbitrary_text_never_panics() {
        for text in [
            "",
            "=",
            "[[[",
            "robot = 1",
            "[robot]\nx = 1e400\n",
            "\u{0}",
            "[[wall]]\n[[wall]]",
        ] {
            let _ = World::from_toml_str(text);
        }
    }
}
