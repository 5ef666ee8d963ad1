"""The GIL is released while drawing: Python threads run (and render) during a render."""
import threading
import time

import numpy as np

import opencv_shading as sh
from conftest import course_mesh, sphere_mesh

SPHERE = sphere_mesh(rings=100, segments=200)
K = np.array([[2800.0, 0, 1024], [0, 2800, 1024], [0, 0, 1]])
POSE = sh.lookAt((0, 0, 3), (0, 0, 0), (0, 1, 0))
PHONG = sh.RenderSettings(shadeType="phong", lights=[sh.PointLight((3, 3, 6)),
                                                     sh.PointLight((-3, 1, 4)),
                                                     sh.PointLight((0, -3, 4))])


def draw_phong():
    """One long call (~0.1 s on 2 cores): a Phong-lit sphere filling a 2048 x 2048 canvas."""
    canvas = np.zeros((2048, 2048, 3), np.float32)
    sh.drawMesh3d(canvas, *SPHERE, K, *POSE, PHONG)
    return canvas


def test_busy_loop_runs_during_render():
    expected = draw_phong()
    span = {}

    def work():
        span["t0"] = time.perf_counter()
        span["img"] = draw_phong()
        span["t1"] = time.perf_counter()

    ticks = []
    th = threading.Thread(target=work)
    th.start()
    while th.is_alive():
        sum(range(200))  # pure-Python work: needs the GIL
        ticks.append(time.perf_counter())
    th.join()
    t0, t1 = span["t0"], span["t1"]
    margin = 0.2 * (t1 - t0)  # > the 5 ms switch interval: argument conversion is outside
    # Had the render held the GIL, this thread could not run between entering and leaving it.
    inside = sum(t0 + margin < t < t1 - margin for t in ticks)
    assert t1 - t0 > 0.03, "render too fast to tell"
    assert inside > 100, (inside, t1 - t0)
    assert np.array_equal(span["img"], expected)


def test_two_threads_render_correctly_at_once():
    v, f, c, d = course_mesh(n=60, size=512, seed=8)
    want = [sh.render(v, f, c, d, shadeType=s) for s in (0, 1)]
    canvases = [np.zeros((512, 512, 3), np.float32) for _ in range(2)]
    want_draw = [sh.drawMesh(np.zeros((512, 512, 3), np.float32), v, f, c, d, s) for s in (0, 1)]
    got = [None, None]
    barrier = threading.Barrier(2)

    def work(i):
        barrier.wait()
        for _ in range(5):
            got[i] = sh.render(v, f, c, d, shadeType=i)
            sh.drawMesh(canvases[i], v, f, c, d, shadeType=i)

    threads = [threading.Thread(target=work, args=(i,)) for i in range(2)]
    for th in threads:
        th.start()
    for th in threads:
        th.join()
    for i in range(2):
        assert np.array_equal(got[i], want[i]) and np.array_equal(canvases[i], want_draw[i])
