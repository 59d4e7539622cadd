"""What a topology check reports: the faults of a polygon structure, and the counts of
Euler's formula with what they say (used by the winged-edge B-Rep and ``glshade info``)."""

from __future__ import annotations

from dataclasses import dataclass, field

__all__ = ["TopologyReport", "EulerReport"]


def _first(items, k: int = 5) -> str:
    items = list(items)
    more = f" ... ({len(items)} in all)" if len(items) > k else ""
    return ", ".join(str(i) for i in items[:k]) + more


@dataclass
class TopologyReport:
    """Problems found while building; empty lists mean a valid 2-manifold structure.

    Parameters
    ----------
    non_manifold_edges : list
        Edges with more than two faces.
    misoriented_edges : list
        Edges two faces traverse the same way.
    isolated_vertices : list
        Vertices no face uses.
    duplicate_faces : list
        Faces repeated.
    non_manifold_vertices : list
        Vertices whose faces do not form one fan.
    fixable_orientation : bool
        Whether reversing faces would orient it.
    """

    non_manifold_edges: list = field(default_factory=list)   # (a, b, [faces])
    misoriented_edges: list = field(default_factory=list)    # (a, b, [faces])
    isolated_vertices: list = field(default_factory=list)
    duplicate_faces: list = field(default_factory=list)      # (f, g)
    non_manifold_vertices: list = field(default_factory=list)  # pinched: 2+ fans meet
    fixable_orientation: bool = False  # Mesh.oriented() winds the faces consistently

    @property
    def ok(self) -> bool:
        return not (self.non_manifold_edges or self.misoriented_edges or
                    self.isolated_vertices or self.duplicate_faces or
                    self.non_manifold_vertices)

    def message(self) -> str:
        parts = []
        if self.non_manifold_edges:
            parts.append(f"{len(self.non_manifold_edges)} non-manifold edges (3 or more faces): "
                         + _first(f"({a}, {b}) in faces {fs}"
                                  for a, b, fs in self.non_manifold_edges))
        if self.misoriented_edges:
            parts.append(f"{len(self.misoriented_edges)} edges where neighbouring faces disagree "
                         "on orientation (both run the same way): "
                         + _first(f"({a}, {b}) in faces {fs}"
                                  for a, b, fs in self.misoriented_edges))
            if self.fixable_orientation:
                parts[-1] += " (Mesh.oriented() winds them consistently)"
        if self.isolated_vertices:
            parts.append(f"{len(self.isolated_vertices)} isolated vertices (in no face): "
                         + _first(self.isolated_vertices))
        if self.duplicate_faces:
            parts.append(f"{len(self.duplicate_faces)} duplicate faces: "
                         + _first(f"{f} = {g}" for f, g in self.duplicate_faces))
        if self.non_manifold_vertices:
            parts.append(f"{len(self.non_manifold_vertices)} non-manifold vertices (several "
                         "fans of faces meet there): " + _first(self.non_manifold_vertices))
        return "; ".join(parts)


@dataclass
class EulerReport:
    """The counts of Euler's formula and what they say.

    Parameters
    ----------
    V, E, F : int
        Vertices, edges, faces.
    H : int
        Holes (inner loops of faces).
    C : int
        Connected components.
    G : int or None
        The genus (None: not closed).
    B : int
        Boundary loops.
    is_closed, is_manifold, is_oriented : bool
        What the structure is.
    genus_per_component : list
        Each component's genus.
    """

    V: int
    E: int
    F: int
    H: int
    C: int
    G: int | None
    B: int
    is_closed: bool
    is_manifold: bool
    is_oriented: bool
    genus_per_component: list

    @property
    def holds(self) -> bool:
        """Whether the counts satisfy ``V - E + F - H + B = 2 (C - G)`` with integer G >= 0."""
        return self.G is not None and \
            self.V - self.E + self.F - self.H + self.B == 2 * (self.C - self.G)

    @property
    def formula(self) -> str:
        lhs = f"{self.V} - {self.E} + {self.F} - {self.H}"
        if self.B:
            lhs += f" + {self.B}"
        value = self.V - self.E + self.F - self.H + self.B
        g = "?" if self.G is None else self.G
        name = "V - E + F - H" + (" + B" if self.B else "")
        return f"{name} = {lhs} = {value} = 2(C - G) = 2({self.C} - {g})"

    def as_dict(self) -> dict:
        return {"V": self.V, "E": self.E, "F": self.F, "H": self.H, "C": self.C, "G": self.G,
                "boundary_loops": self.B, "closed": self.is_closed,
                "manifold": self.is_manifold, "oriented": self.is_oriented,
                "euler_holds": self.holds, "formula": self.formula}
