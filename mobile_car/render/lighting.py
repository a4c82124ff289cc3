"""One lighting model shared by the OpenGL shader and the ray caster, so both agree.

Lights are fixed to the camera (view space: x right, y up, z towards the viewer), so every
view is lit the same way: a key light from the upper left, a weaker fill from the right,
some ambient light, and a small highlight from the key light so that black parts (the
wheels) still show their shape instead of a flat silhouette. Surfaces are lit from
whichever side faces the camera, so open meshes and inverted normals still read well.

Colours are treated as albedo with a floor (ALBEDO_FLOOR): real black plastic or rubber
reflects a few percent of the light, and without that a black wheel renders as a flat
black hole whose faces cannot be told apart.
"""

from __future__ import annotations

import numpy as np

ALBEDO_FLOOR = 0.1
AMBIENT = 0.25
KEY_DIRECTION = (-0.4, 0.6, 0.7)
KEY_STRENGTH = 0.65
FILL_DIRECTION = (0.6, -0.1, 0.8)
FILL_STRENGTH = 0.25
SPECULAR_STRENGTH = 0.25
SHININESS = 40.0


def _unit(vector) -> np.ndarray:
    vector = np.asarray(vector, dtype=np.float64)
    return vector / np.linalg.norm(vector)


KEY = _unit(KEY_DIRECTION)
FILL = _unit(FILL_DIRECTION)
HALFWAY = _unit(KEY + np.array([0.0, 0.0, 1.0]))


def shade(normals_view: np.ndarray, base_rgb: np.ndarray) -> np.ndarray:
    """Lit colour (N, 3) in 0..1 from view-space normals (N, 3) and base colours (N, 3)."""
    normals = normals_view / np.maximum(np.linalg.norm(normals_view, axis=1, keepdims=True),
                                        1e-12)
    normals = np.where(normals[:, 2:3] < 0.0, -normals, normals)  # two-sided
    diffuse = (AMBIENT + KEY_STRENGTH * np.maximum(normals @ KEY, 0.0)
               + FILL_STRENGTH * np.maximum(normals @ FILL, 0.0))
    specular = SPECULAR_STRENGTH * np.maximum(normals @ HALFWAY, 0.0) ** SHININESS
    albedo = ALBEDO_FLOOR + (1.0 - ALBEDO_FLOOR) * base_rgb
    return np.clip(albedo * diffuse[:, None] + specular[:, None], 0.0, 1.0)


def _vec3(vector) -> str:
    return "vec3({:.9f}, {:.9f}, {:.9f})".format(*vector)


# The same formula in GLSL; the constants are written in from this module.
GLSL_SHADE = f"""
vec3 shade(vec3 normal, vec3 base) {{
    vec3 n = normalize(normal);
    if (n.z < 0.0) n = -n;
    float diffuse = {AMBIENT:.9f}
        + {KEY_STRENGTH:.9f} * max(dot(n, {_vec3(KEY)}), 0.0)
        + {FILL_STRENGTH:.9f} * max(dot(n, {_vec3(FILL)}), 0.0);
    float specular = {SPECULAR_STRENGTH:.9f}
        * pow(max(dot(n, {_vec3(HALFWAY)}), 0.0), {SHININESS:.9f});
    vec3 albedo = {ALBEDO_FLOOR:.9f} + {1.0 - ALBEDO_FLOOR:.9f} * base;
    return clamp(albedo * diffuse + specular, 0.0, 1.0);
}}
"""
