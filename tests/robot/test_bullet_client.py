import pybullet as p

from arteleop.robot.bullet_client import KeptBulletClient


def test_the_kept_client_binds_each_function_once_to_its_own_world() -> None:
    a, b = KeptBulletClient(p.DIRECT), KeptBulletClient(p.DIRECT)
    try:
        assert a.stepSimulation is a.stepSimulation
        a.createMultiBody(1.0, a.createCollisionShape(p.GEOM_SPHERE, radius=0.1))
        assert (a.getNumBodies(), b.getNumBodies()) == (1, 0)
    finally:
        b.disconnect()


def test_a_disconnected_client_forgets_its_world_though_a_new_one_takes_its_id() -> None:
    a = KeptBulletClient(p.DIRECT)
    assert a.isConnected()
    old_id = a._client
    a.disconnect()
    b = KeptBulletClient(p.DIRECT)
    try:
        assert b._client == old_id, "premise: PyBullet gives the freed id to the next client"
        assert not a.isConnected()
        assert b.isConnected()
    finally:
        b.disconnect()
