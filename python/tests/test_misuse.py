"""Misuse of rusoar.sml becomes a Python exception with a clear message, never a crash.
(The official module crashes or hangs on several of these, so they run on rusoar alone.)"""

import pytest

import rusoar
import rusoar.sml as sml

RULES = r"""
sp {propose (state <s> ^superstate nil) --> (<s> ^operator <o> +) (<o> ^name go)}
sp {apply (state <s> ^operator.name go ^io.output-link <ol>) --> (<ol> ^go <g>) (<g> ^n 1)}
"""

COUNT_FOREVER = r"""
sp {p*init (state <s> ^superstate nil -^n) --> (<s> ^operator <o> +) (<o> ^name init)}
sp {a*init (state <s> ^operator.name init) --> (<s> ^n 0)}
sp {p*inc (state <s> ^n <n>) --> (<s> ^operator <o> +) (<o> ^name inc ^n <n>)}
sp {a*inc (state <s> ^operator <o> ^n <n>) (<o> ^name inc ^n <n>) --> (<s> ^n <n> -) (<s> ^n (+ <n> 1))}
"""


@pytest.fixture
def agent():
    kernel = sml.Kernel.CreateKernelInNewThread()
    a = kernel.CreateAgent("a")
    a.ExecuteCommandLine(RULES)
    yield a
    kernel.Shutdown()


def test_callback_with_wrong_signature(agent):
    agent.RegisterForRunEvent(sml.smlEVENT_AFTER_DECISION_CYCLE, lambda: None, None)
    with pytest.raises(TypeError):
        agent.RunSelf(3)
    # The agent goes on once the handler is fixed.
    assert "decision" in agent.RunSelf(1)


def test_exception_inside_callback(agent):
    def boom(*args):
        raise ValueError("environment failed")

    agent.AddOutputHandler("go", boom, None)
    with pytest.raises(ValueError, match="environment failed"):
        agent.RunSelf(5)


def test_exception_in_rhs_function():
    kernel = sml.Kernel.CreateKernelInNewThread()
    kernel.AddRhsFunction("bad", lambda *a: 1 / 0, None)
    a = kernel.CreateAgent("a")
    a.ExecuteCommandLine("sp {x (state <s> ^superstate nil) --> (<s> ^v (exec bad))}")
    with pytest.raises(ZeroDivisionError):
        a.RunSelf(1)
    kernel.Shutdown()


def test_handler_not_callable(agent):
    with pytest.raises(TypeError, match="callable"):
        agent.RegisterForPrintEvent(sml.smlEVENT_PRINT, 42, None)


def test_wrong_event_number(agent):
    with pytest.raises(ValueError, match="not a run event"):
        agent.RegisterForRunEvent(sml.smlEVENT_PRINT, lambda *a: None, None)


def test_destroyed_wme_used_again(agent):
    w = agent.GetInputLink().CreateIntWME("x", 1)
    assert agent.DestroyWME(w)
    with pytest.raises(sml.SoarError, match="destroyed"):
        w.GetValueAsString()
    with pytest.raises(sml.SoarError, match="destroyed"):
        agent.Update(w, 2)


def test_update_with_wrong_type(agent):
    w = agent.GetInputLink().CreateIntWME("x", 1)
    with pytest.raises(TypeError):
        agent.Update(w, "text")


def test_calls_after_shutdown():
    kernel = sml.Kernel.CreateKernelInNewThread()
    a = kernel.CreateAgent("a")
    il = a.GetInputLink()
    kernel.Shutdown()
    for call in (lambda: a.RunSelf(1), lambda: a.ExecuteCommandLine("print s1"),
                 lambda: kernel.CreateAgent("b"), lambda: il.CreateIntWME("x", 1),
                 lambda: kernel.GetNumberAgents()):
        with pytest.raises(sml.SoarError, match="shut down"):
            call()


def test_destroyed_agent():
    kernel = sml.Kernel.CreateKernelInNewThread()
    a = kernel.CreateAgent("a")
    kernel.DestroyAgent(a)
    with pytest.raises(sml.SoarError, match="destroyed"):
        a.RunSelf(1)
    kernel.Shutdown()


def test_run_from_inside_a_callback(agent):
    agent.RegisterForRunEvent(sml.smlEVENT_AFTER_DECISION_CYCLE,
                              lambda e, d, a, p: a.RunSelf(1), None)
    with pytest.raises(RuntimeError, match="inside a callback"):
        agent.RunSelf(3)


def test_stop_self_from_a_callback(agent):
    count = []

    def stop(e, d, a, p):
        count.append(p)
        a.StopSelf()

    agent.RegisterForRunEvent(sml.smlEVENT_AFTER_DECISION_CYCLE, stop, None)
    agent.RunSelfForever()
    # The run stops within the next decision.
    assert 1 <= len(count) <= 2
    assert agent.GetRunState() == sml.sml_RUNSTATE_INTERRUPTED


def test_runs_release_the_gil(agent):
    import threading
    agent.ExecuteCommandLine("excise --all")
    agent.ExecuteCommandLine(COUNT_FOREVER)
    agent.ExecuteCommandLine("watch 0")
    ticks = []
    done = threading.Event()

    def tick():
        while not done.is_set():
            ticks.append(1)
            done.wait(0.001)

    t = threading.Thread(target=tick)
    t.start()
    agent.RunSelf(20000)
    done.set()
    t.join()
    assert len(ticks) > 1


# ---- the Pythonic layer ----

def test_pythonic_agent():
    with rusoar.Agent("py") as agent:
        agent.execute(RULES)
        pose = agent.add(agent.input_link, "pose")
        agent.add(pose, "x", 3)
        agent.add(pose, "y", 1.5)
        agent.add(agent.input_link, "name", "bot")
        assert [w.GetAttribute() for w in pose] == ["x", "y"]
        assert len(agent.input_link) == 2
        printed = []
        agent.on_print(printed.append)
        seen = []
        agent.on_output("go", lambda cmd: seen.append(cmd.GetParameterValue("n")))
        result = agent.run(2)
        assert result.decisions == 2 and result.stop == "LimitReached"
        assert seen == ["1"]
        assert [c.GetCommandName() for c in agent.commands()] == ["go"]
        assert "O: O1 (go)" in "".join(printed)


def test_soar_error_has_a_place(tmp_path):
    path = tmp_path / "bad.soar"
    path.write_text("sp {ok (state <s> ^superstate nil) --> (<s> ^a 1)}\n\nsp {bad (state <s> --> }\n")
    with rusoar.Agent() as agent:
        with pytest.raises(rusoar.SoarError) as err:
            agent.source(str(path))
        assert err.value.file.endswith("bad.soar")
        assert err.value.line == 3
        assert err.value.column > 1
        assert "Expected ^" in err.value.message


def test_pythonic_add_rejects_bad_values():
    with rusoar.Agent() as agent:
        with pytest.raises(TypeError):
            agent.add(agent.input_link, "flag", True)
        with pytest.raises(TypeError):
            agent.add(agent.input_link, "list", [1])


def test_failing_print_handler_does_not_stop_the_next_run(agent):
    calls = []

    def bad(*args):
        calls.append(1)
        raise RuntimeError("print handler failed")

    hid = agent.RegisterForPrintEvent(sml.smlEVENT_PRINT, bad, None)
    with pytest.raises(RuntimeError, match="print handler failed"):
        agent.RunSelf(2)
    agent.UnregisterForPrintEvent(hid)
    assert "2 decision cycles" in agent.RunSelf(2)
