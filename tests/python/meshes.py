"""Test meshes made with numpy (no file needed): a UV sphere, optionally bumpy, and an OBJ writer."""
import numpy as np


def sphere(segments, rings, bumps=0.0, radius=1.0):
    """(positions N×3, indices M×3, normals N×3, uvs N×2): a UV sphere with a seam (duplicated vertices at u = 0 and 1).
    bumps: the radius varies by bumps · sin(8 u·2π) · sin(6 v·π), so a baked normal map has detail."""
    u = np.linspace(0.0, 1.0, segments + 1)
    v = np.linspace(0.0, 1.0, rings + 1)
    uu, vv = np.meshgrid(u, v)
    theta, phi = uu * 2 * np.pi, vv * np.pi
    r = radius + bumps * np.sin(8 * theta) * np.sin(6 * phi)
    x, y, z = r * np.sin(phi) * np.cos(theta), r * np.cos(phi), -r * np.sin(phi) * np.sin(theta)
    positions = np.stack([x, y, z], axis=-1).reshape(-1, 3).astype(np.float32)
    normals = positions / np.linalg.norm(positions, axis=1, keepdims=True)
    uvs = np.stack([uu, 1.0 - vv], axis=-1).reshape(-1, 2).astype(np.float32)
    faces = []
    w = segments + 1
    for j in range(rings):
        for i in range(segments):
            a, b, c, d = j * w + i, j * w + i + 1, (j + 1) * w + i, (j + 1) * w + i + 1
            if j > 0:
                faces.append((a, c, b))
            if j < rings - 1:
                faces.append((b, c, d))
    return positions, np.array(faces, dtype=np.uint32), normals.astype(np.float32), uvs


def write_obj(path, positions, indices, normals=None, uvs=None):
    with open(path, "w") as out:
        for p in positions:
            out.write("v %.9g %.9g %.9g\n" % tuple(p))
        if uvs is not None:
            for t in uvs:
                out.write("vt %.9g %.9g\n" % tuple(t))
        if normals is not None:
            for n in normals:
                out.write("vn %.9g %.9g %.9g\n" % tuple(n))
        for f in indices + 1:
            if uvs is not None and normals is not None:
                out.write("f %d/%d/%d %d/%d/%d %d/%d/%d\n" % (f[0], f[0], f[0], f[1], f[1], f[1], f[2], f[2], f[2]))
            elif uvs is not None:
                out.write("f %d/%d %d/%d %d/%d\n" % (f[0], f[0], f[1], f[1], f[2], f[2]))
            else:
                out.write("f %d %d %d\n" % tuple(f))
