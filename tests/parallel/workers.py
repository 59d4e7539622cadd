"""Worker factories for the executor tests (importable by spawned workers)."""

import signal


class SignalMaskWorker:
    """Reports whether Ctrl-C reaches the worker process: blocked or ignored."""

    def __init__(self, *ignored):
        pass

    def __call__(self, item):
        blocked = signal.SIGINT in signal.pthread_sigmask(signal.SIG_BLOCK, [])
        return item, blocked, signal.getsignal(signal.SIGINT) is signal.SIG_IGN

    def close(self):
        pass


class DeviceWorker:
    """Reports the device its process was dealt and the one a context would take: draws a
    frame on it, so the device is one a context can be made on."""

    def __init__(self, *ignored):
        import glshade

        self.renderer = glshade.Renderer(8, 8)

    def __call__(self, item):
        import os
        import time

        from glshade.geometry import primitives
        from glshade.render.context import chosen_device

        import glshade

        scene = glshade.Scene()
        scene.add(primitives.cube())
        self.renderer.render(scene, glshade.Camera.look_at((0, 0, 4), (0, 0, 0)))
        time.sleep(0.3)  # (long enough that every worker takes some items)
        return os.getpid(), os.environ.get("GLSHADE_WORKER_RANK"), chosen_device()[1]

    def close(self):
        self.renderer.close()
