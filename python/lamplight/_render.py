"""``lamplight.render``: a scene of any kind to an :class:`~lamplight.Image`."""

from __future__ import annotations

import difflib
import functools
import inspect
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


#: ``(name, annotation, explain)`` of every render setting, in order: the one
#: table (``crates/lamplight-py/src/settings.rs``) that ``render_array``,
#: ``Scene.explain``, the wrappers here and in :mod:`lamplight.dask` and the
#: type stub take their keywords from.
RENDER_KEYWORDS: Tuple[Tuple[str, str, bool], ...] = tuple(_lamplight.render_keywords())

#: The settings of the table that decide how a mesh file rendered directly is
#: built (``smooth``, ``keep_auto_lights``, ``animation``): :func:`load` takes them too.
BUILD_KEYWORDS: Tuple[str, ...] = tuple(_lamplight.build_keywords())


def load(path: Union[str, "os.PathLike[str]"], **settings: Any) -> Scene:
    """Reads a scene file (``.toml``, ``.xml``) or a mesh file (``.obj``,
    ``.ply``, ``.gltf``, ``.glb``). A mesh file takes the settings that decide
    how it is built, as the scene's own (a render's keywords override them):
    ``smooth=True`` shades its meshes without normals smooth, as
    ``lamplight render --smooth``; ``keep_auto_lights`` (``True``, ``False``
    or ``"auto"``, the default) keeps the automatic lights of a bare model
    beside the file's own, as ``--keep-auto-lights``; ``animation`` (a name
    or an index) chooses which animation of a glTF file plays, as
    ``--animation``, and the scene's frames follow it."""
    for key in settings:
        if key not in BUILD_KEYWORDS:
            near = difflib.get_close_matches(key, BUILD_KEYWORDS, n=1)
            hint = f" (did you mean '{near[0]}'?)" if near else ""
            raise TypeError(f"load() got an unexpected keyword argument '{key}'{hint}")
    return Scene.from_file(os.fspath(path), **settings)


load.__signature__ = inspect.Signature(  # type: ignore[attr-defined]
    [inspect.Parameter("path", inspect.Parameter.POSITIONAL_OR_KEYWORD, annotation='Union[str, "os.PathLike[str]"]')]
    + [
        inspect.Parameter(name, inspect.Parameter.KEYWORD_ONLY, default=None, annotation=annotation)
        for name, annotation, _ in RENDER_KEYWORDS
        if name in BUILD_KEYWORDS
    ],
    return_annotation=Scene,
)


def with_settings(
    skip: Sequence[str] = (), defaults: Optional[dict] = None, positional: bool = True
) -> Callable[[Callable[..., Any]], Callable[..., Any]]:
    """Gives ``func(head..., *, extra..., **settings)`` the signature ``head...,
    <every render setting>, *, extra...``, the settings in the table's order
    (positional too when ``positional``), each defaulting to ``defaults[name]``
    or ``None``, less those in ``skip``. The settings reach ``func`` as keywords;
    a misspelt one is a ``TypeError`` naming the nearest setting."""

    def wrap(func: Callable[..., Any]) -> Callable[..., Any]:
        own = inspect.signature(func)
        head = [p for p in own.parameters.values() if p.kind is inspect.Parameter.POSITIONAL_OR_KEYWORD]
        extra = [p for p in own.parameters.values() if p.kind is inspect.Parameter.KEYWORD_ONLY]
        kind = inspect.Parameter.POSITIONAL_OR_KEYWORD if positional else inspect.Parameter.KEYWORD_ONLY
        settings = [
            inspect.Parameter(name, kind, default=(defaults or {}).get(name), annotation=annotation)
            for name, annotation, _ in RENDER_KEYWORDS
            if name not in skip
        ]
        signature = own.replace(parameters=head + settings + extra)
        names = [p.name for p in signature.parameters.values()]

        @functools.wraps(func)
        def wrapper(*args, **kwargs):
            for key in kwargs:
                if key not in names:
                    near = difflib.get_close_matches(key, names, n=1)
                    hint = f" (did you mean '{near[0]}'?)" if near else ""
                    raise TypeError(f"{func.__name__}() got an unexpected keyword argument '{key}'{hint}")
            bound = signature.bind(*args, **kwargs)
            bound.apply_defaults()
            values = dict(bound.arguments)
            leading = [values.pop(p.name) for p in head]
            return func(*leading, **values)

        wrapper.__signature__ = signature  # type: ignore[attr-defined]
        return wrapper

    return wrap


def resolve(scene: Scene, **settings) -> Tuple[int, int, int, str, int]:
    """Size, samples, integrator and seed: the arguments, else the scene's own
    settings, else the defaults, resolved by the same request layer as the
    command line (with only a width or only a height the other side keeps the
    scene's aspect). Every other setting is checked too."""
    return _lamplight.resolve_settings(scene, **settings)


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


@with_settings()
def render(
    scene: SceneLike,
    *,
    progress: Progress = None,
    base_dir: Optional[Union[str, "os.PathLike[str]"]] = None,
    **settings: Any,
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
    ``.exr`` file; ``"albedo"`` and ``"normal"``, the denoiser's features, for
    any integrator) concern the path tracer. ``denoise=True`` denoises the
    image with Intel Open Image Denoise (``pip install lamplight[denoise]``;
    ``exr_layers=["noisy"]`` keeps the image before it; see
    ``docs/denoise.md``). ``clamp`` scales every sample
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
    takes (1024 by default). A path-traced render given no ``spp`` (here or in
    the scene) samples this way at 0.05. ``image.stats["mean_samples_per_pixel"]``
    says what was spent, and ``exr_layers=["samples"]`` where.
    """
    s = as_scene(scene, base_dir)
    callback, close = progress_reporter(progress)
    try:
        array, stats, layers = _lamplight.render_array(s, progress=callback, **settings)
    finally:
        close()
    for warning in stats.get("warnings", []):
        warnings.warn(warning, stacklevel=2)
    image = Image(array)
    image.stats = stats
    image.layers = layers
    return image
