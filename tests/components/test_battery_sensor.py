from j5aio.components import BatterySensor, BatterySensorInterface

from .component_fakes import RecordingBackend


async def test_reads_voltage_and_current() -> None:
    backend = RecordingBackend()
    backend.voltage = 12.1
    backend.current = 0.4
    sensor = BatterySensor(0, backend)

    assert await sensor.get_voltage() == 12.1
    assert await sensor.get_current() == 0.4
    assert backend.calls == [
        ("get_battery_sensor_voltage", (0,)),
        ("get_battery_sensor_current", (0,)),
    ]


def test_identifier_and_interface() -> None:
    assert BatterySensor(2, RecordingBackend()).identifier == 2
    assert BatterySensor.interface_class() is BatterySensorInterface
