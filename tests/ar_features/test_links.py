"""Links that admit a browser to the view: a socket without an allowed token is sent nothing."""

import time

import numpy as np
import pytest

from arteleop.ar_features.links import LinkGate, link_url
from tests.instruments.view_probe import ViewProbe


@pytest.fixture
def served():
    import viser

    server = viser.ViserServer(host="127.0.0.1", port=0, verbose=False)
    gate = LinkGate(server)
    server.scene.add_point_cloud("/cloud", np.zeros((4, 3), np.float32), (0, 255, 0))
    yield f"http://127.0.0.1:{server.get_port()}", gate
    server.stop()


def _received(url: str, settle_s: float = 0.5) -> int:
    """How many messages a socket to ``url`` is sent in ``settle_s``."""
    with ViewProbe(url) as probe:
        time.sleep(settle_s)
        return len(probe.messages())


def test_only_an_allowed_token_is_sent_the_scene(served) -> None:
    url, gate = served
    assert _received(f"{url}/any") == 0  # none allowed yet
    gate.allow({"good"})
    assert [_received(url), _received(f"{url}/bad"), _received(f"{url}/goodish")] == [0, 0, 0]
    assert _received(f"{url}/good") > 0


def test_a_socket_outlives_its_token_until_expelled(served) -> None:
    url, gate = served
    gate.allow({"first"})
    with ViewProbe(f"{url}/first") as first:
        time.sleep(0.3)
        (client_id,) = gate._tokens
        assert gate.token_of(client_id) == "first"
        gate.allow({"second"})
        assert _received(f"{url}/first") == 0  # new sockets need the new token
        assert gate.token_of(client_id) == "first"  # the open one stays
        gate.expel(keep="second")
        deadline = time.monotonic() + 5
        while gate.token_of(client_id) is not None and time.monotonic() < deadline:
            time.sleep(0.02)
        assert gate.token_of(client_id) is None
        assert first.messages()  # it had been sent the scene while allowed


def test_a_link_carries_the_token_to_the_socket_address() -> None:
    assert link_url("http://10.0.0.5:8080", "Ab-_9") == (
        "http://10.0.0.5:8080/?websocket=ws://10.0.0.5:8080/Ab-_9"
    )
