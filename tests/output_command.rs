//! `output` (Soar manual, ch. 9, `output`): its status listing and the settings 9.6 reports
//! as `NAME is VALUE`; the expected texts were observed on soar-sml 9.6.5 through
//! `ExecuteCommandLine`.

use rusoar::Agent;

fn out(i: &mut Agent, cmd: &str) -> String {
    i.source_text("t", cmd).unwrap();
    i.take_output()
}

#[test]
fn output_lists_its_status_and_reports_its_settings() {
    let mut i = Agent::default();
    let status = out(&mut i, "output");
    assert!(status.starts_with(
        "=======================================================\n-                   Output Status                     -\n"
    ));
    assert!(status.contains("Agent RHS write output                               on   \n"));
    assert!(status.contains("Warnings                                             on   \n"));
    for (cmd, said) in [
        ("output print-depth", "print-depth is 1"),
        ("output print-depth 3", "print-depth is now 3"),
        ("output print-depth", "print-depth is 3"),
        ("output warnings", "warnings is on"),
        ("output warnings off", "warnings is now off"),
    ] {
        assert_eq!(out(&mut i, cmd).trim_end(), said, "{cmd}");
    }
    assert_eq!(
        out(&mut i, "output agent-writes off").trim_end(),
        "agent-writes is now off"
    );
    assert!(out(&mut i, "output")
        .contains("Agent RHS write output                              off   \n"));
    assert!(i.source_text("t", "output bogus").is_err());
}

#[test]
fn agent_writes_off_silences_write_and_print_depth_sets_prints_default() {
    let mut i = Agent::default();
    out(&mut i, "watch 0");
    out(
        &mut i,
        "sp {w (state <s> ^superstate nil) --> (write |hello|) (<s> ^a <x>) (<x> ^b c)}",
    );
    out(&mut i, "output agent-writes off");
    assert!(!out(&mut i, "run 1").contains("hello"));
    out(&mut i, "init-soar");
    out(&mut i, "output agent-writes on");
    assert!(out(&mut i, "run 1").contains("hello"));
    let shallow = out(&mut i, "print s1");
    out(&mut i, "output print-depth 2");
    let deep = out(&mut i, "print s1");
    assert!(!shallow.contains("^b c"), "{shallow}");
    assert!(deep.contains("^b c"), "{deep}");
}
