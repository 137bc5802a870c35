"""``lamplight.render``: a scene of any kind to an :class:`~lamplight.Image`."""

from __future__ import annotations

import os
import sys
import warnings
from typing import Any, Callable, Optional, Sequence, Tuple, Union

from . import _lamplight
from ._lamplight import Scene
from .image import Image

SceneLike = Union[str, "os.PathLike[str]", dict, Scene]
Progress = Union[None, bool, Callable[[int, int], Any]]


def as_scene(scene: SceneLike, base_dir: Optional[Union[str, "os.PathLike[str]"]] = None) -> Scene:
    """``scene`` as a :class:`Scene`: a Scene as it is; a dict through
    :meth:`Scene.from_dict` (relative mesh paths against ``base_dir``, default
    the current directory); a string or path as a built-in name (no separator,
    no extension) or a scene or mesh file."""
    if isinstance(scene, Scene):
        return scene
    if isinstance(scene, dict):
        return Scene.from_dict(scene, os.fspath(base_dir) if base_dir is not None else None)
    if isinstance(scene, (str, os.PathLike)):
        return Scene(os.fspath(scene))
    raise TypeError(f"a scene is a built-in name, a file path, a dict or a lamplight.Scene, got {type(scene).__name__}")


def load(path: Union[str, "os.PathLike[str]"]) -> Scene:
    """Reads a scene file (``.toml``) or a mesh file (``.obj``, ``.ply``, ``.gltf``, ``.glb``)."""
    return Scene.from_file(os.fspath(path))


def resolve(scene: Scene, width, height, spp, integrator, seed) -> Tuple[int, int, int, str, int]:
    """Size, samples, integrator and seed: the arguments, else the scene's own
    settings, else the defaults, resolved by the same request layer as the
    command line (with only a width or only a height the other side keeps the
    scene's aspect)."""
    _check_ints(width=width, height=height, spp=spp, seed=seed)
    return _lamplight.resolve_settings(scene, width, height, spp, integrator, seed)


def _check_ints(**values) -> None:
    """Python's own types first, so that ``width=2.5`` says what it is; the ranges
    (``threads=-1``, ``width=2**32``) are checked by the extension, naming the bound."""
    for name, value in values.items():
        if value is not None and (isinstance(value, bool) or not isinstance(value, int)):
            raise TypeError(f"{name} must be an int, got {type(value).__name__}")


def _in_notebook() -> bool:
    return "ipykernel" in sys.modules


_warned_no_tqdm = False


def _warn_no_tqdm() -> None:
    """Says once why ``progress=True`` shows nothing."""
    global _warned_no_tqdm
    if not _warned_no_tqdm:
        _warned_no_tqdm = True
        warnings.warn(
            "progress=True shows a bar only with tqdm installed (pip install tqdm); rendering without one",
            stacklevel=4,
        )


def progress_reporter(progress: Progress, desc: str = "lamplight", unit: str = "tile"):
    """(callback, closer) for ``progress``: a callable is called with
    ``(done, total)``; ``True`` shows a tqdm bar (where tqdm is installed);
    ``None`` does so only on a terminal or in Jupyter; ``False`` shows nothing."""
    if progress is False:
        return None, lambda: None
    if callable(progress):
        return progress, lambda: None
    if progress is None and not (_in_notebook() or (sys.stderr is not None and sys.stderr.isatty())):
        return None, lambda: None
    try:
        from tqdm.auto import tqdm
    except ImportError:
        if progress is True:
            _warn_no_tqdm()
        return None, lambda: None
    bar = tqdm(total=0, desc=desc, unit=unit, leave=False)

    def report(done: int, total: int) -> None:
        if bar.total != total:
            bar.total = total
        bar.n = done
        bar.refresh()

    return report, bar.close


def render(
    scene: SceneLike,
    width: Optional[int] = None,
    height: Optional[int] = None,
    spp: Optional[int] = None,
    integrator: Optional[str] = None,
    threads: int = 0,
    seed: Optional[int] = None,
    max_depth: Optional[int] = None,
    progress: Progress = None,
    time_limit: Optional[float] = None,
    filter: Optional[str] = None,
    window: Optional[Tuple[int, int, int, int]] = None,
    base_dir: Optional[Union[str, "os.PathLike[str]"]] = None,
    environment: Optional[Union[str, "os.PathLike[str]"]] = None,
    exr_layers: Optional[Sequence[str]] = None,
    clamp: Optional[float] = None,
    antialias: Optional[Union[bool, float]] = None,
    noise_threshold: Optional[float] = None,
    min_spp: Optional[int] = None,
) -> Image:
    """Renders ``scene`` and returns an :class:`Image`: a float32 array
    ``(height, width, 3)`` of linear radiance, the numbers ``lamplight render``
    writes to an ``.exr`` file for the same settings.

    Every option of ``lamplight render`` is here, resolved by the same code:
    ``width``, ``height``, ``spp``, ``integrator`` (``"whitted"`` or ``"path"``)
    and ``seed`` default to the scene's own settings; ``threads=0`` uses every
    core (the image does not depend on it). ``progress`` is a callable
    ``(tiles_done, tiles_total)``, ``True`` for a tqdm bar, ``False`` for none;
    ``None`` shows a bar on a terminal or in Jupyter when tqdm is installed.
    Ctrl-C stops the render and raises ``KeyboardInterrupt``. ``window =
    (x0, y0, w, h)`` renders only those pixels of the full image (exactly the
    values the full render has there). ``time_limit`` (seconds), ``filter``
    (``"box"``, ``"tent"``, ``"gaussian"``), ``environment`` (an ``.exr`` or ``.hdr``
    equirectangular map lighting the scene) and ``exr_layers`` (``"variance"``,
    ``"samples"``: kept in ``image.layers`` and written by ``image.save`` to an
    ``.exr`` file) concern the path tracer. ``clamp`` scales every sample
    whose brightest channel exceeds it down to it: fewer fireflies, but biased
    (off by default, as ``--clamp``).

    Sampling is adaptive unless ``spp`` says otherwise. Whitted renders
    without an ``spp`` (here or in the scene) are anti-aliased as POV-Ray's
    ``+A`` does: 16 samples in each pixel whose colour differs from a
    neighbour's by more than ``antialias`` (a threshold, 0.3 by default;
    ``False`` turns it off). ``noise_threshold`` (the path tracer, Cycles'
    adaptive sampling) stops each pixel once its noise (the standard error of
    its mean over the square root of its brightness) is below it at two checks
    in a row, after ``min_spp`` samples (16); ``spp`` is then the most a pixel
    takes (1024 by default). ``image.stats["mean_samples_per_pixel"]``
    says what was spent, and ``exr_layers=["samples"]`` where.
    """
    s = as_scene(scene, base_dir)
    _check_ints(width=width, height=height, spp=spp, seed=seed, max_depth=max_depth, threads=threads, min_spp=min_spp)
    callback, close = progress_reporter(progress)
    try:
        array, stats, layers = _lamplight.render_array(
            s,
            width,
            height,
            spp,
            integrator,
            threads,
            seed,
            max_depth,
            window,
            callback,
            time_limit,
            filter,
            os.fspath(environment) if environment is not None else None,
            list(exr_layers) if exr_layers is not None else None,
            clamp,
            antialias,
            noise_threshold,
            min_spp,
        )
    finally:
        close()
    for warning in stats.get("warnings", []):
        warnings.warn(warning, stacklevel=2)
    image = Image(array)
    image.stats = stats
    image.layers = layers
    return image
