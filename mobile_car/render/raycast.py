"""The fallback renderer: ray-cast the scene with trimesh + embreex, no OpenGL at all.

Used where no EGL context can be made (no Mesa packages, a container without /dev/dri
access rights, a broken driver). It shares the camera (:meth:`Camera.pixel_rays`) and the
lighting (:func:`mobile_car.render.lighting.shade`) with the OpenGL renderer, so the two
pictures agree except for sub-pixel detail along edges.

Anti-aliasing copies what 4x multisampling does: one ray through every pixel centre, then,
only for pixels on an edge (coverage, colour or depth changes next to them), four more rays
at the sample positions of the standard 4x MSAA pattern, averaged.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np
import trimesh
from trimesh.ray.ray_pyembree import RayMeshIntersector

from .camera import Camera
from .lighting import shade

if TYPE_CHECKING:  # (the drawing process draws without loading yourdfpy)
    from .scene import Scene

# The standard 4x MSAA sample positions, as offsets from the pixel centre (in pixels).
MSAA_OFFSETS = np.array([(-2, -6), (6, -2), (-6, 2), (2, 6)], dtype=float) / 16.0
# A depth jump larger than this many pixel widths between neighbours marks an edge.
DEPTH_EDGE_PIXELS = 3.0


class RaycastRenderer:
    """Draws scenes by casting rays with Embree; same interface as the GL renderer."""

    name = "raycast"
    description = "ray casting (trimesh + embreex)"

    def draw(self, scene: Scene, camera: Camera) -> np.ndarray:
        """The model alone, (H, W, 4) uint8, colour premultiplied by coverage."""
        height, width = camera.height, camera.width
        image = np.zeros((height, width, 4), dtype=np.float32)
        if not scene.triangle_count:
            return image.astype(np.uint8)
        faces = np.arange(len(scene.positions)).reshape(-1, 3)
        mesh = trimesh.Trimesh(vertices=scene.positions.astype(np.float64), faces=faces,
                               process=False, validate=False)
        caster = RayMeshIntersector(mesh)
        right, up, _ = camera.rotation

        origins, direction = camera.pixel_rays()
        origins = origins.reshape(-1, 3)
        rgb, hit, face, depth = self._cast(caster, scene, camera, origins, direction)
        image[..., :3] = (rgb * hit[:, None]).reshape(height, width, 3)
        image[..., 3] = hit.reshape(height, width)

        edges = self._edge_pixels(hit.reshape(height, width), face.reshape(height, width),
                                  depth.reshape(height, width), scene, camera)
        rows, columns = np.nonzero(edges)
        if len(rows):
            centres = origins.reshape(height, width, 3)[rows, columns]
            total = np.zeros((len(rows), 4), dtype=np.float64)
            for dx, dy in MSAA_OFFSETS * camera.pixel_size:
                sample_origins = centres + dx * right - dy * up  # image y grows downwards
                s_rgb, s_hit, _, _ = self._cast(caster, scene, camera, sample_origins,
                                                direction)
                total[:, :3] += s_rgb * s_hit[:, None]
                total[:, 3] += s_hit
            image[rows, columns] = (total / len(MSAA_OFFSETS)).astype(np.float32)
        return np.rint(image * 255.0).astype(np.uint8)

    @staticmethod
    def _cast(caster, scene: Scene, camera: Camera, origins: np.ndarray, direction):
        """Shade the first hit of each ray: colour (N, 3), hit (N,), face (N,), depth (N,)."""
        count = len(origins)
        directions = np.broadcast_to(direction, (count, 3))
        faces, rays, locations = caster.intersects_id(
            origins, directions, multiple_hits=False, return_locations=True)
        rgb = np.zeros((count, 3))
        hit = np.zeros(count, dtype=np.float32)
        face = np.full(count, -1, dtype=np.int64)
        depth = np.zeros(count)  # misses are told apart by ``hit``, not by depth
        if len(faces):
            corners = scene.positions.reshape(-1, 3, 3)[faces].astype(np.float64)
            weights = trimesh.triangles.points_to_barycentric(corners, locations)
            normals = np.einsum("nk,nkj->nj", weights,
                                scene.normals.reshape(-1, 3, 3)[faces].astype(np.float64))
            colors = np.einsum("nk,nkj->nj", weights,
                               scene.colors.reshape(-1, 3, 4)[faces, :, :3].astype(np.float64))
            rgb[rays] = shade(normals @ camera.rotation.T, colors)
            hit[rays] = 1.0
            face[rays] = faces
            depth[rays] = locations @ camera.rotation[2]
        return rgb, hit, face, depth

    @staticmethod
    def _edge_pixels(hit, face, depth, scene: Scene, camera: Camera) -> np.ndarray:
        """Pixels next to a change of coverage, of colour, or of depth."""
        face_colors = scene.colors.reshape(-1, 3, 4)[:, 0, :3]
        color = np.where(hit[..., None] > 0, face_colors[np.maximum(face, 0)], -1.0)
        jump = DEPTH_EDGE_PIXELS * camera.pixel_size
        edges = np.zeros(hit.shape, dtype=bool)
        for axis in (0, 1):
            differs = ((np.diff(hit, axis=axis) != 0)
                       | np.any(np.diff(color, axis=axis) != 0, axis=-1)
                       | (np.abs(np.diff(depth, axis=axis)) > jump))
            if axis == 0:
                edges[:-1] |= differs
                edges[1:] |= differs
            else:
                edges[:, :-1] |= differs
                edges[:, 1:] |= differs
        return edges
