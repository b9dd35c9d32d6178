import math

import pytest

from j5aio.components import Motor, MotorInterface, MotorSpecialState, check_motor_state

from .component_fakes import RecordingBackend

ALLOWED = r"a float between -1 and 1, or MotorSpecialState\.BRAKE / COAST"


@pytest.mark.parametrize("power", [-1.0, -0.25, 0.0, 0.5, 1.0])
async def test_set_power_sends_a_power_in_range(power: float) -> None:
    backend = RecordingBackend()
    motor = Motor(1, backend)

    await motor.set_power(power)
    assert await motor.get_power() == power
    assert backend.calls == [("set_motor_state", (1, power)), ("get_motor_state", (1,))]


@pytest.mark.parametrize("power", [-1, 0, 1])
async def test_set_power_accepts_an_int_and_sends_a_float(power: int) -> None:
    backend = RecordingBackend()
    await Motor(0, backend).set_power(power)
    [(_, (_, sent))] = backend.calls
    assert sent == power
    assert type(sent) is float


@pytest.mark.parametrize("state", list(MotorSpecialState))
async def test_set_power_sends_a_special_state(state: MotorSpecialState) -> None:
    backend = RecordingBackend()
    motor = Motor(0, backend)
    await motor.set_power(state)
    assert await motor.get_power() is state
    assert backend.calls[0] == ("set_motor_state", (0, state))


@pytest.mark.parametrize("power", [1.5, -1.01, 2, math.inf, -math.inf, 10**400])
async def test_set_power_refuses_a_power_out_of_range(power: float) -> None:
    backend = RecordingBackend()
    with pytest.raises(ValueError, match=f"^motor power must be {ALLOWED}; got "):
        await Motor(0, backend).set_power(power)
    assert backend.calls == []


async def test_power_error_message_shows_the_value() -> None:
    with pytest.raises(ValueError) as info:
        await Motor(0, RecordingBackend()).set_power(1.5)
    assert str(info.value) == (
        "motor power must be a float between -1 and 1, or MotorSpecialState.BRAKE / COAST; "
        "got 1.5"
    )


async def test_set_power_refuses_nan() -> None:
    backend = RecordingBackend()
    with pytest.raises(ValueError, match=r"got nan"):
        await Motor(0, backend).set_power(math.nan)
    assert backend.calls == []


@pytest.mark.parametrize("power", [True, False, "0.5", None, [0.5], 0.5j])
async def test_set_power_refuses_a_power_of_the_wrong_type(power: object) -> None:
    backend = RecordingBackend()
    with pytest.raises(TypeError, match=f"^motor power must be {ALLOWED}; got .*\\(a "):
        await Motor(0, backend).set_power(power)  # type: ignore[arg-type]
    assert backend.calls == []


def test_identifier_and_interface() -> None:
    assert Motor(5, RecordingBackend()).identifier == 5
    assert Motor.interface_class() is MotorInterface


def test_check_motor_state_names_the_value_it_checks() -> None:
    assert check_motor_state(MotorSpecialState.BRAKE) is MotorSpecialState.BRAKE
    assert check_motor_state(-1) == -1.0
    with pytest.raises(ValueError, match=f"^safe_state must be {ALLOWED}; got 3$"):
        check_motor_state(3, name="safe_state")
    with pytest.raises(TypeError, match=r"^safe_state must be"):
        check_motor_state(None, name="safe_state")
