"""``python -m glshade`` runs the command line tool."""

try:  # (a Ctrl-C before the command's own handler is up is still the command's)
    from .cli import main

    status = main()
except KeyboardInterrupt:
    import sys

    print("glshade: interrupted", file=sys.stderr)
    status = 130
raise SystemExit(status)
