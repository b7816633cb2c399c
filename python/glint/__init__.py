"""glint: real-time rendering techniques and the offline tools of `glint` (bake, post, cut, render) on numpy arrays.

The functions run the library's own jobs, so their options, defaults, checks and messages are
the command's (``glint bake --help`` lists every option ``glint.bake`` takes, with dashes as
underscores), and their results equal the command's files pixel for pixel.

    >>> import glint
    >>> result = glint.bake("crate_low.obj", "crate_high.ply", size=512, maps=("normal", "ao"))
    >>> result["normal"].shape, result["normal"].dtype
    ((512, 512, 3), dtype('uint8'))

Long calls release the GIL, report progress through ``progress=callable(label, done, total)``
and stop on Ctrl-C (KeyboardInterrupt) with nothing half-written. Errors are
``glint.Error`` subclasses carrying the command's one-line message: UsageError (a bad option,
also a ValueError), InputError (an unreadable or unsuitable input, also a ValueError),
OutputError (also an OSError), NoGpuError, OutOfMemoryError (also a MemoryError).

docs/python.md is the tour.
"""

from __future__ import annotations

import os as _os
from typing import Any, Callable, Iterable, Iterator, Mapping, Optional, Sequence, Tuple, Union

try:  # the installed package: the dlopen()ed modules and data relative to it (python/CMakeLists.txt)
    from . import _locations

    _here = _os.path.dirname(_os.path.abspath(__file__))
    for _name, _variable in (("libglint_oiio.so", "GLINT_OIIO_MODULE"), ("libglint_ffmpeg.so", "GLINT_FFMPEG_MODULE")):
        _path = _os.path.normpath(_os.path.join(_here, _locations.MODULE_DIR, _name))
        if _os.path.exists(_path):
            _os.environ.setdefault(_variable, _path)
    _data = _os.path.normpath(_os.path.join(_here, _locations.DATA_DIR))
    if _os.path.isdir(_data):
        _os.environ.setdefault("GLINT_DATA_DIR", _data)
except ImportError:  # the build tree: the compiled-in build paths
    pass

import numpy as _np

from . import _glint
from ._glint import (  # noqa: F401  (re-exported)
    Error,
    InputError,
    Mesh,
    NoGpuError,
    OutOfMemoryError,
    OutputError,
    UsageError,
)

__version__ = _glint.version()

__all__ = [
    "Error", "UsageError", "InputError", "OutputError", "NoGpuError", "OutOfMemoryError",
    "Mesh", "BakeResult", "info", "load_mesh", "bake_options", "read_image", "write_image", "rgba_rows_up", "bake", "bake_batch", "normalmap", "post", "frames",
    "cut", "render",
]

Progress = Optional[Callable[[str, int, int], Any]]
MeshLike = Union[str, "_os.PathLike[str]", Mesh]
Size = Union[int, Tuple[int, int]]


def info() -> dict:
    """What this glint is: version, worker threads, the bake's maps, post's effects and the scenes' variants."""
    return {
        "version": _glint.version(),
        "threads": _glint.threads(),
        "maps": [name for name, _ in _glint.map_options()],
        "effects": _glint.effect_names(),
        "variants": _glint.variants(),
    }


def load_mesh(path: Union[str, "_os.PathLike[str]"]) -> Mesh:
    """A mesh file (OBJ, PLY, glTF/GLB, FBX, ...) as `glint load` reads it: indexed, with normals (generated when the file has none) and UVs when it has them."""
    return _glint.load_mesh(_os.fspath(path))


def read_image(path: Union[str, "_os.PathLike[str]"]) -> _np.ndarray:
    """An image file as an array: H×W (one channel) or H×W×C; uint8, uint16 or float32 (EXR, HDR: linear light)."""
    return _glint.read_image(_os.fspath(path))


def write_image(path: Union[str, "_os.PathLike[str]"], image: _np.ndarray) -> None:
    """Writes an array as an image file, atomically, as the command writes its outputs (the format from the extension): the same array gives the same bytes as `glint bake`'s or `glint post`'s file."""
    _glint.write_image(_os.fspath(path), _np.asarray(image))


def rgba_rows_up(image: _np.ndarray) -> _np.ndarray:
    """The image as a flat float32 array of RGBA, bottom row first (Blender's Image.pixels, OpenGL's texture rows): integer types scaled to 0..1, grey replicated, alpha 1 when the image has none. Multithreaded: a 2048² map in milliseconds."""
    return _glint.rgba_rows_up(_np.asarray(image))


# ---------------------------------------------------------------------------------------- bake
class BakeResult(Mapping[str, Any]):
    """The maps of a bake, by name ("normal", "ao", ...): an array each, or for a UDIM bake a dict of arrays by tile number (1001, 1002, ...). ``report`` is the command's --json report as a dict."""

    def __init__(self, maps: dict, report: dict):
        self._maps = maps
        self.report = report

    def __getitem__(self, name: str):
        return self._maps[name]

    def __iter__(self):
        return iter(self._maps)

    def __len__(self) -> int:
        return len(self._maps)

    def __repr__(self) -> str:
        parts = []
        for name, value in self._maps.items():
            if isinstance(value, dict):
                parts.append(f"{name}: {len(value)} UDIM tiles")
            else:
                parts.append(f"{name}: {value.shape} {value.dtype}")
        return "BakeResult(" + ", ".join(parts) + ")"


def _size_text(size: Size) -> str:
    if isinstance(size, int):
        return f"{size}x{size}"
    if isinstance(size, str):
        return size
    width, height = size
    return f"{int(width)}x{int(height)}"


def bake_options() -> dict:
    """The bake's options and maps as data, the same as `glint bake --describe` prints: "maps" (each
    map's name, option, label, help and whether it is colour or data), "options" (every option's
    help, default and kind), "samples" (the values samples= takes), "size" and "ao_samples" ranges.
    Front ends (the Blender add-on) build their controls from it instead of copying them."""
    return _glint.bake_options()


def bake(low: MeshLike, high: MeshLike, size: Size = (1024, 1024), maps: Sequence[str] = ("normal",), *,
         bits: int = 8, progress: Progress = None, threads: int = 0,
         **options: Any) -> BakeResult:
    """Bakes the high poly's detail into maps of the low poly's UV layout, as `glint bake` does.

    low, high: mesh files, or glint.Mesh objects made from arrays (the low poly needs UVs).
    size: the maps' size, 1024 or (2048, 1024).
    maps: which maps to return, from glint.info()["maps"]: "normal" (tangent space unless
        space="object"), "ao", "bent_normal", "curvature", "thickness", "height", "position",
        ... (the options' names with underscores).
    bits: 8 (uint8, the command's PNG), 16 (uint16) or 32 (float32, the command's EXR).
    options: any other option of `glint bake`, by its long name with underscores:
        samples=4, ao_samples=64, max_front="2%", directx=True, cage="cage.obj", device="gpu"
        (where the rays are traced: "auto", "cpu" or "gpu"; result.report["device"] says which),
        asset="crate.glb" (written, with the maps), preview="crate-preview" (a folder).
    progress: called as progress(label, done, total) about ten times a second.
    threads: worker threads (0: every core).

    Returns a BakeResult: result["normal"] is an H×W×3 array; a UDIM bake (UVs beyond the unit
    square) gives result["normal"][1001]. Raises UsageError, InputError, ... with the command's message.
    """
    if bits not in (8, 16, 32):
        raise UsageError(f"bits must be 8, 16 or 32, got {bits}")
    options_of = dict(_glint.map_options())
    known = list(options_of)
    maps = tuple(maps)
    for name in maps:
        if name not in known:
            raise UsageError(f"unknown map '{name}': one of {', '.join(known)}")
    extension = ".exr" if bits == 32 else ".png"
    settings: dict = {}
    low_mesh = low if isinstance(low, Mesh) else None
    high_mesh = high if isinstance(high, Mesh) else None
    settings["low"] = "glint.Mesh (low)" if low_mesh is not None else _os.fspath(low)
    settings["high"] = "glint.Mesh (high)" if high_mesh is not None else _os.fspath(high)
    settings["output"] = "normal" + extension
    settings["size"] = _size_text(size)
    if bits == 16:
        settings["bits"] = 16
    for name in maps:
        if name != "normal":
            settings[options_of[name]] = name + extension
    for key, value in options.items():
        if key in ("output", "low", "high", "size", "bits") or key in known or key.replace("_", "-") in options_of.values():
            raise UsageError(f"'{key}' is set by glint.bake's own arguments (low, high, size, maps, bits)")
        settings[key] = value
    baked, report = _glint.bake(settings, low_mesh, high_mesh, progress, threads)
    return _result(baked, report, maps)


def _result(baked: dict, report: dict, maps: Sequence[str]) -> BakeResult:
    out: dict = {}
    for (name, tile), image in baked.items():
        if name not in maps:
            continue
        if tile == 0:
            out[name] = image
        else:
            out.setdefault(name, {})[tile] = image
    return BakeResult({name: out[name] for name in maps if name in out}, report)


def bake_batch(path: Union[str, "_os.PathLike[str]"], *, progress: Progress = None, threads: int = 0,
               **overrides: Any) -> list:
    """Every bake of a batch file (`glint bake --batch FILE`: the same parsing and checks), each into arrays instead of its files: a list of BakeResult in the file's order, each with the maps its job names (a job's paths only name its formats: "ao.exr" gives float32). overrides: options for every job, as on the command line (samples=4)."""
    results = []
    dashed = {key.replace("_", "-"): value for key, value in overrides.items()}
    for baked, report in _glint.bake_batch(_os.fspath(path), dashed, progress, threads):
        names = [n for n, _ in _glint.map_options() if any(key[0] == n for key in baked)]
        results.append(_result(baked, report, names))
    return results


# ---------------------------------------------------------------------------------- normalmap
def normalmap(height: _np.ndarray, scale: Optional[float] = None, wrap: bool = False, formula: str = "gradient") -> _np.ndarray:
    """A tangent-space normal map from a height map, as `glint normalmap` makes one (the VGP353 lecture).

    height: H×W (or a colour image: its luminance is the height); uint8, uint16 or float32.
    scale: the height of the full 0..1 range in texel widths (bumpiness); None: the command's default (8).
    wrap: neighbours wrap around the edges (tileable textures); else they clamp.
    formula: "gradient" (the surface's true normal) or "slide" (the VGP353 lecture's formula as written).
    Returns H×W×3 uint8, (n + 1) / 2; H×W×4 with the input's alpha when it has one.

    >>> import numpy as np
    >>> ramp = np.tile(np.linspace(0.0, 1.0, 64, dtype=np.float32), (32, 1))  # rising to the right
    >>> n = glint.normalmap(ramp, scale=8)
    >>> n.shape, n.dtype, bool(n[16, 32, 0] < 128)  # a slope up to the right tilts the normal to −x
    ((32, 64, 3), dtype('uint8'), True)
    """
    return _glint.normalmap(_np.asarray(height), None if scale is None else float(scale), bool(wrap), formula)


# --------------------------------------------------------------------------------------- post
def _effect_list(effects: Union[str, Sequence[str]]) -> list:
    return [effects] if isinstance(effects, str) else list(effects)


def post(image_or_frames: Union[_np.ndarray, Iterable[_np.ndarray]], effects: Union[str, Sequence[str]] = (),
         *, settings: Sequence[str] = (), backend: str = "auto", channels: int = 0, linear_output: bool = False,
         progress: Progress = None) -> Union[_np.ndarray, Iterator[_np.ndarray]]:
    """Runs post's effects (`glint post -e ...`) on an image array, or lazily on each frame of an iterable of arrays (glint.frames("clip.mp4")).

    effects: "sepia", ["sobel", "kuwahara:size=4"], ... (glint.info()["effects"]; NAME:param=value as `-e` takes it).
    settings: effect settings as `--set` takes them ("kuwahara.size=4").
    backend: "auto" (the CPU on a software renderer, else the GPU), "cpu" or "gpu".
    channels: 1 grey, 2 grey + alpha, 3 RGB, 4 RGBA; 0 keeps the input's.
    linear_output: a float32 result in linear light, as the command writes an EXR.
    progress: accepted for symmetry; an image is one step (Ctrl-C is raised when it returns).

    An image gives an array (uint8 unless linear_output); an iterable gives an iterator of arrays.

    >>> import numpy as np
    >>> grey = np.full((48, 64, 3), 128, dtype=np.uint8)
    >>> toned = glint.post(grey, ["sepia", "kuwahara:size=4"])
    >>> toned.shape, bool(toned[24, 32, 0] > toned[24, 32, 2])  # sepia: warmer than it was
    ((48, 64, 3), True)
    """
    chain = _glint.Post(_effect_list(effects), list(settings), backend, int(channels), bool(linear_output))
    if isinstance(image_or_frames, _np.ndarray):
        return chain.run(image_or_frames, progress)[0]

    def frames_out():
        for frame in image_or_frames:
            yield chain.run(_np.asarray(frame), None)[0]

    return frames_out()


def frames(path: Union[str, "_os.PathLike[str]"], first: int = 0, end: int = -1) -> Iterator[_np.ndarray]:
    """A video file's frames (any format FFmpeg reads), each an H×W×3 uint8 array; `first` and `end` select frames [first, end) (end -1: to the last). The iterator's ``info`` has width, height, fps, frames, codec."""
    return _glint.Frames(_os.fspath(path), int(first), int(end))


# ---------------------------------------------------------------------------------------- cut
def cut(meshes: Union[MeshLike, Sequence[MeshLike]], lights: Sequence[Union[str, Sequence[float]]], *,
        progress: Progress = None, threads: int = 0) -> dict:
    """Cuts the lights' shadows into the meshes, as `glint cut` does (WWDC 2003 session 212's static shadows).

    meshes: one or more mesh files or glint.Mesh objects, joined in order.
    lights: point lights, "x,y,z" or "x,y,z,name" strings, or (x, y, z) sequences.

    Returns a dict: "positions" (N×3 float32), "triangles" (M×3 uint32), "light_masks" (M
    uint32: bit i set when light i reaches the triangle), "triangle_polygon" (M: the convex
    polygon each triangle is part of), "lights", "report" (the command's counts), "warnings".

    >>> import numpy as np
    >>> ground = glint.Mesh(np.array([[-2, 0, -2], [2, 0, -2], [2, 0, 2], [-2, 0, 2]], np.float32),
    ...                     np.array([[0, 2, 1], [0, 3, 2]], np.uint32))
    >>> roof = glint.Mesh(np.array([[-1, 1, -1], [1, 1, -1], [1, 1, 1], [-1, 1, 1]], np.float32),
    ...                   np.array([[0, 2, 1], [0, 3, 2]], np.uint32))
    >>> result = glint.cut([ground, roof], ["0,3,0,lamp"])
    >>> sorted(set(result["light_masks"].tolist()))  # shadowed (0) under the roof, lit (1) around it
    [0, 1]
    """
    items = [meshes] if isinstance(meshes, (str, _os.PathLike, Mesh)) else list(meshes)
    if not items:
        raise UsageError("glint.cut needs at least one mesh")
    loaded = [m if isinstance(m, Mesh) else _glint.load_mesh(_os.fspath(m)) for m in items]
    if len(loaded) == 1:
        scene = loaded[0]
    else:
        positions, indices, base = [], [], 0
        for m in loaded:
            positions.append(_np.asarray(m.positions))
            indices.append(_np.asarray(m.indices, dtype=_np.int64) + base)
            base += m.vertex_count
        scene = Mesh(_np.concatenate(positions), _np.concatenate(indices))
    texts = [light if isinstance(light, str) else ",".join(repr(float(v)) for v in light) for light in lights]
    return _glint.cut(scene, texts, progress, threads)


# ------------------------------------------------------------------------------------- render
def render(variant: Union[str, "_os.PathLike[str]"], size: Optional[Size] = None, time: Optional[float] = None,
           options: Union[Sequence[str], Mapping[str, Any]] = ()) -> _np.ndarray:
    """Renders a scene variant headless, as `glint render` does: an H×W×4 uint8 array (top row first).

    variant: "scene/variant" from glint.info()["variants"] ("basics/triangle/depth"), or a model
        file (.glb .gltf .obj .ply .fbx), shown as `glint render FILE` shows it.
    size: (width, height) or one side, each 1..16384 as `glint render --size` takes them;
        None: the scene's own size.
    time: the scene time in seconds (None: the scene's default).
    options: the scene's options, ["name=value", ...] or {"name": value} (`glint render --set`).

    >>> picture = glint.render("basics/triangle/depth", size=(64, 48))
    >>> picture.shape, picture.dtype
    ((48, 64, 4), dtype('uint8'))
    """
    if size is None:
        dims = None
    elif isinstance(size, str):
        w, _, h = size.partition("x")
        dims = (int(w), int(h))
    else:
        dims = (int(size), int(size)) if isinstance(size, int) else (int(size[0]), int(size[1]))
    if isinstance(options, Mapping):
        assignments = [f"{k}={v}" for k, v in options.items()]
    else:
        assignments = list(options)
    return _glint.render(_os.fspath(variant), dims, time, assignments)
