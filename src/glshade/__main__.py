"""``python -m glshade`` runs the command line tool."""

from .cli import main

raise SystemExit(main())
