import math
from datetime import timedelta

import anyio
import pytest

from j5aio.components import Note, Piezo, PiezoInterface

from .component_fakes import RecordingBackend


@pytest.mark.parametrize(
    ("duration", "expected"),
    [
        (0.5, timedelta(milliseconds=500)),
        (2, timedelta(seconds=2)),
        (timedelta(milliseconds=20), timedelta(milliseconds=20)),
    ],
)
async def test_buzz_sends_the_duration_as_a_timedelta(
    duration: float | timedelta,
    expected: timedelta,
) -> None:
    backend = RecordingBackend()
    await Piezo(1, backend).buzz(duration, 440.0)
    assert backend.calls == [("buzz", (1, expected, 440.0))]


async def test_buzz_sends_an_int_pitch_as_a_float() -> None:
    backend = RecordingBackend()
    await Piezo(0, backend).buzz(1, 440)
    [(_, (_, _, pitch))] = backend.calls
    assert type(pitch) is float
    assert pitch == 440.0


async def test_buzz_sends_a_note_as_the_note() -> None:
    backend = RecordingBackend()
    await Piezo(0, backend).buzz(1, Note.A6)
    [(_, (_, _, pitch))] = backend.calls
    assert pitch is Note.A6
    assert pitch == 1760.0


def test_note_values_are_those_of_j5() -> None:
    assert Note.C6 == 1047.0
    assert Note.B7 == 3951.1
    assert Note.C8 == 4186.0
    assert len(Note) == 15
    assert str(Note.D7) == "D7"


@pytest.mark.parametrize("duration", [True, "1", None, [1]])
async def test_buzz_refuses_a_duration_of_the_wrong_type(duration: object) -> None:
    backend = RecordingBackend()
    with pytest.raises(
        TypeError,
        match=r"^piezo duration must be a number of seconds greater than zero, "
        r"or a datetime.timedelta; got",
    ):
        await Piezo(0, backend).buzz(duration, Note.A6)  # type: ignore[arg-type]
    assert backend.calls == []


@pytest.mark.parametrize(
    "duration",
    [0, -1, 0.0, timedelta(0), timedelta(seconds=-1), 1e-9],
)
async def test_buzz_refuses_a_duration_that_is_not_positive(
    duration: float | timedelta,
) -> None:
    backend = RecordingBackend()
    with pytest.raises(ValueError, match=r"^piezo duration must be greater than zero; got"):
        await Piezo(0, backend).buzz(duration, Note.A6)
    assert backend.calls == []


@pytest.mark.parametrize("duration", [math.nan, math.inf, -math.inf, 1e20, 10**400])
async def test_buzz_refuses_a_duration_that_is_not_a_finite_time(duration: float) -> None:
    backend = RecordingBackend()
    with pytest.raises(ValueError, match=r"not a finite length of time"):
        await Piezo(0, backend).buzz(duration, Note.A6)
    assert backend.calls == []


@pytest.mark.parametrize("pitch", [True, "A6", None, "1760"])
async def test_buzz_refuses_a_pitch_of_the_wrong_type(pitch: object) -> None:
    backend = RecordingBackend()
    with pytest.raises(
        TypeError,
        match=r"^piezo pitch must be a frequency in hertz greater than zero \(an int or a "
        r"float\), or a Note; got",
    ):
        await Piezo(0, backend).buzz(1, pitch)  # type: ignore[arg-type]
    assert backend.calls == []


@pytest.mark.parametrize("pitch", [0, -440, 0.0, math.nan, math.inf, 10**400])
async def test_buzz_refuses_a_pitch_that_is_not_positive_and_finite(pitch: float) -> None:
    backend = RecordingBackend()
    with pytest.raises(ValueError, match=r"^piezo pitch must be .*; got"):
        await Piezo(0, backend).buzz(1, pitch)
    assert backend.calls == []


def test_verify_duration_checks_type_and_sign() -> None:
    Piezo.verify_duration(timedelta(seconds=1))
    with pytest.raises(TypeError, match=r"must be a datetime.timedelta; got 1 \(a int\)"):
        Piezo.verify_duration(1)  # type: ignore[arg-type]
    with pytest.raises(ValueError, match=r"greater than zero"):
        Piezo.verify_duration(timedelta(0))


def test_verify_pitch_checks_type_and_sign() -> None:
    Piezo.verify_pitch(Note.C6)
    Piezo.verify_pitch(1.5)
    Piezo.verify_pitch(300)
    with pytest.raises(TypeError):
        Piezo.verify_pitch(False)
    with pytest.raises(ValueError):
        Piezo.verify_pitch(-1.0)


async def test_buzz_without_blocking_does_not_sleep(monkeypatch: pytest.MonkeyPatch) -> None:
    sleeps: list[float] = []

    async def fake_sleep(delay: float) -> None:
        sleeps.append(delay)

    monkeypatch.setattr(anyio, "sleep", fake_sleep)
    await Piezo(0, RecordingBackend()).buzz(0.25, Note.C6)
    assert sleeps == []


async def test_blocking_buzz_sleeps_for_the_duration_after_the_backend_accepted(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    backend = RecordingBackend()
    events: list[object] = []

    async def fake_sleep(delay: float) -> None:
        events.append(("sleep", delay, len(backend.calls)))

    monkeypatch.setattr(anyio, "sleep", fake_sleep)
    await Piezo(0, backend).buzz(timedelta(milliseconds=250), Note.C6, blocking=True)
    assert events == [("sleep", 0.25, 1)]


async def test_blocking_buzz_waits_and_can_be_cancelled() -> None:
    backend = RecordingBackend()
    with anyio.move_on_after(0.01) as scope:
        await Piezo(0, backend).buzz(30, Note.C6, blocking=True)
    assert scope.cancelled_caught
    assert backend.names() == ["buzz"]


def test_identifier_and_interface() -> None:
    assert Piezo(3, RecordingBackend()).identifier == 3
    assert Piezo.interface_class() is PiezoInterface


@pytest.mark.parametrize(
    ("duration", "pitch", "what"),
    [
        (0.0004, 440, "duration"),
        (0.0005, 440, "duration"),
        (timedelta(microseconds=500), 440, "duration"),
        (0.1, 0.4, "pitch"),
        (0.1, 0.5, "pitch"),
    ],
)
async def test_buzz_refuses_a_note_that_rounds_to_nothing(
    duration: float | timedelta, pitch: float, what: str
) -> None:
    backend = RecordingBackend()
    with pytest.raises(ValueError, match=rf"^piezo {what} .* round"):
        await Piezo(0, backend).buzz(duration, pitch)
    assert backend.calls == []


@pytest.mark.parametrize(("duration", "pitch"), [(0.0006, 440), (0.1, 0.6), (0.0015, 1.5)])
async def test_buzz_sends_a_note_that_rounds_to_one_step_or_more(
    duration: float, pitch: float
) -> None:
    backend = RecordingBackend()
    await Piezo(0, backend).buzz(duration, pitch)
    assert len(backend.calls) == 1


async def test_buzz_uses_the_backends_steps() -> None:
    class CoarseBackend(RecordingBackend):
        DURATION_STEP = timedelta(milliseconds=10)
        PITCH_STEP = 100.0

    backend = CoarseBackend()
    with pytest.raises(ValueError, match=r"0\.01 s"):
        await Piezo(0, backend).buzz(0.004, 440)
    with pytest.raises(ValueError, match="100 Hz"):
        await Piezo(0, backend).buzz(0.5, 40)
    await Piezo(0, backend).buzz(0.006, 60)
    assert len(backend.calls) == 1


def test_the_default_duration_step_is_one_millisecond_read_from_class_or_backend() -> None:
    from_class, from_backend = PiezoInterface.DURATION_STEP, RecordingBackend().DURATION_STEP
    assert from_class == from_backend == timedelta(milliseconds=1)
    assert isinstance(from_class, timedelta)


def test_the_duration_alias_is_made_when_looked_up_and_other_names_are_missing() -> None:
    from j5aio.components import piezo

    assert piezo.Duration == int | float | timedelta
    assert {"Duration", "Note", "Pitch"} <= set(dir(piezo))
    with pytest.raises(AttributeError, match="has no attribute 'Durations'"):
        getattr(piezo, "Durations")  # noqa: B009 - a name type checkers know is missing


def test_note_made_on_first_lookup_is_the_same_enum_everywhere() -> None:
    import pickle
    from enum import Enum

    from j5aio import components
    from j5aio.components import _notes, piezo

    assert piezo.Note is _notes.Note is components.Note is Note
    assert issubclass(Note, float) and issubclass(Note, Enum)
    # found, documented and pickled under the name programs import it by
    assert (Note.__module__, Note.__qualname__) == ("j5aio.components.piezo", "Note")
    assert pickle.loads(pickle.dumps(Note.A6)) is Note.A6
    assert str(Note.C8) == "C8" and Note.A6 == 1760.0 and len(Note) == 15
    assert piezo.Pitch == int | float | Note
    assert "Note" in vars(piezo) and "Pitch" in vars(piezo)  # made once, then kept


async def test_a_pitch_that_is_a_float_enum_but_not_a_note_is_sent_as_a_float() -> None:
    from enum import Enum

    class Other(float, Enum):
        LA = 440.0

    backend = RecordingBackend()
    await Piezo(0, backend).buzz(1, Other.LA)
    [(_, (_, _, pitch))] = backend.calls
    assert type(pitch) is float
    assert pitch == 440.0
