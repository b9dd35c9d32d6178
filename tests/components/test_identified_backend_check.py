"""A component is given its board's backend as it is, and refuses one without its interface."""

from __future__ import annotations

import pytest

from j5aio.components.led import LED, LEDInterface
from j5aio.components.motor import Motor


class JustLEDs(LEDInterface):
    async def get_led_state(self, identifier: int) -> bool:
        return False

    async def set_led_state(self, identifier: int, state: bool) -> None:
        return None


def test_a_backend_with_the_interface_is_taken_as_is() -> None:
    backend = JustLEDs()
    led = LED(0, backend)
    assert led._backend is backend


def test_a_backend_without_the_interface_is_refused_by_name() -> None:
    message = "Motor needs a backend that implements MotorInterface, but JustLEDs does not"
    with pytest.raises(TypeError, match=message):
        Motor(0, JustLEDs())  # type: ignore[arg-type]


def test_the_base_class_is_public_and_its_old_private_home_still_imports() -> None:
    import j5aio.components
    from j5aio.components import _identified, identified

    assert j5aio.components.IdentifiedComponent is identified.IdentifiedComponent
    assert j5aio.components.checked_backend is identified.checked_backend
    assert _identified.IdentifiedComponent is identified.IdentifiedComponent
    assert _identified.checked_backend is identified.checked_backend
    assert issubclass(LED, identified.IdentifiedComponent)
