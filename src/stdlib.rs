//! Soar's default rules as rusoar ships them: embedded in the binary, so
//! `source <stdlib>/selection.soar` works from anywhere. The files live in `stdlib/`.

/// The embedded files, by name.
pub const FILES: &[(&str, &str)] = &[("selection.soar", include_str!("../stdlib/selection.soar"))];

/// The prefix that names the embedded library in `source`.
pub const PREFIX: &str = "<stdlib>/";

/// The text of `<stdlib>/NAME`, if it is one of ours.
pub fn lookup(path: &str) -> Option<&'static str> {
    let name = path.strip_prefix(PREFIX)?;
    FILES.iter().find(|(n, _)| *n == name).map(|(_, t)| *t)
}
