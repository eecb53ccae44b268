"""A PyBullet client that keeps the functions it hands out."""

from __future__ import annotations

from typing import Any

from pybullet_utils.bullet_client import BulletClient


class KeptBulletClient(BulletClient):
    """:class:`BulletClient` that binds each PyBullet function to its client once.

    ``BulletClient`` looks every function up in the module and wraps it anew at each call:
    about 1.5 us, at the physics rate and a dozen times per observation of the site. The
    function it hands out is the same each time (the module's, with this client's id), so it is
    kept on the instance, where the next lookup finds it without ``__getattr__``; until the
    client disconnects, after which a new client may be given the same id.
    """

    def __getattr__(self, name: str) -> Any:
        kept = self.__dict__.setdefault("_kept", set())
        attribute = super().__getattr__(name)
        if name == "disconnect":  # the parent has marked the client gone (its id is -1 now)
            for kept_name in kept:
                del self.__dict__[kept_name]
            kept.clear()
        else:
            self.__dict__[name] = attribute
            kept.add(name)
        return attribute
