"""The private names of playground that rse's adapters use
(rse._adapters.private) are all in the installed release: a release that
drops one fails here, by name and with the versions rse checked, not deep
in a training run."""

import pytest

from rse._adapters import private


@pytest.mark.parametrize("framework", ['playground'])
def test_the_private_names_rse_uses_are_there(framework: str) -> None:
    private.verify(framework)
