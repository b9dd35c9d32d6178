from __future__ import annotations

import pytest

from j5aio import kit_power, power_hints


def test_the_kit_s_wiring_is_what_backends_read(monkeypatch: pytest.MonkeyPatch) -> None:
    # importing kit_power handed it over
    assert power_hints._wiring is kit_power.output_feeding
    monkeypatch.setattr(power_hints, "_wiring", None)
    assert power_hints.output_feeding("SR0ABC") is None  # nothing knows the wiring yet
    power_hints.use_wiring({"SR0ABC": 3}.get)
    assert power_hints.output_feeding("SR0ABC") == 3
    assert power_hints.output_feeding("SR0XYZ") is None
    assert "output L1" in power_hints.power_hint(power_hints.output_feeding("SR0ABC"))


def test_a_wiring_lookup_must_be_callable() -> None:
    with pytest.raises(TypeError, match="the wiring lookup must be a callable"):
        power_hints.use_wiring({"SR0ABC": 3})  # type: ignore[arg-type]
