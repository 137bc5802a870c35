"""Rendered images: float32 ``(H, W, 3)`` numpy arrays of linear radiance that
show themselves in Jupyter and save as PNG, PPM or OpenEXR."""

from __future__ import annotations

import os
from typing import Optional, Union

import numpy as np

from . import _lamplight

PathLike = Union[str, "os.PathLike[str]"]


class Image(np.ndarray):
    """A float32 array ``(H, W, 3)`` of linear radiance (an ``np.ndarray``).

    In Jupyter it displays itself as an sRGB PNG (clamped); :meth:`save` writes
    ``.png``/``.ppm`` (8-bit sRGB) or ``.exr`` (linear float, exact).
    ``stats`` holds the render's statistics when it came from a render, and
    ``layers`` the extra layers it asked for (``exr_layers``): ``"variance"``,
    ``"albedo"``, ``"normal"``, ``"noisy"`` and ``"emitted"`` ``(H, W, 3)`` and ``"samples"``
    ``(H, W)``, which :meth:`save` writes beside
    the image into an ``.exr`` file. Slices and views keep both; the result of
    arithmetic (``image * 2``, ``a - b``) is new data and has neither.
    """

    stats: dict
    layers: dict

    def __new__(cls, array) -> "Image":
        return np.asarray(array, dtype=np.float32).view(cls)

    def __array_finalize__(self, obj) -> None:
        # Views and slices keep the render's stats and layers; results of
        # arithmetic get fresh ones (__array_wrap__ below).
        self.stats = getattr(obj, "stats", {})
        self.layers = getattr(obj, "layers", {})

    def __array_wrap__(self, array, context=None, return_scalar=False):
        # A ufunc's result (image * 2, a - b, np.sqrt(a)) is new data: the
        # operand's stats and layers do not describe it.
        if return_scalar:
            result = super().__array_wrap__(array, context, return_scalar)
        else:  # numpy 1 takes no return_scalar
            result = super().__array_wrap__(array, context)
        if isinstance(result, Image) and context is not None:
            result.stats = {}
            result.layers = {}
        return result

    def _is_image(self) -> bool:
        return self.ndim == 3 and self.shape[2] == 3 and self.shape[0] > 0 and self.shape[1] > 0 and self.dtype == np.float32

    def _repr_png_(self):
        if not self._is_image():
            return None
        return _lamplight.encode_png(np.ascontiguousarray(self).view(np.ndarray), 0.0, "clamp", self._transfer(None))

    def _transfer(self, transfer: Optional[str]) -> str:
        # The render's scene says how its PNGs store values (``[render] transfer``).
        return transfer if transfer is not None else self.stats.get("transfer", "srgb")

    def to_png(self, exposure: float = 0.0, tonemap: str = "clamp", transfer: Optional[str] = None) -> bytes:
        """The image as PNG file bytes, after ``exposure`` (stops) and ``tonemap``
        (``"clamp"`` or ``"filmic"``); ``transfer`` is ``"srgb"`` or ``"linear"``,
        by default the rendered scene's own (``srgb`` for other arrays)."""
        return _lamplight.encode_png(_plain(self), exposure, tonemap, self._transfer(transfer))

    def save(self, path: PathLike, exposure: float = 0.0, tonemap: str = "clamp", transfer: Optional[str] = None) -> None:
        """Writes the image to ``path`` (see :func:`save`), with its ``layers``
        when ``path`` is an ``.exr`` file; ``transfer`` as in :meth:`to_png`."""
        exr = os.fspath(path).lower().endswith(".exr")
        layers = {k: np.ascontiguousarray(v, dtype=np.float32) for k, v in self.layers.items()} if exr and self.layers else None
        _lamplight.write_image(os.fspath(path), _plain(self), exposure, tonemap, layers, self._transfer(transfer))


def _plain(array) -> np.ndarray:
    a = np.asarray(array)
    if a.ndim != 3 or a.shape[2] != 3:
        raise ValueError(f"an image must have shape (H, W, 3), got {a.shape}")
    return np.ascontiguousarray(a, dtype=np.float32).view(np.ndarray)


def save(path: PathLike, image, exposure: float = 0.0, tonemap: str = "clamp", transfer: str = "srgb") -> None:
    """Writes ``image`` (an array ``(H, W, 3)`` of linear radiance) to ``path``,
    in the format of its extension: ``.png`` and ``.ppm`` are 8-bit sRGB after
    ``exposure`` (stops) and ``tonemap`` (``"clamp"`` or ``"filmic"``), ``.exr``
    is linear float32, unchanged. The file is written to a temporary name and
    renamed, so a failed write never leaves a broken image. ``transfer="linear"``
    stores the values themselves in ``.png``/``.ppm`` (display-referred numbers)."""
    _lamplight.write_image(os.fspath(path), _plain(image), exposure, tonemap, None, transfer)


def read_exr(path: PathLike) -> Image:
    """Reads an OpenEXR file's R, G, B channels as an :class:`Image`."""
    return Image(_lamplight.read_exr(os.fspath(path)))


def denoise(image, albedo=None, normal=None, threads: Optional[int] = None, emitted=None) -> Image:
    """``image`` (an array ``(H, W, 3)`` of linear radiance) denoised by Intel
    Open Image Denoise's HDR ``RT`` filter, as ``lamplight render --denoise``
    does, guided by ``albedo`` and ``normal`` arrays of the same shape when
    given. For an :class:`Image` of a render they default to its
    ``layers["albedo"]`` and ``layers["normal"]`` (``exr_layers=["albedo",
    "normal"]``). ``emitted`` (default ``layers["emitted"]``), the emitters and
    sky the camera sees directly, is not filtered but added back, as
    ``render(..., denoise=True)`` does. Needs the library: ``pip install lamplight[denoise]`` (the
    ``pyoidn`` package) or ``LAMPLIGHT_OIDN`` naming it; ``ValueError`` says so
    when it is missing."""
    layers = getattr(image, "layers", {}) or {}
    albedo = layers.get("albedo") if albedo is None else albedo
    normal = layers.get("normal") if normal is None else normal
    emitted = layers.get("emitted") if emitted is None else emitted
    aux = [None if a is None else _plain(a) for a in (albedo, normal, emitted)]
    out = Image(_lamplight.denoise_array(_plain(image), aux[0], aux[1], threads, aux[2]))
    out.stats = dict(getattr(image, "stats", {}) or {})
    return out
