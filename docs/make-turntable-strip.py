"""Renders docs/turntable-strip.png, the frame strip of docs/animation.md:
frames 1, 9, 17, 25, 33 and 41 of examples/turntable.toml at 160x90, side by
side. Run from the repository root with the Python package installed:

    python docs/make-turntable-strip.py
"""

from pathlib import Path

import numpy as np

import lamplight

ROOT = Path(__file__).resolve().parents[1]
FRAMES = [1, 9, 17, 25, 33, 41]

scene = lamplight.Scene(str(ROOT / "examples" / "turntable.toml"))
frames = [lamplight.render(scene, frame=f, width=160, height=90, progress=False) for f in FRAMES]
lamplight.save(ROOT / "docs" / "turntable-strip.png", np.concatenate(frames, axis=1))
