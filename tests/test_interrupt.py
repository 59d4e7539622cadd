"""A Ctrl-C that Python drops inside a ``__del__`` or weakref callback is raised again by
the next item of a long loop, and says nothing meanwhile."""

import subprocess
import sys

CODE = """
import gc, sys
from glshade.interrupt import catch_dropped
from glshade.parallel import Progress, make_executor

class DropsACtrlC:
    def __del__(self):
        raise KeyboardInterrupt  # (as a SIGINT landing in a finalizer would)

class Fails:
    def __del__(self):
        raise ValueError("an ordinary unraisable error")

class Worker:  # (one item at a time, in this process)
    def __call__(self, item):
        return item
    def close(self):
        pass

catch_dropped()
Fails(); gc.collect()  # other unraisables are still reported
DropsACtrlC(); gc.collect()
print("went on")
try:
    Progress(3).update()
except KeyboardInterrupt:
    print("raised by the progress bar")
DropsACtrlC(); gc.collect()
try:
    list(make_executor(Worker, ()).map(range(3)))
except KeyboardInterrupt:
    print("raised by the executor")
Progress(3).update()
print("once only")
"""


def test_a_dropped_ctrl_c_is_raised_at_the_next_item():
    done = subprocess.run([sys.executable, "-c", CODE], capture_output=True, text=True,
                          timeout=60)
    assert done.returncode == 0, done.stderr
    assert done.stdout.split("\n")[:4] == ["went on", "raised by the progress bar",
                                           "raised by the executor", "once only"]
    assert "ValueError: an ordinary unraisable error" in done.stderr
    assert "KeyboardInterrupt" not in done.stderr


HELD = """
import os, signal
from glshade.interrupt import held
try:
    with held():
        os.kill(os.getpid(), signal.SIGINT)
        print("the block went on")
    print("not reached")
except KeyboardInterrupt:
    print("raised after the block")
print(signal.getsignal(signal.SIGINT) is signal.default_int_handler)
"""


def test_a_held_ctrl_c_waits_for_the_block_then_is_raised():
    done = subprocess.run([sys.executable, "-c", HELD], capture_output=True, text=True,
                          timeout=60)
    assert done.stdout.split() == ["the", "block", "went", "on", "raised", "after", "the",
                                   "block", "True"], done.stderr


def test_held_delivers_to_the_handler_that_was_there():
    """Under the command line's own handler (which notes the Ctrl-C, then raises), a held
    Ctrl-C is delivered to it when the block ends (it was let through unheld)."""
    code = HELD.replace("from glshade.interrupt import held", (
        "from glshade.interrupt import held\n"
        "seen = []\n"
        "def mine(signum, frame):\n"
        "    seen.append(signum)\n"
        "    raise KeyboardInterrupt\n"
        "signal.signal(signal.SIGINT, mine)")).replace(
        "print(signal.getsignal(signal.SIGINT) is signal.default_int_handler)",
        "print(signal.getsignal(signal.SIGINT) is mine and seen == [signal.SIGINT])")
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                          timeout=60)
    assert done.stdout.split() == ["the", "block", "went", "on", "raised", "after", "the",
                                   "block", "True"], done.stderr


def test_a_ctrl_c_python_wrapped_in_another_error_is_still_one():
    """A SIGINT that lands in a descriptor's ``__set_name__`` while a class is built (the
    standard library's ``ipaddress`` does so as ``pathlib`` imports it) reaches the command
    as Python's RuntimeError, its cause the KeyboardInterrupt: told apart from a real
    RuntimeError, whose causes hold none."""
    from glshade.interrupt import caused_by_interrupt

    class Landed:
        def __set_name__(self, owner, name):
            raise KeyboardInterrupt  # (as a SIGINT landing there would)

    try:
        type("Network", (), {"broadcast_address": Landed()})
    except RuntimeError as exc:
        wrapped = exc
    assert caused_by_interrupt(wrapped)
    try:
        try:
            raise ValueError("a real fault")
        except ValueError as inner:
            raise RuntimeError("and its report") from inner
    except RuntimeError as exc:
        assert not caused_by_interrupt(exc)
    assert caused_by_interrupt(KeyboardInterrupt())
