"""Boundary representation, the notes' solid-modelling chapter: the winged-edge structure
(:class:`WingedEdge`, with the Euler operators) and what a topology check reports
(:class:`TopologyReport`, :class:`EulerReport`: V - E + F = 2 (C - G) + H checked)."""

from .topology import EulerReport, TopologyReport
from .winged_edge import WingedEdge

__all__ = ["WingedEdge", "EulerReport", "TopologyReport"]
