//! Episodic memory in database files where the official kernel cannot be asked the same
//! thing (`scripts/epmem_db_compat.py` compares the files themselves with 9.6's): what a
//! dropped agent wrote is there for the next one, and a file that cannot be used is
//! reported by name while the agent goes on in memory, never a panic.

use rusoar::Agent;
use std::path::{Path, PathBuf};

const AGENT: &str = include_str!("data/epmem-file-agent.soar");

fn output(agent: &mut Agent, command: &str) -> String {
    agent
        .source_text("t", command)
        .unwrap_or_else(|e| panic!("`{command}`: {}", e.message()));
    agent.take_output()
}

/// A path in a fresh folder of its own, removed at the end.
struct TempFile {
    dir: PathBuf,
}

impl TempFile {
    fn new(name: &str) -> TempFile {
        let dir = std::env::temp_dir().join(format!("rusoar-epmem-{name}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        TempFile { dir }
    }

    fn path(&self) -> PathBuf {
        self.dir.join("episodes.db")
    }
}

impl Drop for TempFile {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.dir);
    }
}

fn agent_on(path: &Path, append: bool) -> Agent {
    let mut agent = Agent::default();
    output(&mut agent, "epmem --set database file");
    output(
        &mut agent,
        &format!("epmem --set path {{{}}}", path.display()),
    );
    output(
        &mut agent,
        &format!("epmem --set append {}", if append { "on" } else { "off" }),
    );
    output(&mut agent, "epmem --set learning on");
    output(&mut agent, AGENT);
    agent
}

#[test]
fn a_dropped_agent_leaves_its_episodes_to_the_next() {
    let file = TempFile::new("persist");
    let episode_5 = {
        let mut first = agent_on(&file.path(), false);
        output(&mut first, "run 10");
        assert_eq!(output(&mut first, "epmem --stats time"), " 10\n");
        output(&mut first, "epmem --print 5")
    };
    // The file opens at the first episode, the second decision's.
    let mut second = agent_on(&file.path(), true);
    output(&mut second, "run 2");
    assert_eq!(output(&mut second, "epmem --stats time"), " 11\n");
    assert_eq!(output(&mut second, "epmem --print 5"), episode_5);
    output(&mut second, "run 3");
    assert_eq!(output(&mut second, "epmem --stats time"), " 14\n");
    // With append off the file starts empty.
    drop(second);
    let mut third = agent_on(&file.path(), false);
    output(&mut third, "run 3");
    assert_eq!(output(&mut third, "epmem --stats time"), " 3\n");
    assert!(third.source_text("t", "epmem --print 5").is_err());
}

#[test]
fn commit_memories_writes_what_lazy_commit_holds_back() {
    let file = TempFile::new("commit");
    let mut agent = Agent::default();
    output(&mut agent, "epmem --set database file");
    output(
        &mut agent,
        &format!("epmem --set path {{{}}}", file.path().display()),
    );
    // 9.6's default, `performance`, holds the file locked while it is open.
    output(&mut agent, "epmem --set optimization safety");
    output(&mut agent, "epmem --set learning on");
    output(&mut agent, AGENT);
    output(&mut agent, "run 6");
    assert_eq!(count_episodes(&file.path()), 0);
    agent.commit_memories().unwrap();
    assert_eq!(count_episodes(&file.path()), 5);
    output(&mut agent, "run 2");
    // An agent the program never drops (as the command line does at its end).
    agent.commit_memories().unwrap();
    std::mem::forget(agent);
    assert_eq!(count_episodes(&file.path()), 7);
}

fn count_episodes(path: &Path) -> i64 {
    let conn = rusqlite::Connection::open(path).unwrap();
    conn.query_row("SELECT count(*) FROM epmem_episodes", [], |r| r.get(0))
        .unwrap()
}

#[test]
fn a_file_that_is_not_a_database_is_named_and_memory_takes_over() {
    let file = TempFile::new("junk");
    std::fs::write(file.path(), "these are not episodes\n".repeat(200)).unwrap();
    let mut agent = agent_on(&file.path(), true);
    let said = output(&mut agent, "run 4");
    assert!(said.contains(&file.path().display().to_string()), "{said}");
    assert!(
        said.contains("...Switching to memory-based database."),
        "{said}"
    );
    assert_eq!(
        output(&mut agent, "epmem --get database"),
        "database is memory\n"
    );
    assert_eq!(output(&mut agent, "epmem --stats time"), " 4\n");
    // The file is left as it was.
    assert!(std::fs::read_to_string(file.path())
        .unwrap()
        .starts_with("these are not"));
}

#[test]
fn another_schema_version_is_named() {
    let file = TempFile::new("version");
    {
        let conn = rusqlite::Connection::open(file.path()).unwrap();
        conn.execute_batch(
            "CREATE TABLE versions (system TEXT PRIMARY KEY, version_number TEXT);
             INSERT INTO versions VALUES ('epmem_schema', '1.0');",
        )
        .unwrap();
    }
    let mut agent = agent_on(&file.path(), true);
    let said = output(&mut agent, "run 2");
    assert!(said.contains("schema version 1.0"), "{said}");
    assert!(said.contains(&file.path().display().to_string()), "{said}");
    assert_eq!(
        output(&mut agent, "epmem --get database"),
        "database is memory\n"
    );
}

#[test]
fn a_locked_file_is_named() {
    let file = TempFile::new("locked");
    let holder = rusqlite::Connection::open(file.path()).unwrap();
    holder
        .execute_batch("CREATE TABLE other (x); BEGIN EXCLUSIVE; INSERT INTO other VALUES (1);")
        .unwrap();
    let mut agent = agent_on(&file.path(), true);
    let said = output(&mut agent, "run 2");
    assert!(said.contains("locked"), "{said}");
    assert!(said.contains(&file.path().display().to_string()), "{said}");
    assert_eq!(
        output(&mut agent, "epmem --get database"),
        "database is memory\n"
    );
    drop(holder);
}

#[test]
fn a_path_that_cannot_be_opened_is_named() {
    let mut agent = Agent::default();
    output(&mut agent, "epmem --set database file");
    output(
        &mut agent,
        "epmem --set path /nonexistent-folder/x/episodes.db",
    );
    output(&mut agent, "epmem --set learning on");
    output(&mut agent, AGENT);
    let said = output(&mut agent, "run 2");
    assert!(said.contains("/nonexistent-folder/x/episodes.db"), "{said}");
    let err = agent.source_text("t", "epmem --backup /nonexistent-folder/x/copy.db");
    assert!(err.is_err());
}

#[test]
fn a_damaged_file_with_numbers_past_its_rows_is_named() {
    let file = TempFile::new("damaged");
    {
        let mut first = agent_on(&file.path(), false);
        output(&mut first, "run 6");
    }
    for damage in [
        "UPDATE epmem_wmes_constant SET wc_id = 4000000000000 WHERE wc_id = 1",
        "UPDATE epmem_episodes SET episode_id = 9223372036854775807 WHERE episode_id = 2",
        "UPDATE epmem_wmes_constant_point SET episode_id = 99 WHERE rowid = 1",
    ] {
        let copy = file.dir.join("copy.db");
        std::fs::copy(file.path(), &copy).unwrap();
        rusqlite::Connection::open(&copy)
            .unwrap()
            .execute_batch(damage)
            .unwrap();
        let mut agent = agent_on(&copy, true);
        let said = output(&mut agent, "run 2");
        assert!(
            said.contains("which this kernel cannot read"),
            "{damage}: {said}"
        );
        assert!(said.contains(&copy.display().to_string()), "{said}");
        assert_eq!(
            output(&mut agent, "epmem --get database"),
            "database is memory\n"
        );
        drop(agent);
        std::fs::remove_file(&copy).unwrap();
    }
}
