"""Meshes made solid with manifold3d, a library independent of ours, to measure overlaps."""

from pathlib import Path

import manifold3d
import numpy as np
import trimesh

from biceps.engine.export import write_mesh


def solid(mesh: trimesh.Trimesh) -> manifold3d.Manifold:
    """The closed parts of ``mesh`` joined into one solid (a bone's parts overlap)."""
    whole = manifold3d.Manifold(manifold3d.Mesh(
        vert_properties=np.asarray(mesh.vertices, np.float32),
        tri_verts=np.asarray(mesh.faces, np.uint32)))
    assert whole.status() == manifold3d.Error.NoError
    return manifold3d.Manifold.batch_boolean(whole.decompose(), manifold3d.OpType.Add)


def exported(arm, flexions, segments: int, folder: Path) -> dict:
    """``arm`` at each of ``flexions``, exported as glTF into ``folder`` and read back:
    {flexion: {part: trimesh.Trimesh}}."""
    meshes = {}
    for flexion in flexions:
        path = folder / f"arm{flexion}.glb"
        write_mesh(path, arm.at_flexion(flexion), segments)
        meshes[flexion] = dict(trimesh.load(path, force="scene").geometry)
    return meshes
