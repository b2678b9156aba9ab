"""The derivation tree an explanation returns: one node per triple, as text, JSON or a rich tree."""

from __future__ import annotations

from dataclasses import dataclass, field


@dataclass
class Explanation:
    """One node of a derivation tree.

    ``status``: ``asserted`` (a leaf), ``inferred`` (``rule`` and ``premises``
    say how), ``condition`` (a premise that is a property path, checked but not
    explained further) or ``not entailed``.
    """

    text: str
    status: str
    rule: str = ""
    origin: str = ""
    premises: list[Explanation] = field(default_factory=list)
    #: the rule's variables bound in this derivation (readable values)
    bindings: dict[str, str] = field(default_factory=dict)
    #: the rule's built-in conditions (FILTER/BIND text), when it has any
    conditions: str = ""
    height: int = 1

    @property
    def entailed(self) -> bool:
        return self.status != "not entailed"

    def label(self) -> str:
        if self.status == "inferred" and self.rule:
            return f"{self.text}  ← {self.rule}: {self.origin}"
        return f"{self.text}  [{self.status}]"

    def lines(self, indent: str = "") -> list[str]:
        """The tree as indented text lines (two spaces per level)."""
        out = [indent + self.label()]
        if self.conditions:
            values = ", ".join(f"{k} = {v}" for k, v in sorted(self.bindings.items()))
            out.append(indent + f"  where {self.conditions}  with {values}")
        for p in self.premises:
            out += p.lines(indent + "  ")
        return out

    def __str__(self) -> str:
        return "\n".join(self.lines())

    def to_dict(self) -> dict:
        d: dict = {"triple": self.text, "status": self.status}
        if self.status == "inferred":
            d.update(rule=self.rule, origin=self.origin, bindings=dict(sorted(self.bindings.items())),
                     premises=[p.to_dict() for p in self.premises])
            if self.conditions:
                d["conditions"] = self.conditions
        return d

    def rich_tree(self):
        """The tree as a :class:`rich.tree.Tree` (for the command line)."""
        from rich.markup import escape
        from rich.tree import Tree

        def style(e: Explanation) -> str:
            if e.status == "inferred" and e.rule:
                return f"[bold]{escape(e.text)}[/bold]  [cyan]← {escape(e.rule)}[/cyan]: {escape(e.origin)}"
            colour = {"asserted": "green", "not entailed": "red"}.get(e.status, "yellow")
            return f"{escape(e.text)}  [{colour}]{escape(e.status)}[/{colour}]"

        def grow(node: Tree, e: Explanation) -> None:
            if e.conditions:
                values = ", ".join(f"{k} = {v}" for k, v in sorted(e.bindings.items()))
                node.add(f"[dim]where {escape(e.conditions)}  with {escape(values)}[/dim]")
            for p in e.premises:
                grow(node.add(style(p)), p)

        root = Tree(style(self))
        grow(root, self)
        return root


__all__ = ["Explanation"]
