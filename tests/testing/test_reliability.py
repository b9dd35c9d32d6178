"""Bounded runs of the reliability trials (the bench runs them at full size)."""

from __future__ import annotations

import pytest

from tests.testing.reliability_rig import (
    BACKEND_NAMES,
    bad_value_trials,
    cancellation_trials,
    fuzzed_reply_trials,
    open_rig,
    summarise,
)


@pytest.mark.parametrize("style", ["anyio", "asyncio"])
@pytest.mark.parametrize("name", BACKEND_NAMES)
async def test_r1_random_cancellations_leave_no_wrong_answer_or_stale_cache(
    name: str, style: str
) -> None:
    report = await cancellation_trials(name, style, 80, seed=7)  # type: ignore[arg-type]
    assert report.trials == 80
    assert (report.wrong_answers, report.mismatches, report.errors) == (0, 0, 0), report.details
    if style == "asyncio":
        assert report.cancelled > 0
    assert summarise([report, report])["trials"] == 160


async def test_open_rig_refuses_an_unknown_name() -> None:
    with pytest.raises(ValueError, match="no rig called 'kettle'"):
        async with open_rig("kettle"):
            pass  # pragma: no cover


@pytest.mark.parametrize("name", BACKEND_NAMES)
async def test_r4_bad_values_never_reach_the_wire(name: str) -> None:
    report = await bad_value_trials(name, 40, seed=3)
    assert report.trials >= 40
    assert report.refused > 0
    assert (report.reached_the_wire, report.foreign) == (0, 0), report.details


@pytest.mark.parametrize("name", BACKEND_NAMES)
async def test_r5_fuzzed_replies_raise_only_communication_errors(name: str) -> None:
    report = await fuzzed_reply_trials(name, 40, seed=11)
    assert report.trials == 40
    assert report.communication_errors > 0
    assert report.foreign == 0, report.details


async def test_fuzzed_reply_trials_refuse_an_unknown_name() -> None:
    with pytest.raises(ValueError, match="no rig called"):
        await fuzzed_reply_trials("kettle", 1)
