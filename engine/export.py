"""Pictures and meshes out: PNG files and mesh formats, always written atomically."""

from __future__ import annotations

import io
import os
import re
from pathlib import Path

import numpy as np
from PIL import Image

from biceps.engine.arm import Arm
from biceps.engine.config import rgb
from biceps.engine.errors import FileError, shown
from biceps.engine.files import check_name, same_file, write_atomically
from biceps.engine.anatomy import arm_parts
from biceps.engine.names import printable
from biceps.engine.settings import RenderSettings

# zlib level 1: within a few per cent of level 6's size on these pictures (a flat
# background, smooth shading) at a fraction of the time, which dominates a headless snapshot.
PNG_COMPRESS_LEVEL = 1

MESH_FORMATS = (".obj", ".stl", ".ply", ".glb")

# Pixels per side: 8K. With 4x4 supersampling such a picture is rendered at 32768 x 32768,
# 7.5 GB of colour and depth; much beyond that no machine here renders it.
LARGEST_SIDE = 8192

_SIZE = re.compile(r"^\s*(\d+)\s*[x×X*, ]\s*(\d+)\s*$")


def parse_size(text: str) -> tuple[int, int]:
    """A picture size written ``WIDTHxHEIGHT`` in pixels, such as ``1920x1080``.

    Raises ValueError saying what is wrong; the command line and the app's export dialog
    both read sizes with this.
    """
    match = _SIZE.match(text)
    if match is None:
        raise ValueError(f"{shown(text)} is not a size: write it as 1920x1080")
    width, height = int(match[1]), int(match[2])
    for side in (width, height):
        if not 1 <= side <= LARGEST_SIDE:
            raise ValueError(f"each side must be 1 to {LARGEST_SIDE} pixels, not {side}")
    return width, height


def check_writable(path: Path, *suffixes: str, read: Path | None = None) -> None:
    """Raise :class:`FileError` now, before any work, if ``path`` cannot be the output; or
    if it is the file ``read``, the configuration the output is made from."""
    name = printable(path)
    if path.suffix.lower() not in suffixes:
        allowed = ", ".join(suffixes)
        raise FileError(f"{name}: the name must end in {allowed}")
    check_name(path)
    parent = path.parent
    try:
        if path.is_dir():
            raise FileError(f"{name}: is a directory")
        if not parent.is_dir():
            raise FileError(f"{name}: there is no directory {printable(parent)}")
    except OSError as error:  # a folder that cannot be searched, a loop of links
        raise FileError(f"{name}: {error.strerror}") from None
    if not os.access(parent, os.W_OK):
        raise FileError(f"{name}: the directory {printable(parent)} is not writable")
    if read is not None and same_file(path, read):
        raise FileError(f"{name}: is the configuration it is made from; writing it would "
                        "replace the model: give another name")


def png_bytes(frame: np.ndarray) -> bytes:
    """Encode ``frame`` ((h, w, 3) uint8) as PNG."""
    buffer = io.BytesIO()
    Image.fromarray(np.ascontiguousarray(frame), "RGB").save(
        buffer, format="PNG", compress_level=PNG_COMPRESS_LEVEL
    )
    return buffer.getvalue()


def write_png(path: str | os.PathLike, frame: np.ndarray) -> None:
    """Write ``frame`` ((h, w, 3) uint8) to ``path`` as PNG, atomically."""
    path = Path(path)
    check_writable(path, ".png")
    write_atomically(path, png_bytes(frame))


def write_mesh(path: str | os.PathLike, arm: Arm, segments: int,
               muscle_colour: str = RenderSettings.muscle_colour,
               bone_colour: str = RenderSettings.bone_colour) -> None:
    """Write the arm in its current pose as named parts (``anatomy.arm_parts``: each muscle
    by its name, and each bone).

    World space, centimetres; the format follows the suffix (OBJ, STL, PLY or binary glTF).
    STL and PLY hold a single mesh, so there the parts are merged. In glTF each part has
    its material, in its muscle's colour (the driver's is ``muscle_colour``, each
    companion's its own) or the bones' (``#rrggbb``); OBJ keeps its
    materials in a second file, so it has none here.
    """
    import trimesh  # heavy, and only this command needs it
    from trimesh.visual import TextureVisuals
    from trimesh.visual.material import PBRMaterial

    path = Path(path)
    check_writable(path, *MESH_FORMATS)
    file_type = path.suffix.lower().lstrip(".")
    scene = trimesh.Scene()
    colours = dict(zip(arm.names, (muscle_colour, *(c.colour for c in arm.companions))))
    for name, mesh in arm_parts(arm, segments).items():
        geometry = trimesh.Trimesh(mesh.vertices, mesh.triangles, vertex_normals=mesh.normals,
                                   process=False)
        if file_type == "glb":
            colour = rgb(colours.get(name, bone_colour))
            # Matte and not metallic: how the app shades them.
            geometry.visual = TextureVisuals(material=PBRMaterial(
                name=name, baseColorFactor=[*colour, 255], metallicFactor=0.0,
                roughnessFactor=0.7))
        scene.add_geometry(geometry, node_name=name, geom_name=name)
    data = scene.to_mesh().export(file_type=file_type) if file_type in ("stl", "ply") \
        else scene.export(file_type=file_type)
    write_atomically(path, data.encode() if isinstance(data, str) else data)
