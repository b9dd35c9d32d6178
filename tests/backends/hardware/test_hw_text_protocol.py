from j5aio.backends.hardware.sr.v4.text_protocol import Identity
from tests.dataclass_twins import assert_like_generated


def test_the_identity_is_the_generated_dataclass() -> None:
    assert_like_generated(
        Identity,
        [
            (("PBv4B", "srABC", "4.4.2"), {}),
            ((), {"board_type": "MCv4B", "asset_tag": "srXYZ", "version": "4.5.0"}),
        ],
    )
    assert Identity("PBv4B", "srABC", "4.4") == Identity("PBv4B", "srABC", "4.4")
