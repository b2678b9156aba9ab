"""The OWL axioms' rules of ``rules/owl/`` held as schema tables: one generic rule per file, not one per axiom.

Why
---
The compiler instantiates a rule of ``rules/owl/`` once per axiom (:mod:`.owl`), and the passes after
compilation (folding, the difference joins, simplification) work on those instantiations.  Once they
are done, the rule set no longer needs to hold them one by one: every instantiation of a file is that
file's generic rule with one row of its schema table bound (:meth:`.schema.SchemaRule.row_of` reads the
row back), so the rule set holds the generic rule and the table (:class:`SchemaTables`), and the number
of OWL rules is the number of files whatever the size of the TBox.

Each reader takes the form it runs:

* a full REASON runs the generic rule over its rows written into its schema graph when the table is
  large, else the rows bound one by one (:mod:`.schema_program`);
* incremental maintenance binds the schema row by the changed class or predicate: its delta rule for a
  changed key is the generic rule with the rows whose term is that key bound
  (:attr:`.rule.RuleSet.inference_rules` holds them, made at compilation, and a robot step reads only
  those of the keys it changed, never the table);
* ``topostore rules`` prints the generic rule and the size of its table.

The rules held are exactly those the passes left as instantiations: a rule a pass changed (an atom
dropped as implied, a class folded into a restriction) matches no row and stays in the rule set as it is.
"""

from __future__ import annotations

from dataclasses import dataclass, field

from .rule import Rule
from .schema import Row, SchemaRule, schema_rules, template_of

#: the rules of ``rules/owl/`` the pairs of disjoint classes use are held apart already (:mod:`.disjointness`)
_HELD_APART = frozenset({"different-disjoint", "cax-dw"})


@dataclass
class SchemaTables:
    """Per generic rule of ``rules/owl/``, its instantiations (each the generic rule with one row bound)."""

    #: generic rule (its file's name, :attr:`.SchemaRule.key`) -> its instantiations, in the order the
    #: compiler emitted them
    held: dict[str, list[Rule]] = field(default_factory=dict)
    #: (position in the compiled list, rule) of each instantiation, and that list's length
    placed: list[tuple[int, Rule]] = field(default_factory=list)
    length: int = 0

    def rules(self) -> list[Rule]:
        """Every instantiation, table after table (what maintenance runs rule by rule)."""
        return [r for rules in self.held.values() for r in rules]

    def merged(self, kept: list[Rule]) -> list[Rule]:
        """``kept`` with each instantiation back where the compiler had it: a full REASON and
        maintenance evaluate the rules in the order they always did (the order of evaluations within a
        round moved the 100,000-location full REASON by several per cent).  Rules added after the
        tables were taken come after them."""
        if len(kept) + len(self.placed) < self.length:
            return kept + self.rules()  # the compiled list was replaced: no position is known
        out: list[Rule] = []
        rest = iter(kept)
        held = iter(self.placed)
        nxt = next(held, None)
        for i in range(self.length):
            if nxt is not None and nxt[0] == i:
                out.append(nxt[1])
                nxt = next(held, None)
            else:
                out.append(next(rest))
        out.extend(rest)
        return out

    def rows(self, name: str) -> list[Row]:
        """The rows of ``name``'s table, each once."""
        template = schema_rules()[name]
        return list(dict.fromkeys(template.row_of(r) for r in self.held.get(name, ())))  # type: ignore[misc]

    def generic(self) -> list[tuple[SchemaRule, int]]:
        """Each generic rule held, with how many rows its table has."""
        templates = schema_rules()
        return [(templates[name], len(rules)) for name, rules in self.held.items()]

    def __len__(self) -> int:
        return sum(len(rules) for rules in self.held.values())


def hold_tables(rules: list[Rule]) -> tuple[list[Rule], SchemaTables | None]:
    """(the rules other than the instantiations of ``rules/owl/``, those instantiations as tables).

    A check is held as any rule (:attr:`.rule.RuleSet.checks` binds its rows back where the compiler
    emitted it); the rules of the disjoint pairs are held as rows already, apart."""
    kept: list[Rule] = []
    tables = SchemaTables()
    for i, rule in enumerate(rules):
        template = template_of(rule)
        if template is None or rule.name in _HELD_APART or template.row_of(rule) is None:
            kept.append(rule)
            continue
        tables.held.setdefault(template.key, []).append(rule)
        tables.placed.append((i, rule))
    tables.length = len(rules)
    return kept, (tables if tables.held else None)


__all__ = ["SchemaTables", "hold_tables"]
