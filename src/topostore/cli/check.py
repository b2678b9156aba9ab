"""``topostore check`` (what a file's load repairs, sets aside or does not reason completely)
and ``topostore repair`` (a saved map's SWRL rules put back from the file they were written in).

``check`` exits 0 when every notice is only informative, 1 with ``--strict`` when
some axiom is not reasoned completely or a rule was set aside.
"""

from __future__ import annotations

from pathlib import Path

import click

from ..compile import compile_ontology
from ..compile.notices import RULE_SKIPPED, grouped
from ..compile.swrl_repair import replace_rules
from ..compile.swrl_text import rules_among
from ..ontology.facade import Ontology
from ..rdf.vocab import ASSERTED
from ..stores import memory_store
from .loading import _existing, load_files


@click.command()
@click.argument("files", nargs=-1, required=True, metavar="FILE...")
@click.option("--strict", is_flag=True, help="Exit 1 when an axiom is not reasoned completely or a rule was skipped "
              "(what a strict load, Ontology(strict=True), refuses).")
@click.option("--input-format", metavar="F", help="Format of the input files when their extension does not tell.")
def check(files: tuple[str, ...], strict: bool, input_format: str | None) -> None:
    """Load FILE(s) and print the load and profile report: rules repaired or skipped, SQWRL
    queries found, and every axiom topostore does not reason completely, with the reason.

    \b
    Examples:
      topostore check ontology/topological_map.ttl ontology/topological_map_abox.ttl
      topostore check --strict ontology/topological_map.ttl
    """
    _existing(files)
    onto = load_files(files, input_format)
    notices = onto.notices
    rules = onto.rules
    swrl = sorted({r.name for r in rules.rules if r.name.startswith("swrl:")})
    click.echo(f"Loaded {len(files)} file(s): {len(swrl)} SWRL rule(s) compiled, {rules.count_text()} in all")
    if not notices:
        click.echo("Every axiom and rule is reasoned completely; nothing was repaired or skipped.")
        return
    for line in grouped(notices):
        click.echo(f"- {line}")
    blocking = [n for n in notices if n.incomplete or n.kind == RULE_SKIPPED]
    if strict and blocking:
        raise click.ClickException(f"{len(blocking)} axiom(s) or rule(s) not reasoned completely (--strict)")


@click.command()
@click.argument("saved", type=click.Path(exists=True, dir_okay=False))
@click.option("--rules-from", "original", required=True, type=click.Path(exists=True, dir_okay=False),
              help="The file the rules were written in (before a SAVE damaged them).")
@click.option("-o", "--output", required=True, type=click.Path(dir_okay=False, writable=True),
              help="Where to write the repaired ontology (format from the extension).")
def repair(saved: str, original: str, output: str) -> None:
    """Put the SWRL rules of ORIGINAL back into SAVED: the facts of the saved file, the rules
    of the original one, written to -o (the file is checked by loading it before it is written).

    \b
    Example:
      topostore repair ontology/topological_map_abox.ttl --rules-from ontology/topological_map.ttl -o fixed_map.owl
    """
    store = memory_store()
    triples, removed, put = replace_rules(store.parse_file(saved), store.parse_file(original))
    onto = Ontology()
    onto.add(*triples)
    # the rules put back are the user's: one that cannot be translated refuses the output, nothing written
    compile_ontology(onto.store, ASSERTED, refuse=rules_among(triples))
    path = onto.save(Path(output))
    click.echo(f"{saved}: {removed} SWRL rule(s) removed, {put} put back from {original}; wrote {path}")


__all__ = ["check", "repair"]
