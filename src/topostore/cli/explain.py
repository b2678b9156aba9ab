"""``topostore explain``: why a triple holds, printed as a tree.

Added to the main command group by :mod:`topostore.cli.group`, like every command family.
"""

from __future__ import annotations

import json

import click
from rich.console import Console

from ..ontology.explain import parse_triple_text
from .loading import _existing, load_files, reason_with_progress

#: Exit code when the triple does not hold.
EXIT_NOT_ENTAILED = 4


@click.command()
@click.argument("args", nargs=-1, required=True, metavar='FILE... "SUBJECT PREDICATE OBJECT"')
@click.option("--json", "as_json", is_flag=True, help="Print the tree as JSON.")
@click.option("--rule", "rules", multiple=True, metavar="LABEL=RULE",
              help="Add a SWRL rule (Protégé syntax) before reasoning (repeatable).")
def explain(args: tuple[str, ...], as_json: bool, rules: tuple[str, ...]) -> None:
    """Load FILE(s), reason, and explain why a triple holds: the rule that derives it and its
    premises, down to asserted facts (one derivation of minimal height).  Exit 4 when the
    triple is not entailed.

    \b
    Example:
      topostore explain ontology/topological_map.ttl ontology/topological_map_abox.ttl "R1 rdf:type URGENT"
    """
    if len(args) < 2:
        raise click.UsageError('give the file(s) and then the triple, e.g. "R1 rdf:type URGENT"')
    files, text = args[:-1], args[-1]
    _existing(files)
    onto = load_files(files)
    for item in rules:
        label, sep, rule = item.partition("=")
        if not sep or not label.strip():
            raise click.UsageError(f"--rule takes LABEL=RULE, not {item!r}")
        onto.add_rule(rule, label.strip())
    reason_with_progress(onto)
    s, p, o = parse_triple_text(onto, text)
    result = onto.explain(s, p, o)
    if as_json:
        click.echo(json.dumps(result.to_dict(), indent=2, ensure_ascii=False))
    else:
        console = Console(highlight=False)
        if not console.is_terminal:
            console = Console(highlight=False, width=400)  # a file or pipe: never crop a line
        console.print(result.rich_tree())
    if not result.entailed:
        raise click.exceptions.Exit(EXIT_NOT_ENTAILED)
