import pytest

from j5aio.backends.hardware.sr.v4 import servo_fw4_codec as codec
from j5aio.errors import CommunicationError, UnexpectedReplyError, UnsupportedFirmwareError
from tests.dataclass_twins import assert_like_generated

BOARD = "Servo Board"
SR = codec.FIRMWARES["4.3"]
SB = codec.FIRMWARES["4.4"]


def test_firmware_table() -> None:
    assert (SR.servo_count, SR.min_pulse, SR.max_pulse) == (12, 500, 4000)
    assert (SB.servo_count, SB.min_pulse, SB.max_pulse) == (8, 300, 4000)


def test_identity_is_parsed() -> None:
    identity = codec.parse_identity(BOARD, b"Student Robotics:SBv4B:srABC:4.3")
    assert identity == codec.Identity("Student Robotics", "SBv4B", "srABC", "4.3")


@pytest.mark.parametrize(
    ("reply", "why"),
    [
        (b"Student Robotics:PBv4B:srABC:4.4.2", "'PBv4B' board"),
        (b"Student Robotics:SBv4B:srABC", "not 'Student Robotics"),
        (b"Student Robotics:SBv4B:srABC:four", "not a dotted number"),
        (b"Student Robotics:SBv4B:sr\xff:4.3", "not ASCII"),
        (b"ACK", "not 'Student Robotics"),
    ],
)
def test_bad_identities_name_board_command_and_reply(reply: bytes, why: str) -> None:
    with pytest.raises(UnexpectedReplyError, match=why) as info:
        codec.parse_identity(BOARD, reply)
    assert "Servo Board answered '*IDN?'" in str(info.value)
    assert repr(reply) in str(info.value)


def test_firmware_for_names_found_and_supported() -> None:
    assert codec.firmware_for(BOARD, "4.4") is SB
    with pytest.raises(UnsupportedFirmwareError) as info:
        codec.firmware_for(BOARD, "4.4", ("4.3",))
    assert (info.value.found, info.value.supported) == ("4.4", ("4.3",))
    with pytest.raises(UnsupportedFirmwareError):
        codec.firmware_for(BOARD, "4.5")


def test_encoders() -> None:
    assert codec.encode_set(SR, 11, 4000) == b"SERVO:11:SET:4000\n"
    assert codec.encode_set(SB, 7, 300) == b"SERVO:7:SET:300\n"
    assert codec.encode_get(SR, 0) == b"SERVO:0:GET?\n"
    assert codec.encode_disable(SR, 3) == b"SERVO:3:DISABLE\n"


@pytest.mark.parametrize(
    ("firmware", "servo", "pulse", "error"),
    [
        (SR, 12, 1500, ValueError),
        (SB, 8, 1500, ValueError),
        (SR, -1, 1500, ValueError),
        (SR, True, 1500, TypeError),
        (SR, 1.0, 1500, TypeError),
        (SR, 0, 499, ValueError),
        (SB, 0, 299, ValueError),
        (SR, 0, 4001, ValueError),
        (SR, 0, 1500.0, TypeError),
        (SR, 0, False, TypeError),
    ],
)
def test_encode_set_refuses(
    firmware: codec.Firmware, servo: object, pulse: object, error: type[Exception]
) -> None:
    with pytest.raises(error):
        codec.encode_set(firmware, servo, pulse)  # type: ignore[arg-type]


def test_ack_and_nack() -> None:
    codec.check_ack(BOARD, b"*RESET\n", b"ACK")
    refused = r"refused 'SERVO:1:SET:9': Invalid servo setpoint"
    with pytest.raises(CommunicationError, match=refused):
        codec.check_ack(BOARD, b"SERVO:1:SET:9\n", b"NACK:Invalid servo setpoint")
    with pytest.raises(UnexpectedReplyError, match="not 'ACK'"):
        codec.check_ack(BOARD, b"*RESET\n", b"ACK ")


def test_nack_is_not_an_unexpected_reply() -> None:
    with pytest.raises(CommunicationError) as info:
        codec.parse_pulse(BOARD, b"SERVO:1:GET?\n", b"NACK:Invalid servo number", SR)
    assert not isinstance(info.value, UnexpectedReplyError)
    assert "Servo Board" in str(info.value)


def test_parse_pulse() -> None:
    assert codec.parse_pulse(BOARD, b"c", b"0", SR) is None
    assert codec.parse_pulse(BOARD, b"c", b"1495", SR) == 1495
    assert codec.parse_pulse(BOARD, b"c", b"500", SR) == 500
    assert codec.parse_pulse(BOARD, b"c", b"300", SB) == 300
    assert codec.parse_pulse(BOARD, b"c", b"4000", SB) == 4000


@pytest.mark.parametrize(
    ("reply", "firmware"),
    [
        (b"1497", SR),
        (b"495", SR),
        (b"295", SB),
        (b"4005", SR),
        (b"-5", SR),
        (b"01500", SR),
        (b"", SR),
        (b"1500 ", SR),
        (b"+1500", SR),
        (b"12345678901", SR),
    ],
)
def test_parse_pulse_is_strict(reply: bytes, firmware: codec.Firmware) -> None:
    with pytest.raises(UnexpectedReplyError, match="answered 'c'"):
        codec.parse_pulse(BOARD, b"c", reply, firmware)


def test_parse_milli_and_status() -> None:
    assert codec.parse_milli(BOARD, codec.READ_VOLTAGE, b"5512") == 5.512
    assert codec.parse_milli(BOARD, codec.READ_CURRENT, b"0") == 0.0
    for bad in (b"-1", b"65536", b"1.5", b""):
        with pytest.raises(UnexpectedReplyError):
            codec.parse_milli(BOARD, codec.READ_CURRENT, bad)
    assert codec.parse_status(BOARD, b"0:1") == codec.Status(watchdog_failed=False, power_good=True)
    assert codec.parse_status(BOARD, b"1:0") == codec.Status(watchdog_failed=True, power_good=False)
    for bad in (b"0", b"0:1:0", b"2:1", b"0:", b"true:false"):
        with pytest.raises(UnexpectedReplyError, match=r"\*STATUS\?"):
            codec.parse_status(BOARD, bad)


def test_position_scaling_follows_sr_robot3() -> None:
    limits = codec.DEFAULT_PULSE_LIMITS
    assert codec.pulse_for_position(-1, limits) == 1000
    assert codec.pulse_for_position(1, limits) == 2000
    assert codec.pulse_for_position(0, limits) == 1500
    assert codec.pulse_for_position(0.333, limits) == 1666  # truncated
    assert codec.pulse_for_position(0.5, (350, 1980)) == 1572
    with pytest.raises(ValueError, match="between -1 and 1"):
        codec.pulse_for_position(1.01, limits)
    assert codec.position_for_pulse(1665, limits) == 0.33
    assert codec.position_for_pulse(1000, limits) == -1.0
    assert codec.position_for_pulse(2500, limits) == 1.0
    assert codec.position_for_pulse(500, limits) == -1.0


def test_the_servo_check_names_what_is_allowed() -> None:
    firmware = next(iter(codec.FIRMWARES.values()))
    codec.check_servo(firmware, firmware.servo_count - 1)
    with pytest.raises(ValueError, match=f"servos 0 to {firmware.servo_count - 1}"):
        codec.check_servo(firmware, firmware.servo_count)
    with pytest.raises(TypeError, match="must be an int"):
        codec.check_servo(firmware, True)


def test_the_records_are_the_generated_dataclasses() -> None:
    assert_like_generated(
        codec.Firmware,
        [
            (("4.3", "Student Robotics", 12, 500, 4000), {}),
            (
                ("4.4", "SourceBots"),
                {
                    "servo_count": 8,
                    "min_pulse": 300,
                    "max_pulse": 4000,
                    "default_limits": (350, 1980),
                },
            ),
        ],
    )
    assert codec.Firmware("9", "x", 1, 2, 3).default_limits == codec.DEFAULT_PULSE_LIMITS
    assert_like_generated(
        codec.Identity,
        [
            (("Student Robotics", "SBv4B", "srABC", "4.3"), {}),
            ((), {"manufacturer": "m", "board_type": "b", "asset_tag": "a", "version": "v"}),
        ],
    )
    assert_like_generated(
        codec.Status, [((False, True), {}), ((), {"watchdog_failed": True, "power_good": False})]
    )
