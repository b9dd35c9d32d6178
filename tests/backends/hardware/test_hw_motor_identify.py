from j5aio.backends.hardware.sr.v4.motor_identify import MotorBoardIdentity
from tests.dataclass_twins import assert_like_generated


def test_the_identity_is_the_generated_dataclass() -> None:
    assert_like_generated(
        MotorBoardIdentity,
        [
            ((3, "3", None), {}),
            ((4, "4.5.0", "srABC"), {}),
            ((), {"generation": 4, "version": "4.4.1", "asset_tag": ""}),
        ],
    )
    assert MotorBoardIdentity(3, "3", None) != MotorBoardIdentity(4, "3", None)
