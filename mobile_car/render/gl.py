"""The main renderer: OpenGL 3.3 through moderngl on a headless EGL context.

On a machine with no display and no GPU, EGL hands out Mesa's llvmpipe software
rasteriser (Debian packages libegl1, libegl-mesa0, libgl1-mesa-dri, libgl1). One context
is made per process and reused for every picture; frames are drawn with 4x multisampling
into an off-screen framebuffer and read back as premultiplied RGBA, ready for
:mod:`mobile_car.render.compose` to lay over the background.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import moderngl
import numpy as np

from .camera import Camera
from .lighting import GLSL_SHADE

if TYPE_CHECKING:  # (the drawing process draws without loading yourdfpy)
    from .scene import Scene

SAMPLES = 4

_VERTEX_SHADER = """
#version 330
uniform mat4 clip;
uniform mat3 to_view;
in vec3 in_position;
in vec3 in_normal;
in vec4 in_color;
out vec3 normal_view;
out vec4 color;
void main() {
    gl_Position = clip * vec4(in_position, 1.0);
    normal_view = to_view * in_normal;
    color = in_color;
}
"""

_FRAGMENT_SHADER = "#version 330\n" + GLSL_SHADE + """
in vec3 normal_view;
in vec4 color;
out vec4 frag_color;
void main() {
    frag_color = vec4(shade(normal_view, color.rgb), 1.0);
}
"""


class GLRenderer:
    """Draws scenes with one EGL context; ``description`` names the OpenGL driver."""

    name = "gl"

    def __init__(self):
        self.ctx = moderngl.create_context(standalone=True, backend="egl", require=330)
        self.program = self.ctx.program(vertex_shader=_VERTEX_SHADER,
                                        fragment_shader=_FRAGMENT_SHADER)
        self.samples = min(SAMPLES, self.ctx.max_samples)
        self._targets: dict[tuple[int, int], tuple] = {}
        info = self.ctx.info
        self.description = f"OpenGL {info['GL_VERSION'].split()[0]}, {info['GL_RENDERER']}"

    def _framebuffers(self, size: tuple[int, int]):
        if size not in self._targets:
            multisampled = self.ctx.framebuffer(
                color_attachments=[self.ctx.renderbuffer(size, 4, samples=self.samples)],
                depth_attachment=self.ctx.depth_renderbuffer(size, samples=self.samples))
            resolved = self.ctx.framebuffer(color_attachments=[self.ctx.renderbuffer(size, 4)])
            self._targets[size] = (multisampled, resolved)
        return self._targets[size]

    def draw(self, scene: Scene, camera: Camera) -> np.ndarray:
        """The model alone, (H, W, 4) uint8, colour premultiplied by coverage."""
        size = (camera.width, camera.height)
        multisampled, resolved = self._framebuffers(size)
        multisampled.use()
        self.ctx.enable(moderngl.DEPTH_TEST)
        multisampled.clear(0.0, 0.0, 0.0, 0.0, depth=1.0)
        if scene.triangle_count:
            self.program["clip"].write(camera.clip_matrix().T.copy().tobytes())
            self.program["to_view"].write(
                camera.rotation.astype(np.float32).T.copy().tobytes())
            vertices = np.hstack([scene.positions, scene.normals, scene.colors])
            # handed over as the array itself: a copy as bytes first was 40 bytes a corner
            # more (100 MB for OpenArm's bimanual robot) for the same buffer
            buffer = self.ctx.buffer(np.ascontiguousarray(vertices, dtype=np.float32))
            array = self.ctx.vertex_array(
                self.program, [(buffer, "3f 3f 4f", "in_position", "in_normal", "in_color")])
            try:
                array.render(moderngl.TRIANGLES)
            finally:
                array.release()
                buffer.release()
        self.ctx.copy_framebuffer(resolved, multisampled)
        pixels = np.frombuffer(resolved.read(components=4, alignment=1), dtype=np.uint8)
        return pixels.reshape(camera.height, camera.width, 4)[::-1]  # GL rows go bottom-up

    def close(self) -> None:
        for multisampled, resolved in self._targets.values():
            multisampled.release()
            resolved.release()
        self._targets.clear()
        self.ctx.release()
