"""Where the view can be served: checked before viser starts, which would otherwise retry
ports forever on a host it cannot bind."""

from __future__ import annotations

import errno
import ipaddress
import socket
from dataclasses import dataclass

import psutil

from arteleop.errors import ArteleopError


class ViewHostError(ArteleopError):
    """The view cannot be served on the host asked for."""


@dataclass(frozen=True)
class HostCheck:
    """What binding ``host`` means.

    Attributes:
        loopback: Only this machine can connect.
        addresses: Addresses to open the view at, for the user: for every interface (0.0.0.0,
            ::) those other machines can reach, loopback only if there are none.
    """

    loopback: bool
    addresses: tuple[str, ...]


def check_port(port: int) -> None:
    """Raise :class:`ViewHostError` unless ``port`` is a TCP port number (0: any free one)."""
    if not 0 <= port <= 65535:
        raise ViewHostError(f"--port {port}: expected a TCP port, 0-65535 (0: any free one).")


def check_host(host: str, port: int = 0) -> HostCheck:
    """Resolve ``host`` and try binding it; raise :class:`ViewHostError` if it cannot be, or,
    given a ``port``, if that port is no port or is taken there."""
    check_port(port)
    try:
        infos = socket.getaddrinfo(host, None, type=socket.SOCK_STREAM)
    except OSError as err:
        raise ViewHostError(
            f"--host {host}: not a name or address of this machine ({err.strerror}). Use "
            "127.0.0.1 (this machine only) or an address of one of its network interfaces."
        ) from None
    family, _, _, _, address = infos[0]
    ip = address[0]
    if (err := _bind(family, ip, 0)) is not None:
        raise ViewHostError(
            f"--host {host}: this machine cannot serve on {ip} ({err.strerror}). Use "
            "127.0.0.1 (this machine only) or an address of one of its network interfaces."
        )
    if port and (err := _bind(family, ip, port)) is not None:
        if err.errno in (errno.EACCES, errno.EPERM):
            raise ViewHostError(
                f"--port {port}: this user may not serve on it ({err.strerror}; ports below "
                "1024 are the system's). Give a port from 1024 (0: any free one)."
            )
        raise ViewHostError(
            f"--port {port}: taken on {ip} ({err.strerror}). Stop what serves there, or give "
            "another port (0: any free one)."
        )
    unspecified = ipaddress.ip_address(ip).is_unspecified
    loopback = ipaddress.ip_address(ip).is_loopback
    addresses: tuple[str, ...] = (ip,)
    if unspecified:  # every interface: name those other machines can reach
        loopback_ip = "::1" if family == socket.AF_INET6 else "127.0.0.1"
        addresses = _reachable(family) or (loopback_ip,)
    return HostCheck(loopback, addresses)


ROUTE_PROBES = {socket.AF_INET: "198.51.100.1", socket.AF_INET6: "2001:db8::1"}
"""Documentation addresses (RFC 5737, RFC 3849): a UDP socket connected to one sends nothing,
but takes the address of the interface this machine would reach other networks from."""


def _reachable(family: socket.AddressFamily) -> tuple[str, ...]:
    """This machine's interfaces' addresses in ``family`` that other machines can reach, the
    one it reaches other networks from first; loopback, link-local and down ones left out. Not its
    name's: Debian and Ubuntu give it 127.0.1.1, which no other machine reaches."""
    up = {name for name, stats in psutil.net_if_stats().items() if stats.isup}
    found = {
        ipaddress.ip_address(a.address.split("%")[0])  # an IPv6 address's zone
        for name, nic in psutil.net_if_addrs().items()
        if name in up
        for a in nic
        if a.family == family
    }
    ips = sorted(str(a) for a in found if not (a.is_loopback or a.is_link_local))
    with socket.socket(family, socket.SOCK_DGRAM) as probe:
        try:
            probe.connect((ROUTE_PROBES[family], 9))
            route = probe.getsockname()[0]
        except OSError:  # no route out: a lab network without a gateway, say
            route = None
    return tuple(sorted(ips, key=lambda a: a != route))


def _bind(family: socket.AddressFamily, ip: str, port: int) -> OSError | None:
    """Why ``(ip, port)`` cannot be bound, None if it can."""
    with socket.socket(family, socket.SOCK_STREAM) as probe:
        # As the server binds: a port that a server just stopped left in TIME_WAIT is free.
        probe.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)
        try:
            probe.bind((ip, port))
        except OSError as err:
            return err
    return None
