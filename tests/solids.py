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


def winding(point: np.ndarray, mesh: trimesh.Trimesh) -> float:
    """The closed ``mesh``'s winding number about ``point`` (3,): 1 inside, 0 outside (the
    solid angles of its triangles seen from the point, over 4 pi; Van Oosterom and
    Strackee 1983)."""
    a, b, c = (mesh.vertices[mesh.faces[:, k]] - point for k in range(3))
    la, lb, lc = (np.linalg.norm(v, axis=1) for v in (a, b, c))
    numerator = np.einsum("ij,ij->i", a, np.cross(b, c))
    denominator = (la * lb * lc + np.einsum("ij,ij->i", a, b) * lc
                   + np.einsum("ij,ij->i", b, c) * la + np.einsum("ij,ij->i", c, a) * lb)
    return float(2.0 * np.arctan2(numerator, denominator).sum() / (4.0 * np.pi))


def distance(point: np.ndarray, mesh: trimesh.Trimesh) -> float:
    """How far ``point`` (3,) is from the surface of ``mesh`` (cm): the least distance to
    its triangles (Ericson, "Real-Time Collision Detection", 5.1.5)."""
    a, b, c = (mesh.vertices[mesh.faces[:, k]] for k in range(3))
    ab, ac, ap = b - a, c - a, point - a
    normal = np.cross(ab, ac)
    normal /= np.linalg.norm(normal, axis=1, keepdims=True)
    # The nearest point of the plane, if inside the triangle; else the nearest of its edges.
    inside_plane = point - np.einsum("ij,ij->i", ap, normal)[:, None] * normal
    best = np.full(len(a), np.inf)
    u = np.einsum("ij,ij->i", np.cross(b - inside_plane, c - inside_plane), normal)
    v = np.einsum("ij,ij->i", np.cross(c - inside_plane, a - inside_plane), normal)
    w = np.einsum("ij,ij->i", np.cross(a - inside_plane, b - inside_plane), normal)
    within = (u >= 0) & (v >= 0) & (w >= 0)
    best[within] = np.abs(np.einsum("ij,ij->i", ap, normal))[within]
    for start, end in ((a, b), (b, c), (c, a)):
        edge = end - start
        share = np.clip(np.einsum("ij,ij->i", point - start, edge)
                        / np.einsum("ij,ij->i", edge, edge), 0.0, 1.0)
        nearest = start + share[:, None] * edge
        best = np.minimum(best, np.linalg.norm(point - nearest, axis=1))
    return float(best.min())
