//! `visualize`: what the command goldens (`tests/commands/visualize*.cmds`) leave out: the
//! files it writes, `dot` failing, and the forms whose 9.6 answer is a quirk rusoar does not
//! share.

use rusoar::Agent;
use std::path::Path;

/// An agent whose current directory is a fresh one under the target directory.
fn agent_in(dir: &str) -> (Agent, std::path::PathBuf) {
    let path = Path::new(env!("CARGO_TARGET_TMPDIR")).join(dir);
    let _ = std::fs::remove_dir_all(&path);
    std::fs::create_dir_all(&path).unwrap();
    let mut a = Agent::default();
    a.execute("watch 0").unwrap();
    a.execute(&format!("cd {}", path.display())).unwrap();
    a.execute("visualize viewer-launch off").unwrap();
    a.execute("visualize generate-image off").unwrap();
    a.execute("sp {a (state <s> ^superstate nil) --> (<s> ^thing <t>) (<t> ^name |a <b> & c|)}")
        .unwrap();
    a.execute("run 1").unwrap();
    (a, path)
}

#[test]
fn new_files_are_numbered_past_those_that_exist() {
    let (mut a, dir) = agent_in("viz-numbering");
    std::fs::write(dir.join("soar_viz1.gv"), "kept").unwrap();
    a.execute("visualize wm").unwrap();
    a.execute("visualize wm s1 2").unwrap();
    assert_eq!(
        std::fs::read_to_string(dir.join("soar_viz1.gv")).unwrap(),
        "kept"
    );
    let second = std::fs::read_to_string(dir.join("soar_viz2.gv")).unwrap();
    assert!(
        second.starts_with("digraph g {\n") && second.ends_with("}\n"),
        "{second}"
    );
    // The record escapes the markup a constant holds, so `dot` can read the file.
    assert!(second.contains("|a &lt;b&gt; &amp; c|"), "{second}");
    assert!(dir.join("soar_viz3.gv").exists());
    a.execute("visualize use-same-file on").unwrap();
    a.execute("visualize file-name same").unwrap();
    a.execute("visualize wm").unwrap();
    a.execute("visualize wm").unwrap();
    assert!(dir.join("same.gv").exists());
    assert!(!dir.join("soar_viz4.gv").exists());
}

#[test]
fn a_drawing_dot_cannot_make_fails_and_keeps_the_file() {
    let (mut a, dir) = agent_in("viz-dot");
    a.execute("visualize generate-image on").unwrap();
    // No `dot` draws an image of this type, whether or not Graphviz is installed.
    a.execute("visualize image-type no-such-format").unwrap();
    let e = a.execute("visualize wm").unwrap_err();
    assert!(
        e.message().contains("`dot` command failed"),
        "{}",
        e.message()
    );
    assert!(dir.join("soar_viz1.gv").exists());
}

#[test]
fn a_missing_directory_is_a_clear_error() {
    let (mut a, _dir) = agent_in("viz-missing-dir");
    a.execute("visualize file-name no/such/dir/x").unwrap();
    let e = a.execute("visualize wm").unwrap_err();
    assert!(
        e.message()
            .starts_with("Could not write the visualization to "),
        "{}",
        e.message()
    );
}

#[test]
fn the_listings_names_are_taken_too() {
    let (mut a, _dir) = agent_in("viz-names");
    assert_eq!(
        a.execute("visualize separate-states off")
            .unwrap()
            .trim_end(),
        "separate_states is now off"
    );
    assert_eq!(
        a.execute("visualize print-debug on").unwrap().trim_end(),
        "print is now on"
    );
    let listing = a.execute("visualize ?").unwrap();
    assert!(
        listing.contains("separate-states                        [ on | OFF ]"),
        "{listing}"
    );
    assert!(
        listing.contains("print-debug                            [ ON | off ]"),
        "{listing}"
    );
    // With print-debug on, the file's text follows the command's line.
    let text = a.execute("visualize wm").unwrap();
    assert!(
        text.starts_with("Generating visualization...\ndigraph g {\n"),
        "{text}"
    );
}

#[test]
fn an_ambiguous_prefix_names_the_candidates() {
    let (mut a, _dir) = agent_in("viz-prefix");
    let e = a.execute("visualize e").unwrap_err();
    assert!(
        e.message().starts_with("Invalid visualize sub-command."),
        "{}",
        e.message()
    );
    let text = format!("{e:?}");
    assert!(
        text.contains("ebc_analysis, editor-launch, epmem"),
        "{text}"
    );
}

#[test]
fn an_episode_that_is_not_stored_draws_nothing() {
    let (mut a, _dir) = agent_in("viz-epmem");
    let e = a.execute("visualize epmem 1").unwrap_err();
    assert_eq!(e.message(), "Visualization produced nothing.");
    a.execute("epmem --enable").unwrap();
    a.execute("run 2").unwrap();
    a.execute("visualize print-debug on").unwrap();
    let text = a.execute("visualize epmem 1").unwrap();
    assert!(text.contains("Visualization of Episodic Memory"), "{text}");
    assert!(text.contains("digraph epmem {"), "{text}");
    let e = a.execute("visualize epmem 99").unwrap_err();
    assert_eq!(e.message(), "Visualization produced nothing.");
}

#[test]
fn a_cycle_in_semantic_memory_draws_each_object_once() {
    let (mut a, _dir) = agent_in("viz-smem");
    a.execute("visualize print-debug on").unwrap();
    a.execute("smem --add {(<a> ^name a ^next <b>) (<b> ^name b ^next <a>)}")
        .unwrap();
    let text = a.execute("visualize smem @1 5").unwrap();
    assert_eq!(
        text.matches("<TD COLSPAN=\"3\">@1</TD>").count(),
        1,
        "{text}"
    );
    assert_eq!(
        text.matches("<TD COLSPAN=\"3\">@2</TD>").count(),
        1,
        "{text}"
    );
    let e = a.execute("visualize smem @1 0").unwrap_err();
    assert_eq!(e.message(), "Invalid depth specified to visualize");
}
