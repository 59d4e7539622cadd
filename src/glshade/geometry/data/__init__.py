"""Published data tables the geometry is built from: Newell's teapot patches and the
Cornell box's measurements. Plain numbers, no code."""
