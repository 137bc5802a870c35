"""Rendering across a ``dask.distributed`` cluster.

:func:`render` cuts the image into tiles, one task per tile, and stitches the
results: the array is the same, byte for byte, as :func:`lamplight.render` of
the same scene and settings, because every pixel's samples are seeded by the
pixel alone. :func:`render_frames` renders an animation, one task per frame.

The scene travels to the workers once: it is scattered (``broadcast=True``) as
its description (the built-in name, the scene file's text, the dict, or the
mesh path; never built data), and each worker process builds it on first use
and keeps the build (by a digest of the description) for the tiles that follow
and for later renders of the same scene. Meshes referenced by path are read on the
workers, which suits a shared file system; with ``ship_meshes=True`` the client
reads them and sends their bytes along, and each worker writes them to a
temporary folder of its own.

When a worker dies, Dask runs its lost tasks again on the others; since tasks
are deterministic the image is the same. The same call runs on any cluster:
only the ``client`` changes (``docs/python.md`` shows Slurm, PBS and Kubernetes).
"""

from __future__ import annotations

import atexit
import collections
import hashlib
import json
import math
import os
import pickle
import re
import shutil
import tempfile
import uuid
from typing import Any, Dict, List, Optional, Sequence, Tuple, Union

import numpy as np

from ._lamplight import Scene, denoise_array
from ._render import SceneLike, as_scene, progress_reporter, resolve, with_settings
from .image import Image

Tiles = Union[None, int, Tuple[int, int]]


def tile_windows(width: int, height: int, tiles: Tiles) -> List[Tuple[int, int, int, int]]:
    """Pixel windows ``(x0, y0, w, h)`` covering a ``width x height`` image in
    row-major order: ``tiles`` is a count (cut into a grid of near-square
    tiles) or ``(columns, rows)``."""
    if tiles is None:
        tiles = 64
    if isinstance(tiles, int) and not isinstance(tiles, bool):
        if tiles < 1:
            raise ValueError(f"tiles must be at least 1, got {tiles}")
        cols = max(1, min(width, round(math.sqrt(tiles * width / height))))
        rows = max(1, min(height, math.ceil(tiles / cols)))
    elif isinstance(tiles, (tuple, list)) and len(tiles) == 2 and all(isinstance(t, int) for t in tiles):
        cols, rows = tiles
        if cols < 1 or rows < 1:
            raise ValueError(f"tiles must be at least (1, 1), got {tuple(tiles)}")
        cols, rows = min(cols, width), min(rows, height)
    else:
        raise TypeError(f"tiles must be an int or a (columns, rows) pair, got {tiles!r}")
    xs = [width * i // cols for i in range(cols + 1)]
    ys = [height * j // rows for j in range(rows + 1)]
    return [(xs[i], ys[j], xs[i + 1] - xs[i], ys[j + 1] - ys[j]) for j in range(rows) for i in range(cols)]


class _Shipped:
    """A scene whose mesh files travel with it as bytes; a worker writes them to
    a temporary folder of its own and builds the scene from there, once."""

    def __init__(self, kind: str, source: Any, files: Dict[str, bytes], depth: int, camera: Optional[dict]):
        self.state = (kind, source, files, depth, camera)
        self._scene: Optional[Scene] = None

    def __getstate__(self):
        return self.state

    def __setstate__(self, state) -> None:
        self.state = state
        self._scene = None

    def scene(self) -> Scene:
        if self._scene is None:
            kind, source, files, depth, camera = self.state
            root = tempfile.mkdtemp(prefix="lamplight-meshes-")
            atexit.register(shutil.rmtree, root, True)
            # `../x.obj` must stay inside the folder: the base sits `depth` levels down.
            base = os.path.join(root, *(["d"] * depth))
            for rel, data in files.items():
                target = os.path.normpath(os.path.join(base, rel))
                if os.path.commonpath([root, target]) != root:
                    raise ValueError(f"mesh path {rel!r} leaves the scene's folder")
                os.makedirs(os.path.dirname(target), exist_ok=True)
                with open(target, "wb") as f:
                    f.write(data)
            os.makedirs(base, exist_ok=True)
            if kind == "dict":
                scene = Scene.from_dict(source, base)
            elif kind == "file":
                scene = Scene.from_toml(source, base)
            else:
                scene = Scene.from_file(os.path.join(base, source))
            self._scene = scene.with_camera(camera) if camera is not None else scene
        return self._scene


def _companions(path: str) -> List[str]:
    """Files a mesh file names (an OBJ's ``mtllib``, a glTF's buffers and images), relative to it."""
    out: List[str] = []
    lower = path.lower()
    try:
        if lower.endswith(".obj"):
            with open(path, "r", errors="replace") as f:
                for line in f:
                    m = re.match(r"\s*mtllib\s+(.+?)\s*$", line)
                    if m:
                        out.append(m.group(1))
        elif lower.endswith(".gltf"):
            with open(path, "r", errors="replace") as f:
                doc = json.load(f)
            for item in doc.get("buffers", []) + doc.get("images", []):
                uri = item.get("uri")
                if isinstance(uri, str) and not uri.startswith("data:"):
                    out.append(uri)
    except (OSError, ValueError):
        pass  # the importer on the worker reports what is wrong with the file
    return out


def shipped(scene: Scene) -> Union[Scene, _Shipped]:
    """The scene with its relative mesh files read here, to be sent as bytes."""
    if scene.kind == "builtin":
        return scene
    base = os.fspath(scene.base_dir)
    files: Dict[str, bytes] = {}
    pending = [f for f in scene.mesh_files() if not os.path.isabs(f)]
    while pending:
        rel = os.path.normpath(pending.pop())
        if rel in files:
            continue
        with open(os.path.join(base, rel), "rb") as f:
            files[rel] = f.read()
        folder = os.path.dirname(rel)
        pending += [os.path.join(folder, c) for c in _companions(os.path.join(base, rel)) if not os.path.isabs(c)]
    depth = max([len(re.findall(r"(?:^|[/\\])\.\.(?=[/\\]|$)", rel)) for rel in files] + [0])
    if scene.kind == "dict":
        source: Any = scene.source
    elif scene.kind == "file":
        source = scene.text
    else:
        source = os.path.basename(os.fspath(scene.source))
    return _Shipped(scene.kind, source, files, depth, scene.camera)


#: Scenes a worker process has built, by the digest of their description: a
#: later render of the same scene on this worker reuses the build.
_WORKER_SCENES: "collections.OrderedDict[str, Scene]" = collections.OrderedDict()
_WORKER_SCENES_KEPT = 4


def _digest(payload: Union[Scene, _Shipped]) -> str:
    return hashlib.sha256(pickle.dumps(payload, protocol=4)).hexdigest()


def _worker_scene(payload: Union[Scene, _Shipped], digest: str) -> Scene:
    scene = _WORKER_SCENES.get(digest)
    if scene is None:
        scene = payload if isinstance(payload, Scene) else payload.scene()
        _WORKER_SCENES[digest] = scene
        while len(_WORKER_SCENES) > _WORKER_SCENES_KEPT:
            _WORKER_SCENES.popitem(last=False)
    else:
        _WORKER_SCENES.move_to_end(digest)
    return scene


def _render_tile(payload, digest: str, options: Dict[str, Any], window: Tuple[int, int, int, int]):
    from ._lamplight import render_array

    array, _, layers = render_array(_worker_scene(payload, digest), window=window, progress=None, **options)
    # With the denoiser's features asked for (a denoised render), they come back too.
    return (array, layers["albedo"], layers["normal"]) if "albedo" in layers else array


def _render_frame(payload, digest: str, camera: Optional[dict], options: Dict[str, Any]) -> np.ndarray:
    from ._lamplight import render_array

    scene = _worker_scene(payload, digest)
    if camera is not None:
        scene = scene.with_camera(camera)
    array, _, _ = render_array(scene, progress=None, **options)
    return array


#: Settings a split render cannot honour: each tile is a window of its own,
#: tiles stopped by a clock would end at different passes, and only the image
#: comes back from the workers.
_LOCAL_ONLY = ("window", "time_limit", "exr_layers")

#: What a task uses when not told: one thread (a worker runs as many tasks at
#: once as it has threads) and the box filter.
_TASK_DEFAULTS = {"threads": 1, "filter": "box"}


def _options(scene: Scene, settings: Dict[str, Any]) -> Dict[str, Any]:
    """The keywords each task renders with: ``settings`` checked here by the
    request layer, with the size, integrator and seed resolved so that every
    tile cuts the same image."""
    width, height, _, integrator, seed = resolve(scene, **settings)
    # spp as given, not resolved: the scene's own (adaptive) sampling then
    # resolves on the worker as it does locally.
    return dict(settings, width=width, height=height, integrator=integrator, seed=seed)


def _gather(client, futures, progress, desc: str, unit: str) -> list:
    """The results of ``futures`` in order, reporting each finished one to
    ``progress``; on any error (Ctrl-C included) the remaining tasks are cancelled."""
    from distributed import as_completed

    callback, close = progress_reporter(progress, desc=desc, unit=unit)
    try:
        for done, _ in enumerate(as_completed(futures), start=1):
            if callback is not None:
                callback(done, len(futures))
        return client.gather(futures)
    except BaseException:
        client.cancel(futures)
        raise
    finally:
        close()


@with_settings(skip=_LOCAL_ONLY, defaults=_TASK_DEFAULTS, positional=False)
def render(
    scene: SceneLike,
    client,
    *,
    tiles: Tiles = None,
    ship_meshes: bool = False,
    progress=None,
    retries: int = 2,
    base_dir=None,
    **settings: Any,
) -> Image:
    """Renders ``scene`` on the cluster of ``client`` (a ``distributed.Client``),
    one task per tile, and returns the same :class:`~lamplight.Image`, byte for
    byte, as ``lamplight.render`` with the same settings.

    ``tiles`` is the number of tiles (default 64, cut into a near-square grid)
    or ``(columns, rows)``. ``threads`` is the threads each task uses (default
    1: a worker runs as many tasks at once as it has threads). ``ship_meshes``
    sends mesh files from here instead of reading them on the workers.
    ``progress`` reports finished tiles as for ``lamplight.render``; ``retries``
    re-runs a task that raised (a worker that died is handled by Dask anyway).
    Every setting of ``lamplight.render`` but ``window``, ``time_limit`` and
    ``exr_layers`` is here and means the same; ``denoise`` denoises the
    assembled image here (never tile by tile, whose edges would show), which
    equals the local denoised render; adaptive sampling (``antialias``,
    ``noise_threshold``, ``min_spp``) decides per pixel from the pixel and its
    neighbours, so the tiles stitch to the local image.
    """
    s = as_scene(scene, base_dir)
    # Denoised as a whole once assembled, never tile by tile: a tile's edge
    # would be a seam. The tiles bring back the feature layers for it.
    denoise = settings.get("denoise")
    denoise = bool(s.defaults().get("denoise")) if denoise is None else denoise
    if denoise:
        settings = dict(settings, denoise=False, exr_layers=["albedo", "normal"])
    options = _options(s, settings)
    if s.defaults().get("crop") is not None:
        # Not yet: tiles of a crop did not reproduce the local render's bytes (unresolved).
        raise ValueError("lamplight.dask.render does not split a scene with [render] crop yet; render it with lamplight.render")
    windows = tile_windows(options["width"], options["height"], tiles)
    payload = shipped(s) if ship_meshes else s
    digest = _digest(payload)
    [remote] = client.scatter([payload], broadcast=True, hash=False)
    token = uuid.uuid4().hex[:12]
    futures = [
        client.submit(_render_tile, remote, digest, options, w, key=f"lamplight-tile-{token}-{i}", retries=retries)
        for i, w in enumerate(windows)
    ]
    parts = _gather(client, futures, progress, "lamplight (dask)", "tile")
    planes = 3 if denoise else 1
    out = np.empty((planes, options["height"], options["width"], 3), dtype=np.float32)
    for (x0, y0, w, h), part in zip(windows, parts):
        out[:, y0 : y0 + h, x0 : x0 + w] = part
    image = Image(out[0])
    if denoise:
        # Here, with this machine's cores, as the local render does.
        image = Image(denoise_array(out[0], out[1], out[2], 0))
    image.stats = {"tiles": len(windows)}
    return image


@with_settings(skip=_LOCAL_ONLY, defaults=_TASK_DEFAULTS, positional=False)
def render_frames(
    scenes: Union[SceneLike, Sequence[SceneLike]],
    client,
    cameras: Optional[Sequence[Dict[str, Any]]] = None,
    *,
    ship_meshes: bool = False,
    progress=None,
    retries: int = 2,
    base_dir=None,
    **settings: Any,
) -> List[Image]:
    """Renders the frames of an animation on the cluster, one task per frame,
    and returns one :class:`~lamplight.Image` per frame, in order.

    Either ``scenes`` is a list of scenes (each is scattered once), or it is
    one scene and ``cameras`` a camera path: a list of dicts with the keys of a
    scene file's ``[camera]`` table (the scene is scattered once and each frame
    replaces its camera). Other arguments are as for :func:`render`; sizes and
    samples not given come from each frame's scene.
    """
    if cameras is not None:
        base = as_scene(scenes, base_dir)  # type: ignore[arg-type]
        frames = [(base, dict(c)) for c in cameras]
        payloads = [shipped(base) if ship_meshes else base]
        index = [0] * len(frames)
    else:
        if isinstance(scenes, (str, dict, Scene, os.PathLike)):
            raise TypeError("render_frames takes a list of scenes, or one scene and cameras=[...]")
        built = [as_scene(s, base_dir) for s in scenes]
        frames = [(s, None) for s in built]
        payloads = [shipped(s) if ship_meshes else s for s in built]
        index = list(range(len(frames)))
    if not frames:
        return []
    options = [_options(s, settings) for s, _ in frames]
    if cameras is not None and settings.get("width") is None and settings.get("height") is None:
        # A camera path keeps one size: the scene's.
        options = [options[0]] * len(frames)
    digests = [_digest(p) for p in payloads]
    remote = client.scatter(payloads, broadcast=True, hash=False)
    token = uuid.uuid4().hex[:12]
    futures = [
        client.submit(
            _render_frame, remote[index[i]], digests[index[i]], camera, options[i], key=f"lamplight-frame-{token}-{i}", retries=retries
        )
        for i, (_, camera) in enumerate(frames)
    ]
    parts = _gather(client, futures, progress, "lamplight (dask frames)", "frame")
    return [Image(p) for p in parts]


__all__ = ["render", "render_frames", "tile_windows"]
