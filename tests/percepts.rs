//! `save percepts` and `load percepts`: input recorded decision by decision and replayed,
//! with the seed that makes a replay's random choices the recording's (Soar manual, ch. 9,
//! `save` and `load`). The seed drawn after `srand 1` and the file's form are the official
//! kernel's (soar-sml 9.6.5 printed `Capturing input with random seed: 1791095845`).

use rusoar::{Agent, RunUnit};

const RULES: &str = r#"
sp {show (state <s> ^io.input-link <il>) (<il> ^<a> <v>) --> (write |saw | <a> | | <v> | | (rand-int 1000) (crlf))}
"#;

fn temp(name: &str) -> std::path::PathBuf {
    let dir = std::env::temp_dir().join(format!("rusoar-percepts-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir.join(name)
}

/// Runs `n` decisions and returns what the agent printed.
fn run(agent: &mut Agent, n: u64) -> String {
    agent.run(n, RunUnit::Decisions).unwrap();
    agent.take_output()
}

#[test]
fn a_recording_replays_the_same_input_and_random_choices() {
    let file = temp("recorded.txt");
    let mut rec = Agent::new("rec");
    rec.source_text("rules", RULES).unwrap();
    rec.execute("srand 1").unwrap();
    let opened = rec
        .execute(&format!("save percepts --open {}", file.display()))
        .unwrap();
    assert_eq!(
        opened.trim(),
        "Capturing input with random seed: 1791095845"
    );
    let (color, block) = {
        let mut io = rec.io();
        let il = io.input_link();
        let color = io.add(il, "color", "red").unwrap();
        let (block, b) = io.add_object(il, "block").unwrap();
        io.add(b, "size", 3).unwrap();
        io.add(b, "width", 2.5).unwrap();
        (color, block)
    };
    let mut recorded = run(&mut rec, 1);
    rec.io().update(color, "blue").unwrap();
    recorded += &run(&mut rec, 1);
    rec.io().remove(block).unwrap();
    rec.io().remove(color).unwrap();
    recorded += &run(&mut rec, 2);
    assert_eq!(rec.execute("save percepts").unwrap().trim(), "open");
    rec.execute("save percepts --close").unwrap();
    assert_eq!(rec.execute("save percepts").unwrap().trim(), "closed");

    let text = std::fs::read_to_string(&file).unwrap();
    let lines: Vec<&str> = text.lines().collect();
    assert_eq!(lines[0], "1791095845");
    assert!(
        lines[1].starts_with("1 -") && lines[1].ends_with(" add-wme I2 color red string"),
        "{text}"
    );
    assert!(lines.iter().any(|l| l.ends_with(" size 3 int")), "{text}");
    assert!(
        lines.iter().any(|l| l.ends_with(" width 2.500000 float")),
        "{text}"
    );
    assert!(
        lines
            .iter()
            .any(|l| l.starts_with("2 -") && l.ends_with("remove-wme")),
        "{text}"
    );

    let mut play = Agent::new("play");
    play.source_text("rules", RULES).unwrap();
    let loaded = play
        .execute(&format!("load percepts --open {}", file.display()))
        .unwrap();
    assert_eq!(
        loaded.trim(),
        format!("Loaded {} actions.", lines.len() - 1)
    );
    let replayed = run(&mut play, 4);
    assert_eq!(replayed, recorded);
    assert!(replayed.contains("saw color blue"), "{replayed}");
    play.execute("load percepts --close").unwrap();
    assert_eq!(play.execute("load percepts").unwrap().trim(), "closed");
}

#[test]
fn a_recording_made_by_the_official_kernel_replays() {
    // Written by soar-sml 9.6.5 for an SML client that added three WMEs, ran a decision,
    // removed the first and ran again.
    let file = temp("official.txt");
    std::fs::write(
        &file,
        "86490210\n1 -3 add-wme I2 color red string\n1 -4 add-wme I2 block b2 id\n1 -5 add-wme b2 size 3 int\n2 -3 remove-wme\n",
    )
    .unwrap();
    let mut agent = Agent::new("play");
    let loaded = agent
        .execute(&format!("load percepts -o {}", file.display()))
        .unwrap();
    assert_eq!(loaded.trim(), "Loaded 4 actions.");
    agent.run(1, RunUnit::Decisions).unwrap();
    agent.take_output();
    let shown = agent.execute("print --depth 2 i2").unwrap();
    assert!(shown.contains("^color red"), "{shown}");
    assert!(shown.contains("^size 3"), "{shown}");
    agent.run(1, RunUnit::Decisions).unwrap();
    let shown = agent.execute("print --depth 2 i2").unwrap();
    assert!(!shown.contains("^color"), "{shown}");
    assert!(shown.contains("^size 3"), "{shown}");
}

#[test]
fn misuse_gets_clear_errors() {
    let mut agent = Agent::new("a");
    let err = agent.execute("save percepts --close").unwrap_err();
    assert!(err.to_string().contains("File is not open."), "{err}");
    let err = agent.execute("load percepts -c").unwrap_err();
    assert!(err.to_string().contains("File is not open."), "{err}");
    let err = agent.execute("save percepts -x").unwrap_err();
    assert!(err.to_string().contains("No such option: x"), "{err}");
    let bad = temp("bad.txt");
    std::fs::write(&bad, "12\n1 -3 add-wme I2\n").unwrap();
    let err = agent
        .execute(&format!("load percepts -o {}", bad.display()))
        .unwrap_err();
    assert!(
        err.to_string().contains(":2: not a line of recorded input"),
        "{err}"
    );
    let err = agent
        .execute("load percepts -o /nonexistent/rusoar/percepts.txt")
        .unwrap_err();
    assert!(err.to_string().contains("Open file failed."), "{err}");
    // A replay that names an identifier it never made warns and goes on.
    let odd = temp("odd.txt");
    std::fs::write(
        &odd,
        "5\n1 -3 add-wme Z9 color red string\n1 -4 remove-wme\n",
    )
    .unwrap();
    agent
        .execute(&format!("load percepts -o {}", odd.display()))
        .unwrap();
    agent.run(1, RunUnit::Decisions).unwrap();
    let out = agent.take_output();
    assert!(
        out.contains("Warning: load percepts: no identifier Z9"),
        "{out}"
    );
    assert!(
        out.contains("Warning: load percepts: no WME -4 to remove"),
        "{out}"
    );
}
