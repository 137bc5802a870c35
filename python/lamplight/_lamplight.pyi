"""Type stubs of the native module ``lamplight._lamplight`` (Rust, PyO3)."""

import os
from typing import Any, Callable, Dict, List, Optional, Sequence, Tuple, Union

import numpy as np
import numpy.typing as npt

_Path = Union[str, "os.PathLike[str]"]
_Float = Union[np.float32, np.float64]

__version__: str

class SceneError(ValueError):
    """A scene that cannot be read or built: the message names the file and
    place (``file:line:col``), or for a dict the key path (``objects[2].radius``)."""

class Scene:
    """A scene from a built-in name, a scene file, a mesh file or a dict.

    It keeps what it was made from and pickles as that; it is built on first
    use and the build is kept, so repeated renders (at any image size) and
    ``intersect`` calls do not rebuild it.
    """

    def __init__(self, scene: Union[str, "os.PathLike[str]", Dict[str, Any]]) -> None:
        """A built-in name (no path separator, no extension), a ``.toml`` scene
        file, a mesh file (``.obj``, ``.ply``, ``.gltf``, ``.glb``) or a dict."""
    @staticmethod
    def builtin(name: str) -> "Scene":
        """The built-in scene ``name`` (see :func:`builtin_names`)."""
    @staticmethod
    def from_file(
        path: _Path,
        *,
        smooth: Optional[bool] = None,
        keep_auto_lights: Optional[Union[bool, str]] = None,
        animation: Optional[Union[str, int]] = None,
    ) -> "Scene":
        """A scene file (``.toml``, read now) or a mesh file (read when built).
        A mesh file takes the settings that decide how it is built (the
        settings table's build keywords), which a render's own override."""
    @staticmethod
    def from_toml(text: str, base_dir: Optional[_Path] = None) -> "Scene":
        """Scene text in the native format; mesh paths relative to ``base_dir`` (default: the current directory)."""
    @staticmethod
    def from_dict(scene: Dict[str, Any], base_dir: Optional[_Path] = None) -> "Scene":
        """A dict with the structure of a scene file (``docs/scene-format.md``);
        numpy arrays and tuples may stand for lists. Mesh paths relative to
        ``base_dir`` (default: the current directory)."""
    def with_camera(self, camera: Dict[str, Any]) -> "Scene":
        """The same scene seen by ``camera`` (the keys of a ``[camera]`` table)."""
    @property
    def kind(self) -> str:
        """``"builtin"``, ``"file"``, ``"dict"`` or ``"mesh"``."""
    @property
    def source(self) -> Any:
        """The built-in name, the file path, or a copy of the dict."""
    @property
    def base_dir(self) -> Optional[str]:
        """Folder that relative mesh paths resolve against (``None`` for built-ins)."""
    @property
    def text(self) -> Optional[str]:
        """The scene file's text, for scenes from ``.toml`` files or text."""
    @property
    def camera(self) -> Optional[Dict[str, Any]]:
        """The camera given to :meth:`with_camera`, if any."""
    def mesh_files(self) -> List[str]:
        """Mesh files the scene reads, as written."""
    @property
    def animation(self) -> Optional[Dict[str, Any]]:
        """The scene's ``[animation]``: ``{"frames": (start, end), "fps": fps}``, or ``None``."""
    def defaults(self) -> Dict[str, Any]:
        """``width``, ``height``, ``spp``, ``seed``, ``integrator`` a render uses when not told,
        ``transfer``, and ``crop``: the ``(x0, y0, w, h)`` of the image the scene renders, or ``None``."""
    def build(self, width: Optional[int] = None, height: Optional[int] = None) -> None:
        """Builds now (errors show here); one build serves every image size, and
        ``width x height`` (default: the scene's size) is only checked."""
    @property
    def warnings(self) -> List[str]:
        """What the importers skipped in the scene's mesh files, one line each
        (``FILE: what``); builds the scene if needed. Building also gives each
        to ``warnings.warn`` (a ``UserWarning``) once."""
    def object_count(self) -> int:
        """Placed shapes in the scene: object ids run from 0 below this."""
    def explain(
        self,
        x: int,
        y: int,
        sample: Optional[int] = None,
        *,
        # BEGIN settings explain generated from crates/lamplight-py/src/settings.rs (LAMPLIGHT_BLESS=1 pytest python/tests/test_keywords.py rewrites)
        width: Optional[int] = None,
        height: Optional[int] = None,
        spp: Optional[int] = None,
        integrator: Optional[str] = None,
        seed: Optional[int] = None,
        max_depth: Optional[int] = None,
        filter: Optional[str] = None,
        environment: Optional[Union[str, os.PathLike[str]]] = None,
        clamp: Optional[float] = None,
        antialias: Optional[Union[bool, float]] = None,
        noise_threshold: Optional[float] = None,
        min_spp: Optional[int] = None,
        memory_budget: Optional[Union[int, str]] = None,
        smooth: Optional[bool] = None,
        keep_auto_lights: Optional[Union[bool, str]] = None,
        frame: Optional[int] = None,
        animation: Optional[Union[str, int]] = None,
        # END settings
    ) -> Dict[str, Any]:
        """Why pixel ``(x, y)`` of the render these settings make has its colour.

        The samples of the pixel (the first 64 in full, the rest summarised in
        ``unrecorded``; or only ``sample``, 0 to ``spp - 1``), as the
        render computes them: for Whitted the ray tree (each ray with its hit,
        the lecture's terms, the Fresnel weights and the rays it spawned), for
        the path tracer each path's vertices (BSDF samples, pdfs, throughput,
        light samples with their MIS weights). Plain dicts and lists, the same
        as ``lamplight explain --json`` prints: ``samples[k]["contributions"]``
        summed in order is ``samples[k]["radiance"]``, and ``value`` is
        the rendered pixel (``sampling``: how adaptive sampling chose its samples). See ``docs/explain.md``.
        """
    def intersect(
        self,
        origins: Union[npt.NDArray[_Float], List[List[float]]],
        directions: Union[npt.NDArray[_Float], List[List[float]]],
        threads: int = 0,
        errors: bool = False,
    ) -> Tuple[npt.NDArray[Any], ...]:
        """Nearest hits of the rays ``origins[i] + s * directions[i]``, ``s > 0``.

        ``origins`` and ``directions`` are ``(N, 3)`` arrays, both float32 or
        both float64, read in place (any strides); a list (or tuple) of
        ``[x, y, z]`` rows is copied into an array of the other argument's
        dtype (float64 when both are lists). Directions need not be unit.
        Runs on ``threads`` threads (0: every core, at most 1024) with the GIL
        released; the answers do not depend on it. Returns
        ``(t, ids, prims, normals)``:

        - ``t``: the distance ``s * |directions[i]|`` from the origin to the
          hit (Embree's ``t`` when the direction is unit), ``inf`` on a miss,
          the input's dtype;
        - ``ids``: the object hit (int64, objects in scene order, ``-1`` on a
          miss);
        - ``prims``: the triangle hit within a mesh object (int64, the mesh's
          face order), ``-1`` on a miss and for shapes that are not meshes;
        - ``normals``: the unit outward geometric normal ``(N, 3)``, zero on a
          miss;
        - ``t_error`` (only with ``errors=True``, a fifth answer): a bound on
          ``|t - t_exact|``, the rounding in each distance including its
          rounding to the input's dtype, ``inf`` on a miss. It says where
          precision is lost: from ``z = 1e17`` a unit sphere is answered at
          ``t = 1e17`` with ``t_error`` about 1,400, far larger than the sphere.
          It holds except for rays within about 1e-8 radians of grazing a
          curved surface, where a quadratic's root is ill-conditioned.

        The same numbers as ``lamplight raycast`` gives for a scene of one mesh
        (its ``T``, ``--objects`` and ``--prims``, to float32 rounding). Zero or
        non-finite directions and non-finite origins miss. Raises ``TypeError``
        for non-arrays or other dtypes and ``ValueError`` for other shapes or
        thread counts.
        """

def builtin_names() -> List[str]:
    """Names of the built-in scenes, the default first."""

def kinds() -> List[Dict[str, Any]]:
    """Every registered kind: ``role`` (shape, light, node, material, texture,
    camera), ``name``, ``summary`` and ``params`` (``name``, ``type``,
    ``default`` (None when required), ``unit``, ``doc``)."""

def scene_from_state(state: Tuple[str, Any, Optional[str], Optional[Dict[str, Any]]]) -> Scene:
    """Rebuilds a pickled :class:`Scene` (used by ``pickle``)."""

def render_array(
    scene: Scene,
    progress: Optional[Callable[[int, int], Any]] = None,
    *,
    # BEGIN settings generated from crates/lamplight-py/src/settings.rs (LAMPLIGHT_BLESS=1 pytest python/tests/test_keywords.py rewrites)
    width: Optional[int] = None,
    height: Optional[int] = None,
    spp: Optional[int] = None,
    integrator: Optional[str] = None,
    threads: Optional[int] = None,
    seed: Optional[int] = None,
    max_depth: Optional[int] = None,
    window: Optional[Tuple[int, int, int, int]] = None,
    time_limit: Optional[float] = None,
    filter: Optional[str] = None,
    environment: Optional[Union[str, os.PathLike[str]]] = None,
    exr_layers: Optional[Sequence[str]] = None,
    denoise: Optional[bool] = None,
    clamp: Optional[float] = None,
    antialias: Optional[Union[bool, float]] = None,
    noise_threshold: Optional[float] = None,
    min_spp: Optional[int] = None,
    memory_budget: Optional[Union[int, str]] = None,
    smooth: Optional[bool] = None,
    keep_auto_lights: Optional[Union[bool, str]] = None,
    frame: Optional[int] = None,
    animation: Optional[Union[str, int]] = None,
    # END settings
) -> Tuple[npt.NDArray[np.float32], Dict[str, Any], Dict[str, npt.NDArray[np.float32]]]:
    """The render under :func:`lamplight.render`: a float32 array ``(h, w, 3)``,
    a dict of statistics and a dict of the extra layers asked for. Settings left
    out or ``None`` come from the scene, then the defaults (the command line's request
    layer). Releases the GIL; Ctrl-C cancels."""

def resolve_settings(
    scene: Scene,
    *,
    # BEGIN settings generated from crates/lamplight-py/src/settings.rs (LAMPLIGHT_BLESS=1 pytest python/tests/test_keywords.py rewrites)
    width: Optional[int] = None,
    height: Optional[int] = None,
    spp: Optional[int] = None,
    integrator: Optional[str] = None,
    threads: Optional[int] = None,
    seed: Optional[int] = None,
    max_depth: Optional[int] = None,
    window: Optional[Tuple[int, int, int, int]] = None,
    time_limit: Optional[float] = None,
    filter: Optional[str] = None,
    environment: Optional[Union[str, os.PathLike[str]]] = None,
    exr_layers: Optional[Sequence[str]] = None,
    denoise: Optional[bool] = None,
    clamp: Optional[float] = None,
    antialias: Optional[Union[bool, float]] = None,
    noise_threshold: Optional[float] = None,
    min_spp: Optional[int] = None,
    memory_budget: Optional[Union[int, str]] = None,
    smooth: Optional[bool] = None,
    keep_auto_lights: Optional[Union[bool, str]] = None,
    frame: Optional[int] = None,
    animation: Optional[Union[str, int]] = None,
    # END settings
) -> Tuple[int, int, int, str, int]:
    """``(width, height, spp, integrator, seed)`` a render with these settings would
    use; every setting is checked as a render checks it."""

def write_image(
    path: _Path,
    array: npt.NDArray[np.float32],
    exposure: float = 0.0,
    tonemap: str = "clamp",
    layers: Optional[Dict[str, npt.NDArray[np.float32]]] = None,
    transfer: str = "srgb",
) -> None:
    """Writes ``(H, W, 3)`` float32 linear radiance as ``.png``, ``.ppm`` or ``.exr``
    (with extra ``layers`` for ``.exr``), atomically; ``transfer`` (``"srgb"``,
    ``"linear"``) is how ``.png``/``.ppm`` store the values."""

def encode_png(array: npt.NDArray[np.float32], exposure: float = 0.0, tonemap: str = "clamp", transfer: str = "srgb") -> bytes:
    """PNG bytes of an ``(H, W, 3)`` float32 image (8-bit, sRGB-encoded or ``transfer="linear"``)."""

def read_exr(path: _Path) -> npt.NDArray[np.float32]:
    """An OpenEXR file's R, G, B as float32 ``(H, W, 3)``."""

def denoise_array(
    color: npt.NDArray[np.float32],
    albedo: Optional[npt.NDArray[np.float32]] = None,
    normal: Optional[npt.NDArray[np.float32]] = None,
    threads: Optional[int] = None,
    emitted: Optional[npt.NDArray[np.float32]] = None,
) -> npt.NDArray[np.float32]:
    """``color`` denoised by Open Image Denoise's HDR ``RT`` filter, guided by
    ``albedo`` and ``normal`` of the same shape when given; with ``emitted``
    only ``color - emitted`` is filtered and ``emitted`` added back;
    ``ValueError`` when the library is missing."""

def frame_range(text: str, name: str) -> Tuple[int, int]:
    """``(start, end)`` of ``"1-48"`` or ``"7"``, as ``--frames`` reads it; the ``ValueError`` names ``name``."""

def frame_paths(pattern: _Path, frames: List[int], name: str) -> List[str]:
    """Each frame's file under ``pattern`` (one run of ``#``, zero-padded), as ``-o`` names them."""

def make_video(pattern: _Path, start: int, end: int, fps: float, video: _Path) -> None:
    """Encodes frames ``start`` to ``end`` of ``pattern`` into ``video`` (``.mp4``, ``.webm``,
    ``.gif``) with ffmpeg; ``FileNotFoundError`` when ffmpeg is not on ``PATH``."""

def check_video(video: _Path, frames: _Path) -> None:
    """``ValueError`` unless ``video`` is ``.mp4``, ``.webm`` or ``.gif`` and ``frames`` (one frame's path) ``.png`` or ``.ppm``."""
