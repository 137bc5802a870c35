"""What the Dask wrappers (:mod:`lamplight.dask`) send to the workers and run
there: a scene's description as a payload (with its mesh files as bytes, when
shipped), the workers' cache of built scenes, the tile task, and how the
client resolves settings and gathers results."""

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
from typing import Any, Dict, List, Optional, Tuple, Union

from ._lamplight import Scene
from ._render import progress_reporter, resolve

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


def _identity(payload):
    return payload


def send(client, payloads: List[Any], token: str) -> list:
    """The payloads as tasks of their own, which the render tasks depend on.
    Not scattered: Dask moves each to the workers that need it either way, but
    scattered data that every holder of it lost (workers killed one after the
    other) cannot be recovered and cancels every task that needs it, while a
    task's result is computed again."""
    return [client.submit(_identity, p, key=f"lamplight-scene-{i}-{token}", pure=False) for i, p in enumerate(payloads)]


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


#: The layers a tile brings back for denoising the assembled image: the
#: denoiser's guides, and the emitted part it leaves as rendered.
FEATURE_LAYERS = ("albedo", "normal", "emitted")


def with_features(array, layers):
    """A tile's image, with the :data:`FEATURE_LAYERS` after it when they were
    asked for (a denoised render)."""
    return (array, *(layers[name] for name in FEATURE_LAYERS)) if "albedo" in layers else array


def _render_tile(payload, digest: str, options: Dict[str, Any], window: Tuple[int, int, int, int]):
    from ._lamplight import render_array

    array, _, layers = render_array(_worker_scene(payload, digest), window=window, progress=None, **options)
    return with_features(array, layers)


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
