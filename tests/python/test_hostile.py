# Model files and arrays from strangers (issue 44), through `import glint` as through the
# command: every file of fuzz/regressions/models/ read by glint.load_mesh ends as the command
# ends it (a mesh where `glint mesh-info` exits 0, glint.InputError with its one line where it
# exits 3), in a child process that must not die of a signal; an array whose copy does not
# fit in memory raises MemoryError instead of crashing the interpreter.
import os
import pathlib
import subprocess
import sys
import textwrap

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
CORPUS = ROOT / "fuzz" / "regressions" / "models"


def child(code, **kwargs):
    """Runs Python code in a child interpreter (the suite's environment); the CompletedProcess."""
    return subprocess.run([sys.executable, "-c", textwrap.dedent(code)], capture_output=True, text=True, timeout=120, **kwargs)


def test_every_regression_file_ends_in_load_mesh_as_in_the_command(run):
    files = sorted(CORPUS.iterdir())
    assert len(files) >= 30
    # One child for every file: it prints a verdict per file, and a signal would cut the list short.
    result = child(f"""
        import glint, sys
        for path in {[str(f) for f in files]!r}:
            try:
                mesh = glint.load_mesh(path)
                print("ok", mesh.positions.shape[0], flush=True)
            except glint.InputError as e:
                assert "\\n" not in str(e)
                print("InputError", str(e), flush=True)
        """)
    assert result.returncode == 0, f"the child died (status {result.returncode}):\n{result.stdout[-2000:]}\n{result.stderr[-2000:]}"
    verdicts = result.stdout.splitlines()
    assert len(verdicts) == len(files)
    for path, verdict in zip(files, verdicts):
        command = run("mesh-info", path, check=False)
        assert command.returncode in (0, 3), (path.name, command.stderr)
        if command.returncode == 0:
            assert verdict.startswith("ok "), (path.name, verdict)
        else:
            # The same one line as the command's (which adds "glint: ").
            assert verdict == "InputError " + command.stderr.strip().splitlines()[-1].removeprefix("glint: "), (path.name, verdict)


def test_an_array_copy_that_does_not_fit_raises_memory_error():
    # A non-contiguous view must be copied; with the address space capped just above what the
    # child uses, the copy cannot be made. Each call must raise MemoryError (pybind11's
    # ensure() returned a null array, which glint then read: SIGSEGV).
    result = child("""
        import resource, numpy as np, glint
        base = np.ones((4096, 16384), np.float32)           # 256 MiB
        view = base[:, ::2]                                 # 4096×8192, not contiguous: 128 MiB to copy
        rgba = np.ones((4096, 8192, 4), np.uint8)[:, ::2]   # likewise for an image: 64 MiB
        rows = np.ones((8 << 20, 6), np.float32)[:, ::2]    # Mesh positions: 96 MiB
        def used():
            with open("/proc/self/statm") as f:
                return int(f.read().split()[0]) * resource.getpagesize()
        limit = used() + (48 << 20)
        resource.setrlimit(resource.RLIMIT_AS, (limit, limit))
        for name, call in [("normalmap", lambda: glint.normalmap(view)),
                           ("write_image", lambda: glint.write_image("unwritten.png", rgba)),
                           ("rgba_rows_up", lambda: glint.rgba_rows_up(rgba)),
                           ("Mesh", lambda: glint.Mesh(rows, np.array([[0, 1, 2]])))]:
            try:
                call()
                print(name, "no error")
            except MemoryError:
                print(name, "MemoryError")
        """, cwd=os.environ.get("TMPDIR", "/tmp"))
    assert result.returncode == 0, f"the child died (status {result.returncode}):\n{result.stdout}\n{result.stderr[-2000:]}"
    assert result.stdout.split("\n")[:4] == ["normalmap MemoryError", "write_image MemoryError", "rgba_rows_up MemoryError",
                                             "Mesh MemoryError"], result.stdout
