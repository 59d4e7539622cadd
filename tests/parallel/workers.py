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
