"""``topostore reason``, ``rules`` and ``query``: what an ontology file gives, on the command line.

Exit code 3 (:data:`EXIT_INCONSISTENT`) when ``reason`` finds the ontology inconsistent.
"""

from __future__ import annotations

import json
import time
from collections.abc import Sequence
from pathlib import Path

import click
from rich.console import Console
from rich.table import Table

from ..compile.rule import Rule
from ..ontology.named_queries import QueryItem, named_queries
from ..rdf.declarations import declared
from ..rdf.vocab import ASSERTED, INFERRED, OWL, RDF, RDFS, XSD
from ..stores.base import guess_format, serialize
from .loading import _existing, load_files, reason_with_progress
from .store_option import store_option

EXIT_INCONSISTENT = 3


@click.command()
@click.argument("files", nargs=-1, metavar="FILE...")
@store_option
@click.option(
    "-o", "--output", type=click.Path(dir_okay=False, writable=True), help="Write asserted + inferred triples here."
)
@click.option("--inferred-only", is_flag=True, help="With -o: write only the inferred triples.")
@click.option(
    "--format", "fmt", metavar="F", help="Output format: turtle, ntriples or rdfxml (default: from -o's extension)."
)
@click.option("--input-format", metavar="F", help="Format of the input files when their extension does not tell.")
@click.option("--strict", is_flag=True, help="Refuse files with axioms not reasoned completely (see topostore check).")
def reason(
    files: tuple[str, ...],
    store: str | None,
    output: str | None,
    inferred_only: bool,
    fmt: str | None,
    input_format: str | None,
    strict: bool,
) -> None:
    """Load FILE(s) (into --store, if given), reason, and print a summary; exit 3 if inconsistent.

    \b
    Examples:
      topostore reason ontology/topological_map.ttl ontology/topological_map_abox.ttl -o out/closure.ttl
      topostore reason --store out/mapdb ontology/topological_map.ttl ontology/topological_map_abox.ttl
      topostore reason --store out/mapdb        # the stored ontology again, no files
    """
    if not files and not store:
        raise click.UsageError("give the ontology file(s), or --store holding an ontology")
    _existing(files)
    if inferred_only and not output:
        raise click.UsageError("--inferred-only needs -o FILE")
    start = time.perf_counter()
    onto = load_files(files, input_format, store=store, strict=strict)
    loaded = time.perf_counter() - start
    report = reason_with_progress(onto)
    asserted = onto.store.count(ASSERTED)
    inferred = onto.store.count(INFERRED)
    click.echo(f"Loaded {len(files)} file(s): {asserted} asserted triples in {loaded:.3f} s")
    click.echo(
        f"Reasoned in {report.stats.seconds:.3f} s ({report.stats.rounds} rounds, "
        f"{onto.rules.count_text()}): {inferred} inferred triples"
    )
    for notice in report.incomplete:
        click.echo(f"warning: {notice}", err=True)
    if output:
        out = Path(output)
        rdf_format = guess_format(out, fmt)
        if inferred_only:
            triples = onto.store.dump([INFERRED], restore_literals_from=ASSERTED)
        else:
            triples = onto.triples(inferred=True)
        prefixes = {"owl": OWL, "rdf": RDF, "rdfs": RDFS, "xsd": XSD, "": onto.prefix}
        out.parent.mkdir(parents=True, exist_ok=True)
        out.write_bytes(serialize(declared(triples), rdf_format, prefixes))
        click.echo(f"Wrote {len(triples)} triples to {out}")
    if report.consistent:
        click.echo("Consistent.")
        return
    click.echo(f"INCONSISTENT: {len(report.violations)} violation(s)", err=True)
    for v in report.violations:
        who = ", ".join(f"{k}={_short(val)}" for k, val in v.individuals.items())
        click.echo(
            f"  - {v.message}\n    axiom: {v.axiom} (rule {v.rule})" + (f"\n    individuals: {who}" if who else ""),
            err=True,
        )
    raise click.exceptions.Exit(EXIT_INCONSISTENT)


def _short(term: object) -> str:
    value = getattr(term, "value", str(term))
    return value.rsplit("#", 1)[-1] if "#" in value else value


# --------------------------------------------------------------------------- rules

RULE_GROUPS = ("SWRL rules", "OWL axioms", "Consistency checks", "Generic OWL 2 RL rules")


@click.command()
@click.argument("files", nargs=-1, required=True, metavar="FILE...")
@click.option("--all", "show_all", is_flag=True,
              help="Also print the generic OWL 2 RL rules every ontology gets, and the rule files of rules/owl/ "
                   "that the OWL axioms' rules instantiate.")
@click.option("--deltas", is_flag=True,
              help="After each rule, the delta rules incremental REASON runs: one per body atom, that atom read "
                   "from the changed facts only.")
@click.option("--step", "step", metavar="PROP[,PROP...]",
              help="Instead, the compiled step of a REASON after replacing a value of each of these properties "
                   "(local names or IRIs): its operations in order, each with when it runs.")
def rules(files: tuple[str, ...], show_all: bool, deltas: bool, step: str | None) -> None:
    """Print the rules compiled from FILE(s): SPARQL per rule, grouped, with its origin.

    \b
    Examples:
      topostore rules ontology/topological_map.ttl
      topostore rules --deltas ontology/topological_map.ttl
      topostore rules --step isIn,now,visitedAt ontology/topological_map.ttl
    """
    from ..compile.generic import generic_rules
    from ..compile.key_form import one_list_rule

    _existing(files)
    onto = load_files(files)
    if step:
        click.echo(_step_program(onto, [p.strip() for p in step.split(",") if p.strip()]))
        return
    generic = {(r.name, r.where(), r.head) for r in (*generic_rules(), one_list_rule(onto.rules.one_list))}
    groups: dict[str, list] = {g: [] for g in RULE_GROUPS}
    for rule in onto.rules.rules:  # the rows of rules/owl/ are shown by table below
        if (rule.name, rule.where(), rule.head) in generic:
            groups["Generic OWL 2 RL rules"].append(rule)
        elif rule.name.startswith("swrl:"):
            groups["SWRL rules"].append(rule)
        elif rule.is_check:
            groups["Consistency checks"].append(rule)
        else:
            groups["OWL axioms"].append(rule)
    for name, rules_of in _tables(onto.rules).items():
        groups["Consistency checks" if rules_of[0].is_check else "OWL axioms"].append((name, rules_of))
    shown = 0
    for title in RULE_GROUPS:
        if title == "Generic OWL 2 RL rules" and not show_all:
            continue
        members = groups[title]
        click.echo(f"### {title} ({len(members)})\n")
        for rule in members:
            if isinstance(rule, tuple):
                click.echo(_table_text(*rule, deltas))
                continue
            click.echo(rule.sparql() + "\n")
            if deltas and not rule.is_check:
                click.echo(_delta_rules(rule))
        shown += len(members)
    if show_all:
        click.echo(_templates(onto.rules.all_rules))
    hidden = "" if show_all else f", {len(groups['Generic OWL 2 RL rules'])} generic rules not shown (--all)"
    click.echo(f"# {shown} rules{hidden}")


def _tables(ruleset) -> dict[str, list[Rule]]:
    """Per rule of ``rules/owl/`` the rule set holds as a table, the rows bound one by one (the schema
    tables, then the pairs of disjoint classes)."""
    from ..compile.schema import template_of

    found: dict[str, list[Rule]] = {}
    for rule in [*ruleset.held_rules(), *ruleset._per_pair()[0], *ruleset._per_pair()[1]]:
        template = template_of(rule)
        found.setdefault(template.key if template is not None else rule.name, []).append(rule)
    return found


def _table_text(name: str, rows: list[Rule], deltas: bool) -> str:
    """A rule of ``rules/owl/`` held as a table: the file's rule once, its schema rows (each with the
    axiom it comes from), and with ``deltas`` the delta rules maintenance runs for each row, whose
    terms the changed class or predicate binds."""
    from ..compile.schema import schema_rule
    from ..resources import rules_dir

    template = schema_rule(name)
    text = (rules_dir() / "owl" / f"{name}.rq").read_text().rstrip()
    lines = [f"# {name}: one rule over its table {template.table} ({len(rows)} rows)", text,
             f"# rows of {template.table} ({', '.join(template.variables)}):"]
    for rule in rows:
        row = template.row_of(rule)
        lines.append(f"#   {' '.join(row) if row is not None else '?'}   ({rule.origin})")
    out = "\n".join(lines) + "\n"
    if deltas and not rows[0].is_check:
        out += "\n" + "\n".join(_delta_rules(rule) for rule in rows)
    return out


def _templates(compiled: list[Rule]) -> str:
    """The rule files of ``rules/owl/`` as written, each with how many of the compiled rules instantiate
    it: the OWL axioms' rules of those kinds are these files with one axiom's schema row filled in."""
    from ..compile.schema import schema_rules, template_of
    from ..resources import rules_dir

    templates = schema_rules()
    out = [f"### OWL rule files of rules/owl/ ({len(templates)})\n"]
    for name, template in sorted(templates.items()):
        count = sum(1 for rule in compiled if template_of(rule) is template and template.row_of(rule) is not None)
        text = (rules_dir() / "owl" / f"{name}.rq").read_text().rstrip()
        out.append(f"# {name}: {count} instantiation(s) among the OWL axioms' rules\n{text}\n")
    return "\n".join(out)


def _delta_rules(rule: Rule) -> str:
    """The semi-naive forms of ``rule`` as a REASON after a change runs them: per body atom, that atom
    on the delta graph (the facts new in this round), the others in the join order fixed for it.

    Printed as plain SPARQL 1.1, the form remote stores run; on Oxigraph a small delta runs each further
    atom under LATERAL (once per delta fact), in the same order.
    """
    from ..reason.insert_text import insert_text

    blocks = []
    for j, atom in enumerate(rule.body):
        blocks.append(f"#   delta on atom {j + 1} ({atom.text()}):\n{insert_text(rule, j, planned=True, lateral=False)}\n")
    return "\n".join(blocks)


def _step_program(onto, props: list[str]) -> str:
    """The compiled step of replacing a value of each property in ``props`` (see reason/program.py and reason/step_compiler.py)."""
    from ..reason.program import Refused, describe, signature

    onto.reason()
    reasoner = onto._reasoner
    keys = {f"<{onto.iri(p).value}>": 1 for p in props}
    sig = signature((keys, {}), (keys, {}), keys)
    try:
        program = reasoner.step.compiler.compile(sig, reasoner.state.present, reasoner.state.asserted)
    except Refused as why:
        return f"# not compiled: {why}"
    return describe(program)


# --------------------------------------------------------------------------- query


def _parse_params(pairs: Sequence[str]) -> dict[str, object]:
    params: dict[str, object] = {}
    for pair in pairs:
        name, sep, value = pair.partition("=")
        if not sep or not name:
            raise click.UsageError(f"--param takes NAME=VALUE, not {pair!r}")
        params[name] = int(value) if value.lstrip("-").isdigit() else value
    return params


def _rows(items: list[QueryItem]) -> tuple[list[str], list[list[str]]]:
    """Regroup aRMOR-style flat items into rows: every row lists every variable, in order."""
    variables: list[str] = []
    for item in items:
        if item.key in variables:
            break
        variables.append(item.key)
    width = len(variables) or 1
    return variables, [[i.value for i in items[k : k + width]] for k in range(0, len(items), width)]


@click.command()
@click.argument("args", nargs=-1, metavar="FILE... NAME_OR_RQ_FILE")
@click.option("--param", "-p", "params", multiple=True, metavar="NAME=VALUE", help="A query parameter (repeatable).")
@click.option("--format", "fmt", type=click.Choice(["table", "json", "tsv"]), default="table", show_default=True)
@click.option("--list", "list_only", is_flag=True, help="List the named queries and their parameters.")
@click.option(
    "--full-iris", is_flag=True, help="Show full IRIs in tables instead of names in the ontology's namespace."
)
@store_option
def query(
    args: tuple[str, ...], params: tuple[str, ...], fmt: str, list_only: bool, full_iris: bool, store: str | None
) -> None:
    """Reason on FILE(s), then run a named query (see --list), a SQWRL query of the files by its
    name, or a SPARQL .rq file.  ``--list`` with FILE(s) also lists their SQWRL queries.

    \b
    Examples:
      topostore query --list
      topostore query ontology/topological_map.ttl ontology/topological_map_abox.ttl urgent-locations
      topostore query ontology/*.ttl reachable-locations --param robot=Robot1 --format json
      topostore query --store out/mapdb urgent-locations      # the ontology kept in a store
    """
    if list_only:
        for q in named_queries().values():
            sig = " ".join(f"{name}={kind}" for name, kind in q.params.items())
            click.echo(f"{q.name}{' ' + sig if sig else ''}\n    {q.description}")
        if args:  # FILE(s) given: their SQWRL queries too
            _existing(args)
            for name, query in load_files(args).rules.queries.items():
                click.echo(f"{name}\n    {query.description}: columns {', '.join(query.columns)}")
        return
    if len(args) < (1 if store else 2):
        raise click.UsageError("give the ontology file(s) and then a query name or .rq file (topostore query --list)")
    files, name = args[:-1], args[-1]
    _existing(files)
    onto = load_files(files, store=store)
    report = reason_with_progress(onto)
    if not report.consistent:
        click.echo(
            f"warning: the ontology is inconsistent ({report.explain()}); answering from asserted facts only", err=True
        )
    items = onto.query(name, _parse_params(params))
    variables, rows = _rows(items)
    if fmt == "json":
        click.echo(json.dumps([dict(zip(variables, row, strict=False)) for row in rows], indent=2, ensure_ascii=False))
    elif fmt == "tsv":
        if variables:
            click.echo("\t".join(variables))
        for row in rows:
            click.echo("\t".join(v.replace("\t", " ").replace("\n", " ") for v in row))
    else:
        table = Table(*variables) if variables else Table("(no variables)")
        for row in rows:
            table.add_row(*[v if full_iris else _readable(v, onto.prefix) for v in row])
        Console(highlight=False, soft_wrap=True).print(table)
        click.echo(f"{len(rows)} row(s)")


def _readable(value: str, prefix: str) -> str:
    """A table cell: names in the ontology's namespace without it, XML Schema values without their datatype."""
    if value.startswith(prefix):
        return value[len(prefix) :]
    lexical, sep, datatype = value.rpartition("^^")
    if sep and datatype.startswith(XSD):
        return lexical
    return value


__all__ = ["reason", "rules", "query", "EXIT_INCONSISTENT"]
