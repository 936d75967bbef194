//! Writing the experiment's output files whole or not at all: each file is written beside
//! its place under a temporary name, flushed to the disk, then renamed over it. A full
//! disk or a killed process leaves the earlier file (or none), never half of a new one.

use std::io::Write;
use std::path::{Path, PathBuf};

/// Writes `bytes` to `path`; the error names the file.
pub fn write(path: &Path, bytes: impl AsRef<[u8]>) -> Result<(), String> {
    let fail = |e: std::io::Error| format!("cannot write {}: {e}", path.display());
    let tmp = temporary_name(path);
    let written = (|| {
        let mut f = std::fs::File::create(&tmp)?;
        f.write_all(bytes.as_ref())?;
        f.sync_all()?;
        std::fs::rename(&tmp, path)
    })();
    if let Err(e) = written {
        let _ = std::fs::remove_file(&tmp);
        return Err(fail(e));
    }
    Ok(())
}

/// `DIR/.NAME.PID.tmp`: hidden, in the same folder (a rename does not cross file systems),
/// and one per process.
fn temporary_name(path: &Path) -> PathBuf {
    let name = path
        .file_name()
        .map_or_else(|| "output".into(), |n| n.to_string_lossy());
    path.with_file_name(format!(".{name}.{}.tmp", std::process::id()))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn folder(name: &str) -> PathBuf {
        let d = std::env::temp_dir().join(format!("soar-slam-out-{name}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&d);
        std::fs::create_dir_all(&d).unwrap();
        d
    }

    #[test]
    fn a_written_file_replaces_the_old_one_and_leaves_nothing_else() {
        let d = folder("replace");
        let p = d.join("report.md");
        std::fs::write(&p, "old").unwrap();
        write(&p, "new").unwrap();
        assert_eq!(std::fs::read_to_string(&p).unwrap(), "new");
        assert_eq!(std::fs::read_dir(&d).unwrap().count(), 1);
        std::fs::remove_dir_all(&d).unwrap();
    }

    #[test]
    fn a_folder_that_is_not_there_is_named() {
        let p = std::env::temp_dir()
            .join("soar-slam-no-such-folder")
            .join("x")
            .join("a.csv");
        let e = write(&p, "data").unwrap_err();
        assert!(
            e.starts_with(&format!("cannot write {}", p.display())),
            "{e}"
        );
    }

    #[test]
    fn a_failed_write_names_the_file_and_keeps_the_old_one() {
        let d = folder("fail");
        // A folder where the file should go: the rename fails after the data is written.
        let p = d.join("runs.csv");
        std::fs::create_dir(&p).unwrap();
        std::fs::write(p.join("keep"), "kept").unwrap();
        let e = write(&p, "new").unwrap_err();
        assert!(
            e.starts_with(&format!("cannot write {}", p.display())),
            "{e}"
        );
        assert_eq!(std::fs::read_to_string(p.join("keep")).unwrap(), "kept");
        assert_eq!(
            std::fs::read_dir(&d).unwrap().count(),
            1,
            "no temporary file is left"
        );
        std::fs::remove_dir_all(&d).unwrap();
    }
}
