"""The ``glshade`` command line tool: the grammar (parser), argument types (validators),
the typed value each subcommand's arguments become (arguments), what is rendered
(inputs) and the subcommands (commands, info, hidden, radiosity).

Exit status: 0 on success; 2 for bad input (arguments, an input file that is missing or
malformed, an output path into a missing folder -- every output is checked before any
work), reported in one line on stderr; 1 for a failure of the environment (no GL context,
a write the system refuses), also one line. ``--debug`` shows tracebacks.
Ctrl-C at any moment, imports included, ends with one line and status 130.
"""

from __future__ import annotations

import sys

__all__ = ["main"]


def main(argv: list[str] | None = None) -> int:
    """The command line: parse ``argv``, run the command; the exit status (2: bad input)."""
    # (the signal module's C half: ``import signal`` builds its enums, milliseconds in
    # which a Ctrl-C would land before the handler below is up)
    import _signal as signal

    seen: list[int] = []
    if argv is None and signal.getsignal(signal.SIGINT) is signal.default_int_handler:
        # (first of all, before any import: a Ctrl-C from here on is the command's; noted
        # too, as one inside an extension's import can surface as that import's
        # ImportError -- numpy's does -- and is still a Ctrl-C)
        def interrupt(signum, frame):
            seen.append(signum)
            raise KeyboardInterrupt

        signal.signal(signal.SIGINT, interrupt)
    try:
        from ..interrupt import catch_dropped

        catch_dropped()
        return _main(argv)
    except KeyboardInterrupt:
        return _interrupted()
    except Exception as exc:
        from ..interrupt import caused_by_interrupt

        # (a Ctrl-C Python wrapped in another error -- RuntimeError from a class built
        # while a module imported, an extension's ImportError, which may not even chain
        # it -- is still a Ctrl-C)
        if caused_by_interrupt(exc) or (seen and isinstance(exc, ImportError)):
            return _interrupted()
        raise
    finally:
        if argv is None:  # (the command itself, not a call from Python code)
            # the run is over, its status decided: a Ctrl-C while the interpreter shuts
            # down would end it by SIGINT instead (a finished render read as killed)
            signal.signal(signal.SIGINT, signal.SIG_IGN)


def _interrupted() -> int:
    # CPython notes a KeyboardInterrupt that leaves a nested exec of source text (the
    # dataclasses and namedtuples being made while modules import) and, handled or not,
    # ends the process with SIGINT instead of this status; the next such exec clears it
    exec("")
    print("glshade: interrupted", file=sys.stderr)
    return 130


def _main(argv: list[str] | None) -> int:
    import warnings

    from ..errors import GlshadeError, exit_status
    from .arguments import from_namespace
    from .parser import build_parser

    # a warning is one line on stderr, like an error
    warnings.formatwarning = lambda message, *_, **__: f"glshade: warning: {message}\n"
    args = build_parser().parse_args(argv)
    try:  # the Namespace becomes the subcommand's typed arguments here, and only here
        if getattr(args, "require_gpu", False):  # (before any context: workers inherit it)
            import os

            os.environ["GLSHADE_REQUIRE_GPU"] = "1"
        if getattr(args, "device", None) is not None:
            _choose_device(args.device)
        import numpy as np

        # numpy's floating-point warnings are silenced here, deliberately: a user reads
        # "overflow encountered in divide" as the error when it is only on the way to it --
        # every input is checked by rule and every picture for what it shows, and those
        # checks say what is wrong in plain numbers
        with np.errstate(all="ignore"):
            return args.func(from_namespace(args.arguments, args))
    except (GlshadeError, OSError) as exc:  # expected: one line, no traceback
        if isinstance(exc, BrokenPipeError) and _stdout_closed():
            return 141  # (`glshade info ... | head`: the reader has all it wanted)
        if args.debug:
            raise
        print(f"glshade: error: {exc}", file=sys.stderr)
        return exit_status(exc)


def _choose_device(spec: str) -> None:
    """``--device``: checked now (one line naming the devices present if there is no such
    one), then given to every context this run makes -- workers too -- as
    GLSHADE_EGL_DEVICE."""
    import os

    from ..render.context import device_index

    os.environ["GLSHADE_EGL_DEVICE"] = str(device_index(spec))


def _stdout_closed() -> bool:
    """Whether it is standard output whose reader went away (not, say, ffmpeg's pipe); if
    so, it is pointed at /dev/null so that nothing more is written to it at exit."""
    import os
    import select

    try:
        fd = sys.stdout.fileno()
        poll = select.poll()
        poll.register(fd, select.POLLOUT)
        closed = any(events & select.POLLERR for _, events in poll.poll(0))
    except (OSError, ValueError, AttributeError):  # (no descriptor, or no poll here)
        return False
    if closed:
        os.dup2(os.open(os.devnull, os.O_WRONLY), fd)
    return closed
