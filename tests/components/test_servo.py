import math

import pytest

from j5aio.components import Servo, ServoInterface

from .component_fakes import RecordingBackend


@pytest.mark.parametrize("position", [-1.0, 0.0, 0.3, 1.0, None])
async def test_set_position_sends_the_position(position: float | None) -> None:
    backend = RecordingBackend()
    servo = Servo(2, backend)
    backend.servo = 0.9

    await servo.set_position(position)
    assert await servo.get_position() == position
    assert backend.calls == [
        ("set_servo_position", (2, position)),
        ("get_servo_position", (2,)),
    ]


async def test_set_position_accepts_an_int_and_sends_a_float() -> None:
    backend = RecordingBackend()
    await Servo(0, backend).set_position(-1)
    [(_, (_, sent))] = backend.calls
    assert type(sent) is float
    assert sent == -1.0


@pytest.mark.parametrize("position", [1.0001, -2, math.nan, math.inf])
async def test_set_position_refuses_a_position_out_of_range(position: float) -> None:
    backend = RecordingBackend()
    with pytest.raises(
        ValueError,
        match=r"^servo position must be a float between -1 and 1, or None \(unpowered\); got",
    ):
        await Servo(0, backend).set_position(position)
    assert backend.calls == []


@pytest.mark.parametrize("position", [True, "0", b"1", object()])
async def test_set_position_refuses_a_position_of_the_wrong_type(position: object) -> None:
    backend = RecordingBackend()
    with pytest.raises(TypeError, match=r"^servo position must be .* got"):
        await Servo(0, backend).set_position(position)  # type: ignore[arg-type]
    assert backend.calls == []


def test_identifier_and_interface() -> None:
    assert Servo(11, RecordingBackend()).identifier == 11
    assert Servo.interface_class() is ServoInterface
