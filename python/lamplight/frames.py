"""Frame sequences: which frames (``"1-48"``, ``(1, 48)``, ``range(1, 49)``),
the file of each (``out/frame_####.png``, the run of ``#`` zero-padded as
``lamplight render -o`` pads it), and the video of them (``make_video``, what
``lamplight render --video`` runs). The range and the pattern are read by the
command line's own code, so both front ends name the same files."""

from __future__ import annotations

import os
from typing import Any, List, Optional, Sequence, Union

from . import _lamplight

PathLike = Union[str, "os.PathLike[str]"]
Frames = Union[None, int, str, Sequence[int], range]


def frame_list(frames: Frames, scene: Optional[Any] = None) -> List[int]:
    """The frame numbers ``frames`` names: ``"1-48"`` or ``"7"`` (as
    ``--frames``), one ``int``, a ``(start, end)`` pair (both included), a
    ``range`` or a list of ints; ``None``: the ``[animation]`` frames of
    ``scene`` (a :class:`lamplight.Scene`), which must have them."""
    if frames is None:
        animation = getattr(scene, "animation", None)
        if animation is None:
            raise ValueError("the scene has no [animation] to give its frames; say which with frames= (\"1-24\", or a range)")
        start, end = animation["frames"]
        return list(range(start, end + 1))
    if isinstance(frames, str):
        start, end = _lamplight.frame_range(frames, "frames")
        return list(range(start, end + 1))
    if isinstance(frames, int) and not isinstance(frames, bool):
        numbers = [frames]
    elif isinstance(frames, tuple) and len(frames) == 2 and all(isinstance(f, int) for f in frames):
        if frames[1] < frames[0]:
            raise ValueError(f"frames {frames} ends before it starts (expected (start, end) with start <= end)")
        numbers = list(range(frames[0], frames[1] + 1))
    elif isinstance(frames, (range, list)) and all(isinstance(f, int) and not isinstance(f, bool) for f in frames):
        numbers = list(frames)
    else:
        raise TypeError(f"frames is \"START-END\", an int, a (start, end) pair, a range or a list of ints, got {frames!r}")
    for f in numbers:
        # Checked as --frames checks a number, with its message.
        _lamplight.frame_range(str(f), "frames")
    if len(set(numbers)) != len(numbers):
        raise ValueError("frames names a frame more than once")
    return numbers


def frame_paths(pattern: PathLike, frames: Sequence[int], name: str = "out") -> List[str]:
    """The file of each of ``frames`` under ``pattern`` (a path with one run of
    ``#``: ``out/frame_####.png`` gives ``out/frame_0007.png``), made absolute
    here, so that workers whose working folder differs write the same files."""
    return [os.path.abspath(os.fspath(p)) for p in _lamplight.frame_paths(os.fspath(pattern), list(frames), name)]


def make_video(pattern: PathLike, video: PathLike, frames: Frames = None, fps: Optional[float] = None, scene: Optional[Any] = None) -> None:
    """Encodes the frames ``frames`` (consecutive; default: the ``[animation]``
    of ``scene``) of ``pattern`` (``out/frame_####.png``) into ``video``
    (``.mp4``: H.264, ``.webm``: VP9, ``.gif``) at ``fps`` frames a second
    (default: the scene's, else 24), as ``lamplight render --video`` does,
    with ffmpeg from ``PATH``. Without ffmpeg, ``FileNotFoundError`` says
    so and the frames are kept; a missing frame is a ``ValueError`` naming it."""
    numbers = frame_list(frames, scene)
    if numbers != list(range(numbers[0], numbers[0] + len(numbers))):
        raise ValueError("a video's frames must be consecutive, such as \"1-48\"")
    if fps is None:
        animation = getattr(scene, "animation", None)
        fps = animation["fps"] if animation is not None else 24.0
    _lamplight.make_video(os.fspath(pattern), numbers[0], numbers[-1], float(fps), os.fspath(video))


__all__ = ["frame_list", "frame_paths", "make_video"]
