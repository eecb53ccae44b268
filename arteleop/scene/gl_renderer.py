"""The head camera's scene drawn with OpenGL: on Mesa's CPU rasteriser (llvmpipe) or a GPU,
headless through EGL, with moderngl.

PyBullet's TinyRenderer takes 60-130 ms for a 640x480 frame of this scene on one core; a
real-time camera at the Kinect's 30 Hz needs under 33 ms. This renderer draws the shapes of a
PyBullet world (the render world's: the same bodies, links, meshes and colours) with the poses
PyBullet gives them, and returns what TinyRenderer returns (:class:`RawImage`: colour, the
OpenGL depth buffer, the segmentation mask), so :class:`~arteleop.scene.HeadCamera` turns either
into the same kind of frame.

Shading is TinyRenderer's, so the bowl tracker sees the same colours from both: a directional
light from PyBullet's default direction, 0.6 ambient, 0.35 diffuse and 0.05 specular (exponent
2, the reflection's z in the world frame), on the material colour truncated to 8 bits. Normals
are TinyRenderer's too: per face for boxes and mesh files without normals, and the normalised
vertex position for cylinders, spheres and meshes given as vertices (the bowl, the target ring).
TinyRenderer draws a cylinder as the hull of 42 support points with a 1 mm margin, this renderer
as a 32-sided prism: the arm's white rings differ at their rims by a pixel or two.
"""

from __future__ import annotations

import functools
import os
import sys
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np
import pybullet as p
from numpy.typing import NDArray

from arteleop.errors import ArteleopError, ConfigurationError
from arteleop.scene.camera import RawImage, RenderRequest
from arteleop.scene.camera_config import RENDERERS
from arteleop.transforms import pybullet_pose_to_transform

if TYPE_CHECKING:
    import moderngl
    from pybullet_utils.bullet_client import BulletClient

AMBIENT = 0.6
DIFFUSE = 0.35
SPECULAR = 0.05
SHININESS = 2.0
LIGHT_DIRECTION = np.array([-50.0, 30.0, 100.0]) / np.linalg.norm([-50.0, 30.0, 100.0])
"""TinyRenderer's defaults for a z-up world (bullet3's TinyRendererVisualShapeConverter)."""

CYLINDER_STEPS = 32
"""Sides of a cylinder, as TinyRenderer tessellates one."""

_VERTEX_SHADER = """
#version 330
uniform mat4 clip_from_world;
uniform mat4 world_from_model;
uniform mat3 normal_to_world;
in vec3 in_position;
in vec3 in_normal;
out vec3 v_normal;
void main() {
    v_normal = normal_to_world * in_normal;
    gl_Position = clip_from_world * world_from_model * vec4(in_position, 1.0);
}
"""

_FRAGMENT_SHADER = """
#version 330
uniform vec3 base_colour;   // 0..255, the material colour truncated to 8 bits
uniform vec3 light;         // unit vector towards the light, world frame
uniform vec4 shading;       // ambient, diffuse, specular, shininess
uniform float body;         // PyBullet body id
in vec3 v_normal;
layout(location = 0) out vec4 colour;
layout(location = 1) out vec2 depth_body;
void main() {
    vec3 n = normalize(v_normal);
    float lit = dot(n, light);
    vec3 reflected = normalize(2.0 * lit * n - light);
    float specular = pow(max(reflected.z, 0.0), shading.w);
    vec3 c = floor(shading.x * base_colour
                   + (shading.y * max(lit, 0.0) + shading.z * specular) * base_colour);
    colour = vec4(min(c, 255.0) / 255.0, 1.0);
    depth_body = vec2(gl_FragCoord.z, body);
}
"""


class RendererUnavailableError(ArteleopError):
    """No OpenGL context could be opened here (no EGL, no driver); the message says why."""


@functools.cache
def gl_context() -> moderngl.Context:
    """This process's OpenGL context, opened headless through EGL on first use.

    Raises :class:`RendererUnavailableError` naming the cause (moderngl missing, no EGL library,
    no device) and what to install.
    """
    # llvmpipe renders on the calling thread: the loop and the render process each own a core,
    # and a frame is the same bit for bit whatever the thread count.
    os.environ.setdefault("LP_NUM_THREADS", "0")
    try:
        import moderngl

        ctx = moderngl.create_standalone_context(backend="egl")
    except Exception as err:  # ImportError, or whatever the EGL loader raises
        raise RendererUnavailableError(
            f"no OpenGL context through EGL ({type(err).__name__}: {err}); on Debian, "
            "'apt-get install libegl1 libegl-mesa0 libgl1-mesa-dri' provides one"
        ) from err
    if ctx.version_code < 330:
        raise RendererUnavailableError(
            f"OpenGL {ctx.version_code} through EGL is older than the 3.3 this renderer needs"
        )
    return ctx


@functools.cache
def resolve_renderer(choice: str) -> str:
    """The renderer ``choice`` (one of :data:`RENDERERS`) gives here: ``"gl"`` or ``"tiny"``.

    ``"auto"`` falls back to TinyRenderer where no OpenGL context opens, saying so once on
    stderr; ``"gl"`` raises :class:`RendererUnavailableError` there instead.
    """
    if choice not in RENDERERS:
        raise ConfigurationError(f"renderer {choice!r}: expected one of {', '.join(RENDERERS)}")
    if choice == "tiny":
        return "tiny"
    try:
        gl_context()
    except RendererUnavailableError as err:
        if choice == "gl":
            raise RendererUnavailableError(
                f"The head camera can't render with OpenGL: {err}. Or choose the renderer "
                "'tiny' (PyBullet's TinyRenderer, several times slower)."
            ) from err
        print(f"arteleop: the head camera renders with PyBullet's TinyRenderer: {err}",
              file=sys.stderr)  # fmt: skip
        return "tiny"
    return "gl"


def renderer_description(renderer: str) -> str:
    """What draws the head camera's frames, for a run's manifest: the renderer and, for GL, the
    device (a GPU and llvmpipe may differ in the last bit of a pixel)."""
    if renderer != "gl":
        return "tiny: PyBullet TinyRenderer"
    info = gl_context().info
    return f"gl: {info['GL_RENDERER']}, {info['GL_VERSION']}"


@dataclass(frozen=True)
class _Part:
    """One visual shape: where to find its pose, its geometry on the GPU, and its look."""

    body: int
    link: int
    T_link_shape: NDArray[np.float64]
    vao: moderngl.VertexArray
    base_colour: tuple[float, float, float]


class GLScene:
    """The visual shapes of ``bodies`` in ``client``, uploaded once and drawn with the poses
    the client holds at each :meth:`render`.

    ``meshes`` gives the geometry of shapes created from vertices in memory (PyBullet does not
    hand it back): body id -> (vertices (N, 3) m, triangles (M, 3)) in the body's frame.
    """

    def __init__(
        self,
        client: BulletClient,
        bodies: tuple[int, ...],
        meshes: dict[int, tuple[NDArray[np.float64], NDArray[np.int32]]],
    ) -> None:
        self._client = client
        self.ctx = ctx = gl_context()
        self._program = ctx.program(vertex_shader=_VERTEX_SHADER, fragment_shader=_FRAGMENT_SHADER)
        self._program["light"].value = tuple(LIGHT_DIRECTION)
        self._program["shading"].value = (AMBIENT, DIFFUSE, SPECULAR, SHININESS)
        self._parts: list[_Part] = []
        self._buffers: list[moderngl.Buffer] = []
        for body in bodies:
            for shape in client.getVisualShapeData(body):
                triangles = _shape_triangles(shape, meshes.get(body))
                if triangles is None:
                    continue
                self._add_part(body, shape, triangles)
        self._targets: dict[tuple[int, int], _Targets] = {}
        # What a frame asks PyBullet, found once: each body's links that carry shapes, and where
        # a base's own frame sits from its centre of mass (PyBullet reports a base by the latter).
        self._links: dict[int, list[int]] = {}
        for part in self._parts:
            if part.link >= 0 and part.link not in self._links.setdefault(part.body, []):
                self._links[part.body].append(part.link)
        self._T_inertial_base = {
            part.body: np.linalg.inv(
                pybullet_pose_to_transform(*client.getDynamicsInfo(part.body, -1)[3:5])
            )
            for part in self._parts
            if part.link < 0
        }

    def _add_part(self, body: int, shape: tuple, triangles: NDArray[np.float32]) -> None:
        buffer = self.ctx.buffer(np.ascontiguousarray(triangles, dtype=np.float32).tobytes())
        self._buffers.append(buffer)
        vao = self.ctx.vertex_array(self._program, [(buffer, "3f 3f", "in_position", "in_normal")])
        T = pybullet_pose_to_transform(shape[5], shape[6])
        # TinyRenderer multiplies the colour's 8 bits by the material, into 8 bits again.
        base = tuple(float(np.floor(255.0 * c)) for c in shape[7][:3])
        self._parts.append(_Part(body, shape[1], T, vao, base))  # type: ignore[arg-type]

    def render(self, request: RenderRequest) -> RawImage:
        """Draw the client's current state as ``request`` says (size, view, projection)."""
        w, h = request.width_px, request.height_px
        targets = self._targets.get((w, h))
        if targets is None:
            targets = self._targets[(w, h)] = _Targets(self.ctx, w, h)
        view = np.array(request.view_gl, dtype=np.float64).reshape(4, 4).T
        projection = np.array(request.projection_gl, dtype=np.float64).reshape(4, 4).T
        # TinyRenderer samples a pixel at its corner, OpenGL at its centre: shift by half a pixel
        # so that both see the same point of the scene in a pixel (depth then agrees to microns).
        to_corner = np.eye(4)
        to_corner[0, 3], to_corner[1, 3] = 1.0 / w, 1.0 / h
        projection = to_corner @ projection
        program = self._program
        program["clip_from_world"].write((projection @ view).T.astype(np.float32).tobytes())
        targets.clear()
        targets.both.use()
        self.ctx.enable(self.ctx.DEPTH_TEST)
        poses = self._link_poses()
        for part in self._parts:
            T = poses[part.body, part.link] @ part.T_link_shape
            program["world_from_model"].write(T.T.astype(np.float32).tobytes())
            # A rigid motion turns normals as it turns points (meshes are scaled on upload).
            program["normal_to_world"].write(T[:3, :3].T.astype(np.float32).tobytes())
            program["base_colour"].value = part.base_colour
            program["body"].value = float(part.body)
            part.vao.render()
        return targets.read(request.with_segmentation)

    def _link_poses(self) -> dict[tuple[int, int], NDArray[np.float64]]:
        """The world pose of the frame of every link that carries a shape, by (body, link)."""
        c = self._client
        poses = {}
        for body, T_inertial_base in self._T_inertial_base.items():
            T_world_inertial = pybullet_pose_to_transform(*c.getBasePositionAndOrientation(body))
            poses[body, -1] = T_world_inertial @ T_inertial_base
        for body, links in self._links.items():
            states = c.getLinkStates(body, links, computeForwardKinematics=True)
            for link, state in zip(links, states, strict=True):
                poses[body, link] = pybullet_pose_to_transform(state[4], state[5])
        return poses

    def close(self) -> None:
        for part in self._parts:
            part.vao.release()
        for buffer in self._buffers:
            buffer.release()
        for targets in self._targets.values():
            targets.release()
        self._program.release()
        self._parts, self._buffers, self._targets = [], [], {}


class _Targets:
    """The images one size of frame is drawn into: colour (8 bits) and, as floats, the depth
    buffer's value with the id of the body drawn there."""

    def __init__(self, ctx: moderngl.Context, width: int, height: int) -> None:
        self.width, self.height = width, height
        self.colour = ctx.texture((width, height), 4)
        self.depth_body = ctx.texture((width, height), 2, dtype="f4")
        self.depth = ctx.depth_renderbuffer((width, height))
        self.both = ctx.framebuffer([self.colour, self.depth_body], self.depth)
        # A clear sets every colour image of a framebuffer to one value: this one has its own.
        self._depth_body_only = ctx.framebuffer([self.depth_body])

    def clear(self) -> None:
        self.both.clear(1.0, 1.0, 1.0, 1.0, depth=1.0)  # TinyRenderer's white background
        self._depth_body_only.clear(1.0, -1.0, 0.0, 0.0)  # the far plane, no body

    def read(self, with_segmentation: bool) -> RawImage:
        h, w = self.height, self.width
        # OpenGL's rows run bottom-up; PyBullet's, top-down.
        rgba = np.frombuffer(self.colour.read(), dtype=np.uint8).reshape(h, w, 4)[::-1]
        depth_body = np.frombuffer(self.depth_body.read(), dtype=np.float32).reshape(h, w, 2)[::-1]
        segmentation = None
        if with_segmentation:
            # PyBullet's mask without its link flag: the body id, -1 where nothing is drawn.
            segmentation = depth_body[..., 1].astype(np.int32)
        return RawImage(rgba.copy(), depth_body[..., 0].copy(), segmentation)

    def release(self) -> None:
        for item in (self.both, self._depth_body_only, self.colour,
                     self.depth_body, self.depth):  # fmt: skip
            item.release()


def _shape_triangles(
    shape: tuple, memory_mesh: tuple[NDArray[np.float64], NDArray[np.int32]] | None
) -> NDArray[np.float32] | None:
    """(3T, 6) vertices and normals of a visual shape's triangles, in its own frame, with
    TinyRenderer's normals; None for a shape with nothing to draw."""
    kind, dims, filename = shape[2], tuple(float(d) for d in shape[3]), shape[4]
    if kind == p.GEOM_MESH and not filename:
        return None if memory_mesh is None else _memory_triangles(memory_mesh, dims)
    return _described_triangles(kind, dims, filename)


@functools.cache
def _described_triangles(
    kind: int, dims_m: tuple[float, ...], filename: bytes
) -> NDArray[np.float32] | None:
    """The triangles of a shape that its kind, dimensions and file describe, built once per
    process (read-only): every site of a study's worker draws the same robot and table."""
    dims = np.asarray(dims_m, dtype=np.float64)
    if kind == p.GEOM_BOX:
        corners = np.array([[x, y, z] for x in (-1, 1) for y in (-1, 1) for z in (-1, 1)])
        triangles = _flat(_convex(corners * dims / 2.0)[:, :3].reshape(-1, 3, 3).astype(np.float64))
    elif kind == p.GEOM_CYLINDER:
        # About z and centred, with TinyRenderer's 32 sides.
        length, radius = dims[0], dims[1]
        a = 2 * np.pi * np.arange(CYLINDER_STEPS) / CYLINDER_STEPS
        ring = radius * np.column_stack([np.sin(a), np.cos(a)])
        ends = [
            np.column_stack([ring, np.full(CYLINDER_STEPS, z)]) for z in (-length / 2, length / 2)
        ]
        triangles = _convex(np.vstack(ends))
    elif kind == p.GEOM_SPHERE:
        # 42 points spread on the sphere (a Fibonacci lattice).
        k = np.arange(42) + 0.5
        polar, azimuth = np.arccos(1 - 2 * k / 42), np.pi * (1 + 5**0.5) * k
        triangles = _convex(dims[0] * np.column_stack(
            [np.sin(polar) * np.cos(azimuth), np.sin(polar) * np.sin(azimuth), np.cos(polar)]
        ))  # fmt: skip
    elif kind == p.GEOM_MESH:
        vertices, faces = _mesh_file(filename.decode())
        triangles = _flat((vertices * dims)[faces])
    else:
        return None
    triangles.flags.writeable = False
    return triangles


def _memory_triangles(
    memory_mesh: tuple[NDArray[np.float64], NDArray[np.int32]], dims_m: tuple[float, ...]
) -> NDArray[np.float32]:
    """A mesh given from memory (the bowl), scaled by ``dims_m``, with TinyRenderer's normals."""
    vertices, triangles = memory_mesh
    vertices = np.asarray(vertices, dtype=np.float64) * np.asarray(dims_m, dtype=np.float64)
    # TinyRenderer's normal for a vertex given without one: its position, normalised (or x).
    length = np.linalg.norm(vertices, axis=1, keepdims=True)
    normals = np.where(length > 1e-9, vertices / np.maximum(length, 1e-9), [1.0, 0.0, 0.0])
    corners = np.asarray(triangles).ravel()
    return np.hstack([vertices[corners], normals[corners]]).astype(np.float32)


def _mesh_file(path: str) -> tuple[NDArray[np.float64], NDArray[np.int64]]:
    """A mesh file's vertices (V, 3) and faces (F, 3); read once per process through
    :func:`_described_triangles`' cache."""
    import trimesh

    mesh = trimesh.load(Path(path), force="mesh", process=False)
    return np.asarray(mesh.vertices, dtype=np.float64), np.asarray(mesh.faces, dtype=np.int64)


def _convex(points: NDArray[np.float64]) -> NDArray[np.float32]:
    """The convex hull of ``points`` as triangles facing out, each corner's normal its
    position normalised: TinyRenderer draws cylinders and spheres as hulls shaded so."""
    from scipy.spatial import ConvexHull

    hull = ConvexHull(points)
    tri = points[hull.simplices]
    # A hull's equations hold its outward normals; wind each triangle to agree with them.
    normal = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
    inward = np.einsum("ij,ij->i", normal, hull.equations[:, :3]) < 0
    tri[inward] = tri[inward][:, ::-1]
    corners = tri.reshape(-1, 3)
    normals = corners / np.linalg.norm(corners, axis=1, keepdims=True)
    return np.hstack([corners, normals]).astype(np.float32)


def _flat(tri: NDArray[np.float64]) -> NDArray[np.float32]:
    """Triangles (T, 3, 3) with their face normal at every corner: (3T, 6)."""
    normal = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
    normal /= np.maximum(np.linalg.norm(normal, axis=1, keepdims=True), 1e-12)
    normals = np.repeat(normal[:, None, :], 3, axis=1)
    return np.concatenate([tri, normals], axis=2).reshape(-1, 6).astype(np.float32)
