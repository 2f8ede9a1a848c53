"""Meshes made solid with manifold3d, a library independent of ours, to measure overlaps."""

import manifold3d
import numpy as np
import trimesh


def solid(mesh: trimesh.Trimesh) -> manifold3d.Manifold:
    """The closed parts of ``mesh`` joined into one solid (a bone's parts overlap)."""
    whole = manifold3d.Manifold(manifold3d.Mesh(
        vert_properties=np.asarray(mesh.vertices, np.float32),
        tri_verts=np.asarray(mesh.faces, np.uint32)))
    assert whole.status() == manifold3d.Error.NoError
    return manifold3d.Manifold.batch_boolean(whole.decompose(), manifold3d.OpType.Add)
