"""lamplight.dask.render_frames for an animated scene (issue 29): each frame
written by its worker, the bytes of ``lamplight render --frames`` and of
``lamplight.render(frame=)``; a job killed halfway resumes with no frame
rendered twice and none lost; a lost worker's frame is retried, and a frame
that keeps failing is reported by number while the others finish; the
turntable of the lamp to MP4 locally and on a LocalCluster, the same frames."""

import json
import os
import re
import shutil
import signal
import subprocess
import sys
import time

import pytest

import lamplight
from conftest import EXAMPLES

distributed = pytest.importorskip("distributed")
import dask  # noqa: E402
import lamplight.dask  # noqa: E402

#: A sphere crossing the view over frames 1 to 5 under a dimming light; at
#: frame 3 (`step_radius`) its radius can be made invalid.
MOVING = """
[animation]
frames = [1, 5]
fps = 12
[render]
width = 24
height = 16
spp = 2
[camera]
eye = [0, 0, 5]
look_at = [0, 0, 0]
vfov = 40
[[objects]]
type = "point_light"
position = [2, 4, 5]
animate.intensity = { frames = [1, 5], values = [40, 10] }
[[objects]]
type = "sphere"
center = [0, 0, 0]
radius = 0.6
animate.translate = { frames = [1, 5], values = [[-1.5, 0, 0], [1.5, 0, 0]] }
"""


def have_ffmpeg() -> bool:
    if shutil.which("ffmpeg") and shutil.which("ffprobe"):
        return True
    if os.environ.get("CI"):
        pytest.fail("CI must have ffmpeg (scripts/test.sh installs Debian's ffmpeg)")
    return False


def frames_of(video) -> int:
    out = subprocess.run(
        ["ffprobe", "-v", "error", "-select_streams", "v:0", "-count_frames", "-show_entries", "stream=nb_read_frames", "-of", "csv=p=0", str(video)],
        check=True,
        capture_output=True,
        text=True,
    )
    return int(out.stdout.strip())


def test_each_frame_is_the_bytes_of_the_command_line_and_of_frame(client, cli, tmp_path, capsys):
    scene = tmp_path / "moving.toml"
    scene.write_text(MOVING)
    subprocess.run([cli, "render", str(scene), "-o", str(tmp_path / "cli" / "f_####.png"), "-q"], check=True)
    with distributed.get_task_stream(client) as stream:
        done = lamplight.dask.render_frames(str(scene), client, out=tmp_path / "dask" / "f_####.png", progress=True)
    assert done.written == [1, 2, 3, 4, 5] and done.skipped == []
    assert set(done.seconds) == {1, 2, 3, 4, 5}
    # The tasks are named by frame, for the dashboard; a tqdm bar counted them.
    keys = sorted({re.sub(r"-[0-9a-f]{12}$", "", t["key"]) for t in stream.data if "lamplight-frame" in str(t["key"])})
    assert keys == [f"lamplight-frame-{f:04d}" for f in range(1, 6)]
    assert "lamplight frames (dask)" in capsys.readouterr().err
    for f in range(1, 6):
        name = f"f_{f:04d}.png"
        written = (tmp_path / "dask" / name).read_bytes()
        assert written == (tmp_path / "cli" / name).read_bytes(), f"frame {f}: cluster and command line"
        lamplight.render(str(scene), frame=f, progress=False).save(tmp_path / name)
        assert written == (tmp_path / name).read_bytes(), f"frame {f}: cluster and frame="
    # A frame's tiles as tasks, stitched on a worker, are the same file; images come back equal too.
    tiled = lamplight.dask.render_frames(str(scene), client, frames=[2, 4], tiles=3, out=tmp_path / "tiled" / "f_####.png")
    assert tiled.written == [2, 4]
    assert all((tmp_path / "tiled" / f"f_{f:04d}.png").read_bytes() == (tmp_path / "cli" / f"f_{f:04d}.png").read_bytes() for f in (2, 4))
    # One frame on two worker threads: cut into tiles by itself (2 per thread).
    with distributed.get_task_stream(client) as stream:
        lamplight.dask.render_frames(str(scene), client, frames=[5], out=tmp_path / "one" / "f_####.png")
    tiles = {str(t["key"]).rsplit("-", 1)[0] for t in stream.data if "lamplight-frame-tile" in str(t["key"])}
    assert tiles == {f"lamplight-frame-tile-0005-{i}" for i in range(4)}
    assert (tmp_path / "one" / "f_0005.png").read_bytes() == (tmp_path / "cli" / "f_0005.png").read_bytes()
    images = lamplight.dask.render_frames(str(scene), client, frames="2-3")
    assert [i.tobytes() for i in images] == [lamplight.render(str(scene), frame=f, progress=False).tobytes() for f in (2, 3)]
    # A second run skips what exists, and reports only what it rendered.
    calls = []
    (tmp_path / "dask" / "f_0004.png").unlink()
    again = lamplight.dask.render_frames(str(scene), client, out=tmp_path / "dask" / "f_####.png", progress=lambda d, t: calls.append((d, t)))
    assert (again.written, again.skipped, calls) == ([4], [1, 2, 3, 5], [(1, 1)])


def test_a_frame_that_keeps_failing_is_reported_and_the_others_are_written(client, tmp_path):
    broken = MOVING.replace("radius = 0.6\n", 'animate.radius = { frames = [1, 3, 4], values = [0.6, -1, 0.6], interpolation = "step" }\n')
    scene = tmp_path / "broken.toml"
    scene.write_text(broken)
    with pytest.raises(lamplight.dask.FramesFailed) as failed:
        lamplight.dask.render_frames(str(scene), client, out=tmp_path / "out" / "f_#.png", retries=0)
    assert list(failed.value.failed) == [3] and failed.value.done == [1, 2, 4, 5]
    assert re.fullmatch(
        r"1 of 5 frames failed \(the other 4 finished\): frame 3: SceneError: .*frame 3: sphere: invalid radius: must be a positive number, got -1",
        str(failed.value),
    ), str(failed.value)
    assert sorted(os.listdir(tmp_path / "out")) == ["f_1.png", "f_2.png", "f_4.png", "f_5.png"]


def test_a_lost_workers_frame_is_retried_up_to_allowed_failures(tmp_path):
    """Frame 2's worker dies once: it is run again and written. Frame 3's
    worker dies every time: after Dask's allowed-failures (1 here) it is
    reported as KilledWorker, and every other frame is written."""
    marks = tmp_path / "marks"
    marks.mkdir()
    scene = tmp_path / "moving.toml"
    scene.write_text(MOVING)

    def crashing_plugin(folder: str):
        from distributed import WorkerPlugin

        class Crash(WorkerPlugin):
            name = "lamplight-test-crash"

            def transition(self, key, start, finish, **kwargs):
                m = re.match(r"lamplight-frame-(\d+)-", str(key))
                frame = int(m.group(1)) if m else None
                if finish != "executing" or frame not in (2, 3):
                    return
                mark = os.path.join(folder, str(frame))
                if frame == 2 and os.path.exists(mark):
                    return
                with open(mark, "a") as f:
                    f.write("x")
                os.kill(os.getpid(), signal.SIGKILL)

        return Crash()

    config = {"distributed.scheduler.allowed-failures": 1, "distributed.scheduler.worker-saturation": 1.0}
    with dask.config.set(config):
        cluster = distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=":0")
    try:
        with distributed.Client(cluster) as client:
            client.register_plugin(crashing_plugin(str(marks)))
            with pytest.raises(lamplight.dask.FramesFailed) as failed:
                lamplight.dask.render_frames(str(scene), client, out=tmp_path / "out" / "f_#.png")
    finally:
        cluster.close()
    assert list(failed.value.failed) == [3] and failed.value.done == [1, 2, 4, 5]
    assert type(failed.value.failed[3]).__name__ == "KilledWorker", repr(failed.value.failed[3])
    assert (marks / "2").read_text() == "x" and (marks / "3").read_text() == "xx", "frame 2 ran twice, frame 3 allowed-failures + 1 times"
    assert sorted(os.listdir(tmp_path / "out")) == ["f_1.png", "f_2.png", "f_4.png", "f_5.png"]


JOB = """
import json, sys
import distributed
import lamplight.dask

if __name__ == "__main__":
    # Threads, not processes: they start at once, and the render releases the GIL.
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=False, dashboard_address=":0") as cluster:
        with distributed.Client(cluster) as client:
            done = lamplight.dask.render_frames(sys.argv[1], client, frames="1-12", out=sys.argv[2], progress=False)
    print(json.dumps({"written": done.written, "skipped": done.skipped}))
"""


@pytest.mark.skipif(sys.platform == "win32", reason="process groups and SIGKILL")
def test_a_job_killed_halfway_resumes_with_no_frame_rendered_twice(cli, tmp_path):
    job = tmp_path / "job.py"
    job.write_text(JOB)
    scene = str(EXAMPLES / "turntable.toml")
    out = tmp_path / "out"
    pattern = str(out / "f_####.png")
    finished = lambda: sorted(n for n in os.listdir(out) if n.endswith(".png")) if out.exists() else []  # noqa: E731
    # The client, its scheduler and its workers, killed together, as a job is.
    proc = subprocess.Popen([sys.executable, str(job), scene, pattern], start_new_session=True, stdout=subprocess.PIPE, stderr=subprocess.PIPE)
    deadline = time.monotonic() + 120
    while len(finished()) < 4 and proc.poll() is None and time.monotonic() < deadline:
        time.sleep(0.01)
    try:
        os.killpg(proc.pid, signal.SIGKILL)
    except ProcessLookupError:
        pass  # it ended by itself: the assertion below says so
    proc.communicate()
    # A write the kill interrupted leaves its temporary file (SIGKILL runs no cleanup); the rerun removes it.
    (out / ".f_0012.png.AbC123.tmp").write_bytes(b"half a frame")
    before = {n: (os.stat(out / n).st_ino, os.stat(out / n).st_mtime_ns) for n in finished()}
    assert 4 <= len(before) < 12, f"killed halfway: {sorted(before)}"
    again = subprocess.run([sys.executable, str(job), scene, pattern], check=True, capture_output=True, text=True)
    said = json.loads(again.stdout.strip().splitlines()[-1])
    names = lambda frames: {f"f_{f:04d}.png" for f in frames}  # noqa: E731
    assert names(said["skipped"]) == set(before), "the rerun skipped exactly the frames written before the kill"
    assert names(said["written"]) == names(range(1, 13)) - set(before), "and rendered each of the others once"
    assert {n: (os.stat(out / n).st_ino, os.stat(out / n).st_mtime_ns) for n in before} == before, "no frame written again"
    assert sorted(os.listdir(out)) == sorted(names(range(1, 13))), "none lost, and no temporary file of a killed write left"
    subprocess.run([cli, "render", scene, "--frames", "1-12", "-o", str(tmp_path / "ref" / "f_####.png"), "-q"], check=True)
    for n in finished():
        assert (out / n).read_bytes() == (tmp_path / "ref" / n).read_bytes(), n


def test_the_lamp_turntable_to_mp4_locally_and_on_a_cluster_has_the_same_frames(client, cli, tmp_path):
    scene = str(EXAMPLES / "turntable.toml")
    size = ["--width", "64", "--height", "36", "--spp", "1"]
    video = have_ffmpeg()
    local = [cli, "render", scene, *size, "-o", str(tmp_path / "local" / "f_####.png"), "-q"]
    subprocess.run(local + (["--video", str(tmp_path / "local.mp4")] if video else []), check=True)
    done = lamplight.dask.render_frames(
        scene, client, width=64, height=36, spp=1, out=tmp_path / "dask" / "f_####.png", video=tmp_path / "dask.mp4" if video else None
    )
    assert done.written == list(range(1, 49))
    for f in range(1, 49):
        name = f"f_{f:04d}.png"
        assert (tmp_path / "dask" / name).read_bytes() == (tmp_path / "local" / name).read_bytes(), name
    if not video:
        pytest.skip("ffmpeg is not installed (apt-get install ffmpeg): the frames were compared, not the videos")
    assert done.video == str(tmp_path / "dask.mp4")
    assert frames_of(tmp_path / "local.mp4") == frames_of(tmp_path / "dask.mp4") == 48


def test_bad_frames_and_patterns_say_what_was_expected(client, tmp_path):
    with pytest.raises(ValueError, match=r'^frames "5-1" ends before it starts \(expected START <= END\)$'):
        lamplight.dask.render_frames(str(EXAMPLES / "turntable.toml"), client, frames="5-1", out=tmp_path / "f_#.png")
    with pytest.raises(ValueError, match=r'^out="f\.png" must hold a run of # for the frame number, such as frame_####\.png$'):
        lamplight.dask.render_frames(str(EXAMPLES / "turntable.toml"), client, frames="1-2", out="f.png")
    with pytest.raises(ValueError, match=r"^the scene has no \[animation\] to give its frames; say which with frames="):
        lamplight.dask.render_frames("spheres", client, out=tmp_path / "f_#.png")
    with pytest.raises(ValueError, match=r'^video="v\.avi" must end in \.mp4, \.webm or \.gif \(the video.s format\)$'):
        lamplight.dask.render_frames(str(EXAMPLES / "turntable.toml"), client, frames="1-2", out=tmp_path / "f_#.png", video="v.avi")
    with pytest.raises(ValueError, match=r'^a video.s frames must be consecutive, such as "1-48"$'):
        lamplight.dask.render_frames(str(EXAMPLES / "turntable.toml"), client, frames=[1, 3], out=tmp_path / "f_#.png", video="v.mp4")
    assert os.listdir(tmp_path) == [], "nothing rendered"


def test_make_video_without_ffmpeg_keeps_the_frames(tmp_path, monkeypatch):
    scene = lamplight.Scene.from_toml(MOVING)
    for f in (1, 2):
        lamplight.render(scene, frame=f, progress=False).save(tmp_path / f"f_{f}.png")
    monkeypatch.setenv("PATH", str(tmp_path / "nothing"))
    with pytest.raises(FileNotFoundError) as missing:
        lamplight.make_video(tmp_path / "f_#.png", tmp_path / "v.mp4", frames="1-2")
    assert str(missing.value) == (
        f"cannot make {tmp_path / 'v.mp4'}: ffmpeg is not on PATH (install it: apt-get install ffmpeg, brew install ffmpeg, "
        f"or ffmpeg.org); the frames are kept ({tmp_path / 'f_1.png'} to {tmp_path / 'f_2.png'})"
    )
    assert sorted(os.listdir(tmp_path)) == ["f_1.png", "f_2.png"]
    with pytest.raises(ValueError, match=r"frame 3 \(.*f_3\.png\) is missing; render it first"):
        lamplight.make_video(tmp_path / "f_#.png", tmp_path / "v.mp4", frames="1-3")


def test_denoised_frames_are_the_local_denoised_frames(client, tmp_path, oidn):
    """Issue 28 on an animation's frames: a denoised frame, rendered as one
    task or as tiles stitched on a worker (denoised whole there, never tile by
    tile), is the local denoised render of that frame, and its file is the
    command line's `--denoise` frame."""
    scene = tmp_path / "moving.toml"
    scene.write_text(MOVING.replace("spp = 2", "spp = 4\nintegrator = \"path\""))
    frames = (2, 4)
    local = [lamplight.render(str(scene), frame=f, denoise=True, progress=False) for f in frames]
    noisy = [lamplight.render(str(scene), frame=f, progress=False) for f in frames]
    assert all(d.tobytes() != n.tobytes() for d, n in zip(local, noisy)), "the denoiser changed nothing: the test would not see it"
    whole = lamplight.dask.render_frames(str(scene), client, frames=list(frames), tiles=1, denoise=True)
    tiled = lamplight.dask.render_frames(str(scene), client, frames=list(frames), tiles=3, denoise=True)
    for f, a, b, c in zip(frames, local, whole, tiled):
        assert b.tobytes() == a.tobytes(), f"frame {f}: one task per frame"
        assert c.tobytes() == a.tobytes(), f"frame {f}: tiles stitched and denoised on a worker"
    done = lamplight.dask.render_frames(str(scene), client, frames=list(frames), tiles=3, denoise=True, out=tmp_path / "d" / "f_####.png")
    assert done.written == list(frames)
    for f, a in zip(frames, local):
        a.save(tmp_path / f"local_{f}.png")
        assert (tmp_path / "d" / f"f_{f:04d}.png").read_bytes() == (tmp_path / f"local_{f}.png").read_bytes()
