"""``lamplight.dask.render_frames``: the frames of an animation as tasks on a
Dask cluster, each written to its file as soon as it is done.

Who writes: **the worker that finishes a frame**, to ``out`` (made absolute
on the client), atomically (a temporary name, then a rename: the same writer
as ``lamplight render``). So ``out`` must be storage that the workers and the
client share (one machine's disk for a ``LocalCluster``; NFS, Lustre or the
like on a cluster), frames never travel back through the client, and a frame
is on disk the moment its task ends, whatever becomes of the client.

Resuming: the client lists the frames whose files exist and submits only the
others (a worker checks again before it renders), so a job killed at any point
and started again renders each missing frame once and none twice. A frame in
flight when the job died has no file (the rename had not happened) and is
rendered by the next run.

Failures: a frame whose worker dies is run again by the scheduler, up to
Dask's ``distributed.scheduler.allowed-failures`` (3 by default), then fails
with ``KilledWorker``; a frame whose task raises is tried ``retries`` more
times. Neither stops the other frames: :class:`FramesFailed` names each
failed frame with its error once all the others are written.

Tasks are named by frame (``lamplight-frame-0007-<token>``), so the dashboard
groups them as ``lamplight-frame`` and its task stream shows each frame's
number; with few frames and many worker threads, a frame's tiles are tasks
(``lamplight-frame-tile-0007-3-<token>``) and a small task stitches and writes
it.
"""

from __future__ import annotations

import math
import os
import time
import uuid
from dataclasses import dataclass, field
from typing import Any, Dict, List, Optional, Sequence, Tuple, Union

import numpy as np

from ._dask_tasks import FEATURE_LAYERS, _LOCAL_ONLY, _TASK_DEFAULTS, _digest, _options, _worker_scene, send, shipped, tile_windows, with_features
from ._lamplight import Scene, check_video, denoise_array
from ._render import SceneLike, as_scene, progress_reporter, with_settings
from .frames import Frames, frame_list, frame_paths, make_video
from .image import Image


class FramesFailed(RuntimeError):
    """Frames that kept failing, raised once every other frame is done.

    ``failed`` maps each failed frame's number to its exception (a
    ``KilledWorker`` for a frame whose workers kept dying); ``done`` lists the
    frames that finished; ``images`` holds their images when they were
    returned rather than written (``out=None``)."""

    def __init__(self, failed: Dict[int, BaseException], done: List[int], images: Optional[Dict[int, Image]] = None):
        self.failed = dict(sorted(failed.items()))
        self.done = sorted(done)
        self.images = images or {}
        said = "; ".join(f"frame {f}: {type(e).__name__}: {e}" for f, e in self.failed.items())
        total = len(self.failed) + len(self.done)
        super().__init__(f"{len(self.failed)} of {total} frames failed (the other {len(self.done)} finished): {said}")


@dataclass
class FramesWritten:
    """What :func:`render_frames` with ``out`` did: the frames it rendered and
    wrote, those it skipped because their files existed, every frame's file,
    the seconds each rendered frame's task took on its worker, and the video.
    A frame written by this call whose worker then died before the client
    heard of it runs again, finds its file and is listed as skipped."""

    written: List[int]
    skipped: List[int]
    paths: Dict[int, str]
    seconds: Dict[int, float] = field(default_factory=dict)
    video: Optional[str] = None


def _save(array: np.ndarray, transfer: str, path: str) -> None:
    os.makedirs(os.path.dirname(path), exist_ok=True)
    Image(array).save(path, transfer=transfer)  # atomic: a temporary name, then a rename


def _frame_task(payload, digest: str, camera: Optional[dict], options: Dict[str, Any], path: Optional[str], overwrite: bool):
    """Renders one frame (``options`` holds its ``frame`` for an animated
    scene): its array, or, given ``path``, the frame written there and a note."""
    from ._lamplight import render_array

    if path is not None and not overwrite and os.path.exists(path):
        # Written by a run that ended before the client heard of it.
        return {"rendered": False}
    start = time.perf_counter()
    scene = _worker_scene(payload, digest)
    if camera is not None:
        scene = scene.with_camera(camera)
    array, stats, _ = render_array(scene, progress=None, **options)
    if path is None:
        return array
    _save(array, stats.get("transfer", "srgb"), path)
    return {"rendered": True, "seconds": time.perf_counter() - start}


def _tile_task(payload, digest: str, camera: Optional[dict], options: Dict[str, Any], window: Tuple[int, int, int, int]):
    from ._lamplight import render_array

    scene = _worker_scene(payload, digest)
    if camera is not None:
        scene = scene.with_camera(camera)
    array, _, layers = render_array(scene, window=window, progress=None, **options)
    return with_features(array, layers)


def _stitch_task(size: Tuple[int, int], windows, denoise: bool, transfer: str, path: Optional[str], *parts):
    """A frame from its tiles, denoised whole (a tile's edge would be a seam), then written."""
    width, height = size
    out = np.empty((1 + len(FEATURE_LAYERS) if denoise else 1, height, width, 3), dtype=np.float32)
    for (x0, y0, w, h), part in zip(windows, parts):
        out[:, y0 : y0 + h, x0 : x0 + w] = part
    image = denoise_array(out[0], out[1], out[2], 0, out[3]) if denoise else out[0]
    if path is None:
        return image
    _save(image, transfer, path)
    return {"rendered": True}


def _remove_stale_temporaries(paths: List[str]) -> None:
    """Removes what a killed job's writes of ``paths`` left: the atomic
    writer's ``.<name>.<random>.tmp`` beside each (a process killed by SIGKILL
    cannot remove its own), so that resumed jobs do not pile them up."""
    by_folder: Dict[str, set] = {}
    for path in paths:
        by_folder.setdefault(os.path.dirname(path), set()).add(os.path.basename(path))
    for folder, names in by_folder.items():
        try:
            entries = os.listdir(folder)
        except OSError:
            continue  # not made yet: nothing left there
        for entry in entries:
            stem, dot, rest = entry[1:].rpartition(".tmp")[0].rpartition(".")
            if entry.startswith(".") and entry.endswith(".tmp") and dot and stem in names:
                try:
                    os.remove(os.path.join(folder, entry))
                except OSError:
                    pass  # gone already, or not ours to remove


@dataclass
class _Frame:
    number: int
    payload: int  # index into the payloads sent
    camera: Optional[dict]
    scene: Scene


def _jobs(scenes, cameras, frames: Frames, base_dir) -> Tuple[List[_Frame], List[Scene], bool]:
    """The frames to render and the scenes to send; whether they are one animated scene's."""
    if cameras is not None:
        base = as_scene(scenes, base_dir)
        return [_Frame(i, 0, dict(c), base) for i, c in enumerate(cameras)], [base], False
    if isinstance(scenes, (str, dict, Scene, os.PathLike)):
        scene = as_scene(scenes, base_dir)
        return [_Frame(f, 0, None, scene) for f in frame_list(frames, scene)], [scene], True
    built = [as_scene(s, base_dir) for s in scenes]
    return [_Frame(i, i, None, s) for i, s in enumerate(built)], built, False


def _tiles_per_frame(tiles, client, frames: int, scene: Scene) -> int:
    """1 (a task per frame) unless the frames are fewer than the cluster's
    threads: then enough tiles that each thread has about two tasks."""
    if tiles is not None:
        if not isinstance(tiles, int) or isinstance(tiles, bool) or tiles < 1:
            raise ValueError(f"tiles must be a whole number of tiles per frame, at least 1, got {tiles!r}")
        return tiles
    if scene.defaults().get("crop") is not None:
        return 1  # tiles of a crop do not reproduce the local render (lamplight.dask.render refuses them)
    threads = sum(client.nthreads().values()) or 1
    return 1 if frames >= threads else math.ceil(2 * threads / frames)


@with_settings(skip=_LOCAL_ONLY + ("frame",), defaults=_TASK_DEFAULTS, positional=False)
def render_frames(
    scenes: Union[SceneLike, Sequence[SceneLike]],
    client,
    cameras: Optional[Sequence[Dict[str, Any]]] = None,
    *,
    frames: Frames = None,
    out: Optional[Union[str, "os.PathLike[str]"]] = None,
    overwrite: bool = False,
    video: Optional[Union[str, "os.PathLike[str]"]] = None,
    tiles: Optional[int] = None,
    ship_meshes: bool = False,
    progress=None,
    retries: int = 2,
    base_dir=None,
    **settings: Any,
) -> Union[List[Image], FramesWritten]:
    """Renders the frames of an animation on the cluster of ``client``.

    ``scenes`` is one scene with an ``[animation]`` (``frames``: ``"1-48"``, a
    ``(start, end)`` pair, a range or a list; default its own frames); or a list
    of scenes, one frame each; or one scene and ``cameras``, a camera path
    (dicts with the keys of ``[camera]``, one frame each).

    With ``out`` (a path with a run of ``#`` for the frame number, as
    ``lamplight render -o out/frame_####.png``), each frame is written there by
    its worker as soon as it is done, frames whose file exists are skipped
    (``overwrite=True`` renders them again), ``video`` (``.mp4``, ``.webm``,
    ``.gif``) is then made from them with ffmpeg (as ``--video``), and a
    :class:`FramesWritten` is returned. Without ``out`` the images come back,
    one :class:`~lamplight.Image` per frame, in order.

    A frame's pixels are the bytes of ``lamplight render --frames N`` and of
    ``lamplight.render(scene, frame=N)``. ``tiles`` splits each frame into that
    many tiles (default: whole frames, unless the frames are fewer than the
    cluster's threads). ``progress`` shows finished frames of the total and the
    time left (a tqdm bar, or a callable ``(done, total)``). A frame that keeps
    failing (its task raised ``retries + 1`` times, or its workers died more
    than Dask's ``allowed-failures``) does not stop the others:
    :class:`FramesFailed` names it with its error once they are done. Other
    arguments are as for :func:`lamplight.dask.render`.
    """
    if settings.get("animation") is not None and isinstance(scenes, (str, os.PathLike)):
        # The frames follow the glTF animation chosen, as `lamplight render --animation`'s do.
        scenes = Scene.from_file(os.fspath(scenes), animation=settings["animation"])
    jobs, scenes_used, animated = _jobs(scenes, cameras, frames, base_dir)
    if (out is not None or video is not None) and not animated:
        raise TypeError("out= and video= write the frames of one animated scene; a list of scenes or a camera path comes back as images")
    if frames is not None and not animated:
        raise TypeError("frames= numbers the frames of one animated scene; a list of scenes or a camera path has its own")
    if video is not None and out is None:
        raise TypeError("video= encodes frames written to files: give out= too (out=\"frames/frame_####.png\")")
    if not jobs:
        return FramesWritten([], [], {}) if out is not None else []
    paths = dict(zip([j.number for j in jobs], frame_paths(out, [j.number for j in jobs]))) if out is not None else {}
    if video is not None:
        check_video(os.fspath(video), paths[jobs[0].number])
        numbers = [j.number for j in jobs]
        if numbers != list(range(numbers[0], numbers[0] + len(numbers))):
            raise ValueError("a video's frames must be consecutive, such as \"1-48\"")
    todo = [j for j in jobs if out is None or overwrite or not os.path.exists(paths[j.number])]
    skipped = sorted({j.number for j in jobs} - {j.number for j in todo})
    _remove_stale_temporaries([paths[j.number] for j in todo] if out is not None else [])
    written: List[int] = []
    seconds: Dict[int, float] = {}
    if todo:
        results = _run(client, todo, scenes_used, paths, overwrite, cameras is not None, animated, tiles, ship_meshes, progress, retries, settings)
        if out is None:
            return [Image(results[j.number]) for j in jobs]
        for number, note in sorted(results.items()):
            if note["rendered"]:
                written.append(number)
                if "seconds" in note:
                    seconds[number] = note["seconds"]
            else:
                skipped.append(number)
    result = FramesWritten(written, sorted(skipped), paths, seconds)
    if video is not None:
        scene = scenes_used[0]
        make_video(out, video, [j.number for j in jobs], scene=scene)
        result.video = os.path.abspath(os.fspath(video))
    return result


def _run(client, todo: List[_Frame], scenes: List[Scene], paths, overwrite, camera_path, animated, tiles, ship_meshes, progress, retries, settings):
    """Submits the frames ``todo`` and waits for them all: ``{frame: result}``,
    or :class:`FramesFailed` once the frames that can finish have."""
    from distributed import as_completed

    first = todo[0].scene
    denoise = settings.get("denoise")
    denoise = bool(first.defaults().get("denoise")) if denoise is None else denoise
    per_frame = _tiles_per_frame(tiles, client, len(todo), first)
    tiled = dict(settings, denoise=False, exr_layers=list(FEATURE_LAYERS)) if denoise and per_frame > 1 else settings
    options = {id(s): _options(s, tiled) for s in scenes}
    if camera_path and settings.get("width") is None and settings.get("height") is None:
        options = {k: options[id(scenes[0])] for k in options}  # a camera path keeps one size: the scene's
    payloads = [shipped(s) if ship_meshes else s for s in scenes]
    digests = [_digest(p) for p in payloads]
    token = uuid.uuid4().hex[:12]
    remote = send(client, payloads, token)
    # Each frame's arguments: (payload, digest, camera, options, path).
    args = []
    for job in todo:
        opts = dict(options[id(job.scene)], frame=job.number) if animated else options[id(job.scene)]
        args.append((remote[job.payload], digests[job.payload], job.camera, opts, paths.get(job.number)))
    names = [f"lamplight-frame-{job.number:04d}-{token}" for job in todo]
    # One graph for all the frames (client.map), so that the scheduler sees the
    # whole group and queues it, handing a worker a frame only when it has a
    # free thread: a dying worker then takes down only the frames it runs.
    if per_frame == 1:
        columns = [list(c) for c in zip(*args)]
        mapped = client.map(_frame_task, *columns, [overwrite] * len(todo), key=names, retries=retries, pure=False)
    else:
        tiles_of = [tile_windows(a[3]["width"], a[3]["height"], per_frame) for a in args]
        cells = [(a, w, f"lamplight-frame-tile-{job.number:04d}-{i}-{token}") for job, a, ws in zip(todo, args, tiles_of) for i, w in enumerate(ws)]
        columns = [list(c) for c in zip(*[a[:4] for a, _, _ in cells])]
        parts = client.map(_tile_task, *columns, [w for _, w, _ in cells], key=[k for _, _, k in cells], retries=retries, pure=False)
        mapped, at = [], 0
        for job, a, windows, name in zip(todo, args, tiles_of, names):
            size = (a[3]["width"], a[3]["height"])
            transfer = job.scene.defaults()["transfer"]
            mine = parts[at : at + len(windows)]
            at += len(windows)
            mapped.append(client.submit(_stitch_task, size, windows, denoise, transfer, a[4], *mine, key=name, retries=retries))
    futures = {future: job.number for future, job in zip(mapped, todo)}
    callback, close = progress_reporter(progress, desc="lamplight frames (dask)", unit="frame")
    results: Dict[int, Any] = {}
    failed: Dict[int, BaseException] = {}
    try:
        for done, future in enumerate(as_completed(list(futures)), start=1):
            number = futures[future]
            if future.status == "finished":
                results[number] = future.result()
            else:
                # Kept going: the other frames finish, and this one is reported with them.
                failed[number] = future.exception()
            future.release()
            if callback is not None:
                callback(done, len(futures))
    except BaseException:
        client.cancel(list(futures))
        raise
    finally:
        close()
    if failed:
        images = {n: Image(r) for n, r in results.items() if isinstance(r, np.ndarray)}
        raise FramesFailed(failed, list(results), images)
    return results
