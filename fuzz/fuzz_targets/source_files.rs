//! `source` of an agent made of several files: the input is cut into files at each line
//! `#file`, the first sources the others (by name, and through `pushd`/`popd` folders when
//! a file's first line names one), and the agent runs 50 decisions.
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    if !rusoar_fuzz::confined(text) {
        return;
    }
    let dir = rusoar_fuzz::scratch_dir().join("agent");
    let _ = std::fs::remove_dir_all(&dir);
    if std::fs::create_dir_all(dir.join("sub")).is_err() {
        return;
    }
    let parts: Vec<&str> = text.split("\n#file\n").collect();
    let mut main = String::new();
    for (i, part) in parts.iter().enumerate().skip(1) {
        // Odd files go in a sub-folder, reached with pushd/popd as VisualSoar's load
        // files reach theirs.
        let (folder, name) = if i % 2 == 1 {
            ("sub", format!("part{i}.soar"))
        } else {
            ("", format!("part{i}.soar"))
        };
        if std::fs::write(dir.join(folder).join(&name), part).is_err() {
            return;
        }
        if folder.is_empty() {
            main.push_str(&format!("source {name}\n"));
        } else {
            main.push_str(&format!("pushd {folder}\nsource {name}\npopd\n"));
        }
    }
    main.push_str(parts[0]);
    if std::fs::write(dir.join("main.soar"), &main).is_err() {
        return;
    }
    let mut agent = rusoar_fuzz::bounded_agent();
    agent.set_working_directory(&dir);
    let _ = agent.source_file(dir.join("main.soar"));
    let _ = agent.execute("run 50");
    let _ = agent.take_output();
    rusoar_fuzz::assert_invariants(&agent);
});
