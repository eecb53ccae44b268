"""Links that admit a browser to the view: a socket without an allowed token is sent nothing."""

import numpy as np
import pytest

from arteleop.ar_features import OperatorView, ViewConfig
from arteleop.ar_features.links import BAD_LINK_PAGE, LinkGate, link_url
from arteleop.errors import ConfigurationError
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


def test_behind_a_proxy_that_adds_tls_the_link_opens_a_secure_socket() -> None:
    # A secure page may open no plain socket: ws:// under https never connected.
    assert link_url("https://study.example.org", "Ab-_9") == (
        "https://study.example.org/?websocket=wss://study.example.org/Ab-_9"
    )


@pytest.mark.parametrize(
    "url", ["ftp://proxy", "study.example.org", "https://", "https://proxy/study",
            "https://proxy:0", "https://proxy:99999", "https://proxy/?a=1", "https://u:p@proxy",
            "https://:p@proxy"],
)  # fmt: skip
def test_a_public_url_browsers_cannot_be_sent_to_is_refused(url: str) -> None:
    with pytest.raises(ConfigurationError) as refusal:
        ViewConfig(public_url=url)
    assert str(refusal.value) == (
        f"--public-url {url}: expected http://HOST[:PORT] or https://HOST[:PORT], the address "
        "participants open (a reverse proxy's or a tunnel's), with nothing after it: the proxy "
        "forwards every path, the page's and its socket's, to the server."
    )


def test_a_public_url_is_read_as_browsers_read_it() -> None:
    # Browsers lowercase the scheme and drop an empty query or fragment: the socket's scheme
    # is derived from the page's, so it must be read the same way.
    assert ViewConfig(public_url=" HTTPS://Study.example.org:8443/? ").public_url == (
        "https://Study.example.org:8443"
    )


def test_links_name_the_public_url_and_admit_through_it() -> None:
    # This machine's other name stands in for a proxy's: the link must name it, and work.
    view_config = ViewConfig(port=0, links=True, public_url="http://localhost:1/")
    with OperatorView(view_config) as view:
        assert view.url == "http://localhost:1"
        link = view.link("tok")
        assert link == "http://localhost:1/?websocket=ws://localhost:1/tok"
        view.gate.allow({"tok"})
        socket_url = link.split("websocket=")[1].replace(":1/", f":{view.server.get_port()}/")
        assert admitted(socket_url)


def _get(url: str) -> tuple[int, str]:
    import urllib.error
    import urllib.request

    try:
        with urllib.request.urlopen(url, timeout=10) as answer:
            return answer.status, answer.read().decode()
    except urllib.error.HTTPError as refused_page:
        return refused_page.code, refused_page.read().decode()


def test_a_link_without_an_allowed_token_gets_a_page_that_says_so(served) -> None:
    """Not viser's page, which retries its socket for ever beside a developer panel: a page
    that says the link opens no session; the page's own files are served to any address."""
    url, gate = served
    gate.allow({"good"})
    socket = "ws" + url.removeprefix("http")
    status, page = _get(link_url(url, "good"))
    assert status == 200 and "viser" in page.lower()
    for bad in (link_url(url, "stale"), f"{url}/", f"{url}/index.html?websocket={socket}/goodish",
                f"{url}/./", f"{url}/%69ndex.html"):  # fmt: skip
        status, page = _get(bad)
        assert (status, page) == (403, BAD_LINK_PAGE), bad
    assert _get(f"{url}/robots.txt")[0] == 404  # viser's answer to any other path stands
    gate.allow({"stale"})
    assert _get(link_url(url, "stale"))[0] == 200
