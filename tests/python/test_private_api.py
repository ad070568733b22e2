"""rse._adapters.private: the list of the frameworks' private names the
adapters use, and the checks that fail clearly when a release drops one.
Each framework's own venv verifies its list (tests/*/test_private_api.py,
make test-frameworks); here, Gymnasium's (installed in make test's venv)
and the mechanism itself, on a stand-in framework."""

from __future__ import annotations

import sys
import types

import pytest

from rse._adapters import private


def test_gymnasiums_private_names_are_there() -> None:
    private.verify("gymnasium")


def test_every_framework_lists_its_checked_versions() -> None:
    for name, framework in private.FRAMEWORKS.items():
        assert framework.checked, name
        assert private.uses(name), f"{name} is listed but uses nothing"
    assert {u.framework for u in private.USES} == set(private.FRAMEWORKS)


@pytest.fixture
def stand_in(monkeypatch: pytest.MonkeyPatch) -> type:
    """A framework "fakefw" whose class ``Thing`` sets ``self._kept`` and
    no longer has ``_gone``, listed as two private uses."""
    module = types.ModuleType("fakefw")
    exec("class Thing:\n    _kept = 1\n", module.__dict__)
    monkeypatch.setitem(sys.modules, "fakefw", module)
    monkeypatch.setitem(private.FRAMEWORKS, "fakefw", private.Framework("fakefw-dist", ("9.9",)))
    uses = (
        private.Use("fakefw", "fakefw:Thing", "_kept", "rse.fake.kept", "the kept thing"),
        private.Use("fakefw", "fakefw:Thing", "_gone", "rse.fake.gone", "the gone thing", instance=True),
    )
    monkeypatch.setattr(private, "USES", private.USES + uses)
    private._owner_class.cache_clear()
    return module.Thing


def test_a_name_gone_is_named_with_the_versions(stand_in: type) -> None:
    with pytest.raises(private.PrivateApiError) as caught:
        private.verify("fakefw")
    message = str(caught.value)
    assert "fakefw-dist (installed: not installed; rse checked 9.9)" in message, message
    assert "fakefw.Thing._gone is gone: rse.fake.gone uses it for the gone thing" in message, message
    assert "_kept" not in message, message


def test_checked_access_reads_writes_and_refuses(stand_in: type) -> None:
    thing = stand_in()
    assert private.getattr_checked(thing, "_kept", "fakefw") == 1
    private.setattr_checked(thing, "_kept", 2, "fakefw")
    assert thing._kept == 2
    with pytest.raises(private.PrivateApiError, match="fakefw.Thing._gone is gone"):
        private.setattr_checked(thing, "_gone", 3, "fakefw")
    assert not hasattr(thing, "_gone"), "nothing set when the framework lacks the name"
    with pytest.raises(AssertionError, match="not in rse._adapters.private.USES"):
        private.getattr_checked(thing, "_unlisted", "fakefw")


def test_an_unknown_framework_is_refused() -> None:
    with pytest.raises(ValueError, match="^framework: 'nope'"):
        private.verify("nope")
