"""Links that admit a browser to the view: a socket without an allowed token is sent nothing."""

import numpy as np
import pytest

from arteleop.ar_features.links import LinkGate, link_url
from tests.instruments.view_probe import ViewProbe, admitted, refused, until


@pytest.fixture
def served():
    import viser

    server = viser.ViserServer(host="127.0.0.1", port=0, verbose=False)
    gate = LinkGate(server)
    server.scene.add_point_cloud("/cloud", np.zeros((4, 3), np.float32), (0, 255, 0))
    yield f"http://127.0.0.1:{server.get_port()}", gate
    server.stop()


def test_only_an_allowed_token_is_sent_the_scene(served) -> None:
    url, gate = served
    assert refused(f"{url}/any", gate)  # none allowed yet
    gate.allow({"good"})
    assert all(refused(u, gate) for u in (url, f"{url}/bad", f"{url}/goodish"))
    assert admitted(f"{url}/good")


def test_a_socket_outlives_its_token_until_expelled(served) -> None:
    url, gate = served
    gate.allow({"first"})
    with ViewProbe(f"{url}/first") as first:
        assert until(lambda: gate.count("first") == 1)
        gate.allow({"second"})
        assert refused(f"{url}/first", gate)  # new sockets need the new token
        assert gate.count("first") == 1  # the open one stays
        gate.expel(keep={"second"})
        assert until(lambda: gate.count("first") == 0)
        assert first.messages()  # it had been sent the scene while allowed


def test_a_link_carries_the_token_to_the_socket_address() -> None:
    assert link_url("http://10.0.0.5:8080", "Ab-_9") == (
        "http://10.0.0.5:8080/?websocket=ws://10.0.0.5:8080/Ab-_9"
    )
