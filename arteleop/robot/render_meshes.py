"""Decimated copies of the robot's visual meshes, for fast CPU rendering.

PyBullet's TinyRenderer cost grows with the triangle count: Baxter's COLLADA meshes hold about
270k triangles and a 640x480 frame takes 70-130 ms. Quadric decimation (open3d) to a fixed
budget per mesh keeps the silhouette the head camera sees at a fraction of the cost.
"""

from __future__ import annotations

import os
import tempfile
from pathlib import Path

import numpy as np


def decimated_mesh(source: Path, target_triangles: int, out_dir: Path) -> Path:
    """Return an OBJ copy of ``source`` with at most ``target_triangles`` triangles.

    The file is written once into ``out_dir`` and reused. Geometry is in the source's units
    after COLLADA unit scaling, i.e. metres, in the mesh's own frame.
    """
    out = out_dir / f"{source.stem}-{target_triangles}.obj"
    if out.is_file():
        return out
    # 3 s to import between them (open3d pulls in dash and IPython): only on a cache miss.
    import open3d as o3d
    import trimesh

    mesh = trimesh.load(source, force="mesh")
    # COLLADA stores a vertex per face corner; quadric decimation needs shared vertices.
    mesh.merge_vertices()
    o3 = o3d.geometry.TriangleMesh(
        o3d.utility.Vector3dVector(np.asarray(mesh.vertices)),
        o3d.utility.Vector3iVector(np.asarray(mesh.faces)),
    )
    if len(mesh.faces) > target_triangles:
        o3 = o3.simplify_quadric_decimation(target_number_of_triangles=target_triangles)
    o3.remove_unreferenced_vertices()
    simplified = trimesh.Trimesh(np.asarray(o3.vertices), np.asarray(o3.triangles), process=False)
    fd, tmp = tempfile.mkstemp(dir=out_dir, suffix=".obj")
    os.close(fd)
    simplified.export(tmp, file_type="obj", include_normals=False)
    os.replace(tmp, out)
    return out
