"""The Python module against the glint command (issue 36): the same options, the same
messages, and results equal to the command's files byte for byte (an array written with
glint.write_image gives the very bytes of the command's file, and the file read back is the
array); Ctrl-C, progress and the GIL."""
import json
import os
import signal
import subprocess
import sys
import textwrap
import threading
import time

import numpy as np
import pytest

import glint
import meshes


def same_file_bytes(tmp_path, array, expected_file):
    """The array written as the command writes its outputs has the command file's bytes."""
    mine = tmp_path / ("mine" + os.path.splitext(str(expected_file))[1])
    glint.write_image(mine, array)
    return mine.read_bytes() == open(expected_file, "rb").read()


# ----------------------------------------------------------------------------------- module
def test_info_names_what_the_command_has(run):
    info = glint.info()
    assert info["version"] == glint.__version__
    assert run("--version").stdout.strip().endswith(glint.__version__)
    assert "normal" in info["maps"] and "ao" in info["maps"]
    assert "sepia" in info["effects"] and "kuwahara" in info["effects"]
    listed = run("list").stdout
    assert "basics/triangle/depth" in info["variants"] and "basics/triangle" in listed
    assert info["threads"] >= 1


def test_mesh_from_arrays_shares_its_memory_and_checks_its_input():
    positions, indices, normals, uvs = meshes.sphere(8, 4)
    mesh = glint.Mesh(positions, indices, normals, uvs)
    assert mesh.vertex_count == len(positions) and mesh.triangle_count == len(indices)
    assert np.array_equal(mesh.positions, positions) and np.array_equal(mesh.uvs, uvs)
    view = mesh.positions
    assert not view.flags.writeable and view.base is not None  # a view on the mesh, not a copy
    with pytest.raises(glint.InputError, match="out of range"):
        glint.Mesh(positions, indices + len(positions))
    # Every integer type gives the same triangles (uint32 and int32 are read as they are).
    for dtype in (np.uint32, np.int32, np.int64, np.uint16):
        same = glint.Mesh(positions, indices.astype(dtype))
        assert np.array_equal(same.indices, mesh.indices), dtype
    with pytest.raises(glint.InputError, match="out of range"):
        glint.Mesh(positions, (indices + len(positions)).astype(np.uint32))
    with pytest.raises(glint.InputError, match="-1 at 0 is out of range"):
        glint.Mesh(positions, np.where(np.arange(indices.size).reshape(indices.shape) == 0, -1, indices).astype(np.int32))
    with pytest.raises(glint.UsageError, match="N×3"):
        glint.Mesh(positions[:, :2], indices)
    bad = positions.copy()
    bad[0, 0] = np.nan
    with pytest.raises(glint.InputError, match="NaN|finite"):
        glint.Mesh(bad, indices)


# ------------------------------------------------------------------------------------- bake
def test_bake_equals_the_command_byte_for_byte(tmp_path, pair, run):
    low, high = pair
    n, ao, report = tmp_path / "n.png", tmp_path / "ao.png", tmp_path / "report.json"
    run("bake", low, high, "-o", n, "--ao", ao, "--size", "64x48", "--ao-samples", "4", "--samples", "4",
        "--json", report, "-q")
    result = glint.bake(low, high, size=(64, 48), maps=("normal", "ao"), ao_samples=4, samples=4)
    assert result["normal"].shape == (48, 64, 3) and result["normal"].dtype == np.uint8
    assert result["ao"].shape == (48, 64) and result["ao"].dtype == np.uint8
    assert same_file_bytes(tmp_path, result["normal"], n)
    assert same_file_bytes(tmp_path, result["ao"], ao)
    assert np.array_equal(glint.read_image(n), result["normal"])
    command = json.load(open(report))
    for key in ("rays", "covered_texels", "padded_texels", "hit_ratio", "ao_rays", "samples"):
        assert result.report[key] == command[key], key
    assert result.report["tool"] == "bake"
    assert "normal" in repr(result)


def test_bake_on_the_gpu_equals_the_cpu_and_the_command(tmp_path, pair, run):
    """device= is --device: the GPU's maps are the CPU's, and the report says where the rays ran."""
    low, high = pair
    cpu = glint.bake(low, high, size=64, maps=("normal", "ao"), ao_samples=8, device="cpu")
    gpu = glint.bake(low, high, size=64, maps=("normal", "ao"), ao_samples=8, device="gpu")
    assert cpu.report["device"] == "cpu" and gpu.report["device"] == "gpu"
    assert gpu.report["gpu_dispatches"] > 0 and gpu.report["device_reason"].startswith("--device gpu")
    assert np.abs(cpu["normal"].astype(int) - gpu["normal"].astype(int)).max() <= 1
    assert abs(cpu["ao"].astype(float).mean() - gpu["ao"].astype(float).mean()) <= 1.0
    n, report = tmp_path / "n.png", tmp_path / "report.json"
    run("bake", low, high, "-o", n, "--ao", tmp_path / "ao.png", "--size", "64x64", "--ao-samples", "8",
        "--device", "gpu", "--json", report, "-q")
    command = json.load(open(report))
    assert command["device"] == "gpu"
    for key in ("rays", "ao_rays", "hits", "device_reason"):
        assert command[key] == gpu.report[key], key
    assert same_file_bytes(tmp_path, gpu["normal"], n)
    with pytest.raises(glint.UsageError, match="--device"):
        glint.bake(low, high, size=64, device="tpu")


def test_bake_from_arrays_equals_the_bake_from_files(pair):
    low, high = pair
    from_files = glint.bake(low, high, size=48)
    m = glint.load_mesh(low)
    low_arrays = glint.Mesh(np.array(m.positions), np.array(m.indices), np.array(m.normals), np.array(m.uvs))
    from_arrays = glint.bake(low_arrays, high, size=48)
    assert np.array_equal(from_arrays["normal"], from_files["normal"])
    # The high poly from arrays: the same surface, so the same map to within a code (the
    # file's high poly is loaded unjoined, the arrays' joined: the same triangles).
    h = meshes.sphere(96, 48, bumps=0.03)
    both = glint.bake(low_arrays, glint.Mesh(*h), size=48)
    difference = np.abs(both["normal"].astype(int) - from_files["normal"].astype(int))
    assert difference.max() <= 1


def test_bake_bits_give_the_commands_depths(tmp_path, pair, run):
    low, high = pair
    run("bake", low, high, "-o", tmp_path / "n16.png", "--bits", "16", "--size", "32x32", "-q")
    run("bake", low, high, "-o", tmp_path / "n.exr", "--position", tmp_path / "p.exr", "--size", "32x32", "-q")
    wide = glint.bake(low, high, size=32, bits=16)
    assert wide["normal"].dtype == np.uint16
    assert np.array_equal(glint.read_image(tmp_path / "n16.png"), wide["normal"])
    floats = glint.bake(low, high, size=32, bits=32, maps=("normal", "position"))
    assert floats["normal"].dtype == np.float32 and floats["position"].dtype == np.float32
    assert np.array_equal(glint.read_image(tmp_path / "n.exr"), floats["normal"])
    assert np.array_equal(glint.read_image(tmp_path / "p.exr"), floats["position"])


def test_a_udim_bake_gives_a_map_per_tile(tmp_path, run):
    positions, indices, normals, uvs = meshes.sphere(16, 8)
    uvs = uvs.copy()
    uvs[:, 0] *= 0.999
    right = positions[:, 0] > 0  # the right half's UVs one tile over: two tiles
    uvs[right, 0] += 1.0
    low = glint.Mesh(positions, indices, normals, uvs)
    # (a triangle with corners on both sides is baked in its centre's tile: said as a warning)
    h = meshes.sphere(64, 32, bumps=0.02)
    meshes.write_obj(tmp_path / "u_low.obj", positions, indices, normals, uvs)
    meshes.write_obj(tmp_path / "u_high.obj", *h)
    result = glint.bake(tmp_path / "u_low.obj", tmp_path / "u_high.obj", size=32)
    assert sorted(result["normal"]) == [1001, 1002]
    run("bake", tmp_path / "u_low.obj", tmp_path / "u_high.obj", "-o", tmp_path / "n.<UDIM>.png", "--size", "32x32", "-q")
    for tile in (1001, 1002):
        assert same_file_bytes(tmp_path, result["normal"][tile], tmp_path / f"n.{tile}.png")
    assert len(result.report["udim_tiles"]) == 2
    assert sorted(glint.bake(low, tmp_path / "u_high.obj", size=32)["normal"]) == [1001, 1002]


def test_a_batch_file_bakes_every_job_into_arrays(tmp_path, pair, run):
    low, high = pair
    batch = {"defaults": {"size": "32x32", "high": str(high)},
             "bakes": [{"low": str(low), "output": "a.png"}, {"low": str(low), "output": "b.png", "ao": "b_ao.png",
                                                             "ao-samples": 2}]}
    path = tmp_path / "jobs.json"
    path.write_text(json.dumps(batch))
    results = glint.bake_batch(path, samples=4)
    assert [sorted(r) for r in results] == [["normal"], ["ao", "normal"]]
    run("bake", "--batch", path, "--samples", "4", "-q")
    assert same_file_bytes(tmp_path, results[0]["normal"], tmp_path / "a.png")
    assert same_file_bytes(tmp_path, results[1]["ao"], tmp_path / "b_ao.png")


def test_errors_are_the_commands_one_line_messages(tmp_path, pair, run):
    low, high = pair
    missing = tmp_path / "nothing.obj"
    command = run("bake", low, missing, "-o", tmp_path / "x.png", check=False)
    assert command.returncode == 3
    with pytest.raises(glint.InputError) as caught:
        glint.bake(low, missing, size=32)
    message = str(caught.value)
    assert "\n" not in message and message in command.stderr
    assert isinstance(caught.value, ValueError) and isinstance(caught.value, glint.Error)
    with pytest.raises(glint.UsageError, match="unknown key 'sampels'"):
        glint.bake(low, high, size=32, sampels=4)
    command = run("bake", low, high, "-o", tmp_path / "x.png", "--size", "0x4", check=False)
    with pytest.raises(glint.UsageError) as caught:
        glint.bake(low, high, size=(0, 4))
    assert command.returncode == 2 and str(caught.value) in command.stderr
    with pytest.raises(glint.UsageError, match="unknown map"):
        glint.bake(low, high, maps=("normals",))
    with pytest.raises(glint.OutputError):
        glint.write_image(tmp_path / "no-such-folder" / "x.png", np.zeros((4, 4, 3), np.uint8))


def test_progress_reaches_the_callback_and_the_gil_is_released(pair):
    low, high = pair
    calls = []
    ticks = [0]
    done = threading.Event()

    def count():
        while not done.is_set():
            ticks[0] += 1
            time.sleep(0.001)

    counter = threading.Thread(target=count)
    counter.start()
    try:
        result = glint.bake(low, high, size=256, samples=4, maps=("normal", "ao"), ao_samples=8,
                            progress=lambda label, d, total: calls.append((label, d, total)))
    finally:
        done.set()
        counter.join()
    seconds = result.report["seconds"]["total"]
    assert calls and all(total > 0 and 0 <= d <= total for _, d, total in calls)
    assert calls[-1][1] == calls[-1][2]  # the last call: complete
    assert calls[0][0].startswith("bake")
    # Python ran beside the bake: the counter thread ticked through it (≥ 1 tick per 10 ms).
    assert ticks[0] >= 0.1 * seconds * 1000 / 10


INTERRUPTED = textwrap.dedent("""
    import os, sys, glint
    started = []
    def progress(label, done, total):
        if not started:
            started.append(1)
            print("started", flush=True)
    try:
        glint.bake(sys.argv[1], sys.argv[2], size=2048, samples=16, maps=("normal", "ao"), ao_samples=64,
                   asset=sys.argv[3], progress=progress)
    except KeyboardInterrupt as e:
        print("KeyboardInterrupt", e, flush=True)
        sys.exit(0 if not os.path.exists(sys.argv[3]) else 1)
    print("finished", flush=True)
    sys.exit(2)
""")


def test_ctrl_c_stops_a_bake_with_keyboard_interrupt_and_writes_nothing(tmp_path, pair):
    low, high = pair
    asset = tmp_path / "asset.glb"
    child = subprocess.Popen([sys.executable, "-c", INTERRUPTED, str(low), str(high), str(asset)],
                             stdout=subprocess.PIPE, text=True, env=os.environ)
    assert child.stdout.readline().strip() == "started"
    start = time.monotonic()
    child.send_signal(signal.SIGINT)
    out, _ = child.communicate(timeout=120)
    assert child.returncode == 0, out
    assert "KeyboardInterrupt" in out
    assert time.monotonic() - start < 10  # stopped at the next poll, not after the bake
    assert not asset.exists() and not list(tmp_path.glob("*.tmp*"))


# -------------------------------------------------------------------------- normalmap, post
def test_normalmap_equals_the_command(tmp_path, run):
    y, x = np.mgrid[0:40, 0:56]
    height = (127 + 100 * np.sin(x / 5.0) * np.cos(y / 7.0)).astype(np.uint8)
    glint.write_image(tmp_path / "h.png", height)
    run("normalmap", tmp_path / "h.png", "-o", tmp_path / "n.png", "--scale", "4", "--wrap")
    normals = glint.normalmap(height, scale=4, wrap=True)
    assert normals.shape == (40, 56, 3)
    assert same_file_bytes(tmp_path, normals, tmp_path / "n.png")
    with pytest.raises(glint.UsageError, match="formula"):
        glint.normalmap(height, formula="sobel")


def test_post_on_an_image_equals_the_command(tmp_path, run):
    y, x = np.mgrid[0:60, 0:80]
    image = np.stack([x * 3, y * 4, (x + y) * 2], axis=-1).astype(np.uint8)
    glint.write_image(tmp_path / "in.png", image)
    run("post", tmp_path / "in.png", "-e", "sepia", "-e", "sobel", "-o", tmp_path / "out.png")
    result = glint.post(image, ["sepia", "sobel"])
    assert result.shape == (60, 80, 3) and result.dtype == np.uint8
    assert same_file_bytes(tmp_path, result, tmp_path / "out.png")
    grey = glint.post(image, "posterize", channels=1)
    assert grey.shape == (60, 80)
    with pytest.raises(glint.UsageError):
        glint.post(image, "no-such-effect")


def test_post_runs_over_a_videos_frames(tmp_path, run):
    clip = tmp_path / "clip.mkv"
    run("post", "--input", "lavfi:testsrc2=size=64x48:rate=10:duration=1", "-o", clip, "--codec", "ffv1")
    frames = glint.frames(clip)
    assert frames.info["width"] == 64 and frames.info["height"] == 48
    originals = list(frames)
    assert len(originals) == 10 and originals[0].shape == (48, 64, 3)
    processed = list(glint.post(glint.frames(clip), "sepia"))
    assert len(processed) == 10
    run("post", clip, "-e", "sepia", "--frames", "3:4", "-o", tmp_path / "still.png")
    assert same_file_bytes(tmp_path, processed[3], tmp_path / "still.png")
    assert len(list(glint.frames(clip, 2, 5))) == 3
    # The GPU backend (forced: llvmpipe would pick the CPU) over every frame of one chain: its
    # GL context stays current on the calling thread from frame to frame; it agrees with the
    # CPU backend within one 8-bit step.
    on_gpu = list(glint.post(glint.frames(clip), "sepia", backend="gpu"))
    assert len(on_gpu) == 10
    assert max(int(np.abs(a.astype(int) - b.astype(int)).max()) for a, b in zip(on_gpu, processed)) <= 1


# ------------------------------------------------------------------------------ cut, render
def test_cut_equals_the_command(tmp_path, run):
    ground = (np.array([[-2, 0, -2], [2, 0, -2], [2, 0, 2], [-2, 0, 2]], np.float32), np.array([[0, 2, 1], [0, 3, 2]]))
    card = (np.array([[-0.5, 1, -0.5], [0.5, 1, -0.5], [0.5, 1, 0.5], [-0.5, 1, 0.5]], np.float32),
            np.array([[0, 2, 1], [0, 3, 2]]))
    meshes.write_obj(tmp_path / "ground.obj", *ground)
    meshes.write_obj(tmp_path / "card.obj", *card)
    run("cut", tmp_path / "ground.obj", tmp_path / "card.obj", "--light", "0.3,4,0.2,sun", "-o", tmp_path / "c.ply",
        "--json", tmp_path / "c.json", "-q")
    result = glint.cut([tmp_path / "ground.obj", glint.Mesh(*card)], ["0.3,4,0.2,sun"])
    command = json.load(open(tmp_path / "c.json"))
    for key in ("output_polygons", "output_triangles", "output_vertices"):
        assert result["report"][key] == command[key], key
    assert result["triangles"].shape == (command["output_triangles"], 3)
    assert result["lights"][0]["name"] == "sun"
    # The ground's shadowed pieces: the card's shadow on it, lit elsewhere.
    assert set(np.unique(result["light_masks"])) == {0, 1}
    assert len(glint.cut(glint.Mesh(*ground), [(0.0, 3.0, 0.0)])["triangles"]) == 2
    with pytest.raises(glint.UsageError):
        glint.cut(glint.Mesh(*ground), ["up high"])


def test_render_equals_the_command(tmp_path, run):
    run("render", "basics/triangle/depth", "--size", "96x64", "-o", tmp_path / "t.png")
    image = glint.render("basics/triangle/depth", (96, 64))
    assert image.shape == (64, 96, 4) and image.dtype == np.uint8
    assert np.array_equal(glint.read_image(tmp_path / "t.png")[..., :3], image[..., :3])
    with pytest.raises(glint.UsageError, match="no-such-scene"):
        glint.render("no-such-scene")
