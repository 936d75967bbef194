"""Fixtures of the differential suite: each SML-surface test runs once with the official
kernel's `soar_sml` and once with `rusoar.sml`; `both` runs a client script with each and
hands back the two transcripts, which must be equal."""

import importlib

import pytest

MODULES = ["soar_sml", "rusoar.sml"]


def _load(name):
    try:
        return importlib.import_module(name)
    except ImportError:
        pytest.skip("%s is not installed" % name)


@pytest.fixture(params=MODULES)
def sml(request):
    """The SML module under test (parametrized over both)."""
    return _load(request.param)


@pytest.fixture
def both():
    """Runs `script(sml, log)` with each module; returns the logs of both."""

    def run(script):
        logs = []
        for name in MODULES:
            module = _load(name)
            kernel = module.Kernel.CreateKernelInNewThread()
            log = []
            try:
                script(module, kernel, log)
            finally:
                kernel.Shutdown()
            logs.append(log)
        return logs

    return run
