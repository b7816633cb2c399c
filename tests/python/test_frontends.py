# `import glint` keeps the command's promises (issue 45): each check the command makes, the
# module makes from the same place in the library, tested side by side with the command; and
# a mesh from arrays is the mesh from a file: the same high poly baked from arrays, OBJ, PLY
# and GLB gives the same bytes.
import json
import os
import struct

import numpy as np
import pytest

import glint
import meshes


def one_line(text):
    return text.strip().splitlines()[-1].removeprefix("glint: ")


# ------------------------------------------------------------------------------ the same checks
def test_max_memory_is_refused_as_the_command_refuses_it(pair, run):
    low, high = pair
    command = run("bake", low, high, "-o", "n.png", "--size", "4096x4096", "--max-memory", "100", check=False)
    assert command.returncode == 2, command.stderr
    with pytest.raises(glint.UsageError) as error:
        glint.bake(low, high, size=4096, max_memory=100)
    assert str(error.value) == one_line(command.stderr)


def test_render_sizes_are_checked_as_the_commands(run):
    for size in ((0, 0), (-1, -1), (20000, 10)):
        command = run("render", "basics/triangle/color", "-o", "x.png", "--size", f"{size[0]}x{size[1]}", check=False)
        assert command.returncode == 2
        with pytest.raises(glint.UsageError, match="out of range|WIDTHxHEIGHT"):
            glint.render("basics/triangle/color", size)
    assert glint.render("basics/triangle/color").shape[2] == 4  # None: the scene's own size


def test_render_takes_a_model_file_as_the_command_does(tmp_path, run):
    path = tmp_path / "ball.obj"
    meshes.write_obj(path, *meshes.sphere(24, 12))
    run("render", path, "-o", tmp_path / "ball.png", "--size", "64x48", "-q")
    image = glint.render(path, (64, 48))
    assert np.array_equal(image, glint.read_image(tmp_path / "ball.png"))


def test_a_height_field_that_is_not_finite_is_an_input_error(tmp_path, run):
    height = np.zeros((16, 16), np.float32)
    height[3, 5] = np.nan
    with pytest.raises(glint.InputError, match=r"texel \(5, 3\)"):
        glint.normalmap(height)
    height[3, 5] = np.inf
    with pytest.raises(glint.InputError, match="not a number"):
        glint.normalmap(height)
    glint.write_image(tmp_path / "h.exr", height)
    command = run("normalmap", tmp_path / "h.exr", "-o", tmp_path / "n.png", check=False)
    assert command.returncode == 3 and "not a number at texel (5, 3)" in command.stderr, command.stderr


def test_a_directory_as_a_mesh_is_an_input_error(tmp_path, pair, run):
    low, high = pair
    command = run("bake", tmp_path, high, "-o", tmp_path / "n.png", check=False)
    assert command.returncode == 3, command.stderr
    with pytest.raises(glint.InputError) as error:
        glint.bake(tmp_path, high, size=16)
    assert str(error.value) == one_line(command.stderr)


# ------------------------------------------------------------------------------ the user's folder
def test_a_preview_folder_is_new_empty_or_glints(tmp_path, pair, run):
    low, high = pair
    # A trailing slash, as shell completion types it.
    run("bake", low, high, "-o", tmp_path / "n.png", "--size", "32x32", "-q", "--preview", str(tmp_path / "prev") + "/")
    assert (tmp_path / "prev" / "index.html").exists() and (tmp_path / "prev" / ".glint-page").exists()
    glint.bake(low, high, size=32, preview=str(tmp_path / "prev") + "/")  # glint's own folder: written again
    # The user's own folder: refused before any work, naming what is there; nothing touched.
    mine = tmp_path / "mine"
    mine.mkdir()
    (mine / "index.html").write_text("my page")
    command = run("bake", low, high, "-o", tmp_path / "m.png", "--size", "32x32", "--preview", mine, check=False)
    assert command.returncode == 4 and "index.html" in command.stderr, command.stderr
    with pytest.raises(glint.OutputError) as error:
        glint.bake(low, high, size=32, preview=str(mine))
    assert str(error.value) == one_line(command.stderr)
    assert (mine / "index.html").read_text() == "my page" and sorted(os.listdir(mine)) == ["index.html"]
    assert not (tmp_path / "m.png").exists()
    # --asset and --preview naming one place: refused before the bake.
    command = run("bake", low, high, "-o", tmp_path / "k.png", "--asset", tmp_path / "x.gltf", "--preview",
                  tmp_path / "x.gltf", check=False)
    assert command.returncode == 2 and "x.gltf" in command.stderr, command.stderr
    assert not (tmp_path / "k.png").exists()


def test_export_web_keeps_to_its_folder(tmp_path, pair, run):
    low, _ = pair
    run("view", low, "--export-web", str(tmp_path / "page") + "/", "-q")
    assert (tmp_path / "page" / "model.glb").exists()
    mine = tmp_path / "photos"
    mine.mkdir()
    (mine / "a.jpg").write_bytes(b"x")
    command = run("view", low, "--export-web", mine, check=False)
    assert command.returncode == 4 and "a.jpg" in command.stderr, command.stderr
    assert os.listdir(mine) == ["a.jpg"]


# ------------------------------------------------------------------------------ arrays and files
def write_ply(path, positions, indices):
    with open(path, "wb") as out:
        out.write(b"ply\nformat binary_little_endian 1.0\nelement vertex %d\nproperty float x\nproperty float y\n"
                  b"property float z\nelement face %d\nproperty list uchar int vertex_indices\nend_header\n"
                  % (len(positions), len(indices)))
        out.write(np.asarray(positions, "<f4").tobytes())
        faces = np.zeros(len(indices), dtype=[("n", "u1"), ("i", "<i4", 3)])
        faces["n"], faces["i"] = 3, indices
        out.write(faces.tobytes())


def write_glb(path, positions, indices):
    data = np.asarray(positions, "<f4").tobytes() + np.asarray(indices, "<u4").tobytes()
    doc = {"asset": {"version": "2.0"}, "buffers": [{"byteLength": len(data)}],
           "bufferViews": [{"buffer": 0, "byteLength": positions.nbytes},
                           {"buffer": 0, "byteOffset": positions.nbytes, "byteLength": indices.size * 4}],
           "accessors": [{"bufferView": 0, "componentType": 5126, "count": len(positions), "type": "VEC3",
                          "min": positions.min(0).tolist(), "max": positions.max(0).tolist()},
                         {"bufferView": 1, "componentType": 5125, "count": int(indices.size), "type": "SCALAR"}],
           "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
           "nodes": [{"mesh": 0}], "scenes": [{"nodes": [0]}], "scene": 0}
    text = json.dumps(doc).encode()
    text += b" " * (-len(text) % 4)
    data += b"\0" * (-len(data) % 4)
    body = struct.pack("<II", len(text), 0x4E4F534A) + text + struct.pack("<II", len(data), 0x004E4942) + data
    with open(path, "wb") as out:
        out.write(struct.pack("<III", 0x46546C67, 2, 12 + len(body)) + body)


def test_a_high_poly_from_arrays_obj_ply_and_glb_bakes_the_same_bytes(tmp_path, pair):
    low, _ = pair
    positions, indices, _, _ = meshes.sphere(64, 32, bumps=0.03)
    meshes.write_obj(tmp_path / "high.obj", positions, indices)
    write_ply(tmp_path / "high.ply", positions, indices)
    write_glb(tmp_path / "high.glb", positions, indices)
    # No normals anywhere: glint makes them, the same for a mesh from arrays as from a file.
    maps = ("normal", "ao", "height")
    reference = glint.bake(low, glint.Mesh(positions, indices), size=48, maps=maps, ao_samples=8)
    for name in ("high.obj", "high.ply", "high.glb"):
        baked = glint.bake(low, tmp_path / name, size=48, maps=maps, ao_samples=8)
        for m in maps:
            assert np.array_equal(baked[m], reference[m]), f"{name}: {m} differs from the arrays' bake"
