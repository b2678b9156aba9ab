"""The aRMOR command table: every COMMAND/SPEC1/SPEC2 of spec §3, its arguments and its handler.

The handlers live by family: manipulations in :mod:`.manipulation`, queries in
:mod:`.query`, administration of the service and its references in
:mod:`.admin`, the commands beyond aRMOR in :mod:`.live_commands`; what they
share (:class:`Context`, :class:`Reply`, :class:`Command`) in :mod:`.context`.
This module only assembles them into :data:`COMMANDS`, the one place that
says which key runs which handler and how the call is gated (arity, needs a
reference, counts as a manipulation).  Failures are raised as
:class:`~topostore.armor.codes.CommandError` with a documented exit code and a
message that says what to fix; the service turns them into replies.
"""

from __future__ import annotations

from .admin import (
    drop,
    get_all_refs,
    get_ref_client,
    invalid_command,
    load,
    log_file_off,
    log_file_on,
    log_screen,
    mount,
    save,
    unmount,
)
from .context import Command, Context, Handler, Reply
from .live_commands import live_commands
from .manipulation import (
    add_cardinality_min,
    add_class,
    add_class_class,
    add_dataprop_ind,
    add_ind,
    add_ind_class,
    add_objectprop_ind,
    apply_buffer,
    disjoint_class,
    disjoint_class_class,
    disjoint_ind,
    disjoint_ind_class,
    make_equivalent_class,
    reason,
    remove_class,
    remove_class_class,
    remove_dataprop_ind,
    remove_ind,
    remove_ind_class,
    remove_objectprop_ind,
    rename,
    replace_dataprop_ind,
    replace_objectprop_ind,
)
from .query import (
    most_specific,
    query_class_class,
    query_class_ind,
    query_dataprop_ind,
    query_ind,
    query_ind_class,
    query_ind_dataprop,
    query_ind_objectprop,
    query_objectprop_ind,
    query_sparql,
    query_sparql_formatted,
    run_select,
)
from .restrictions import query_class_restrictions


def _table() -> dict[tuple[str, str, str], Command]:
    """Key (COMMAND, SPEC1, SPEC2), upper case → command.  Tuples, so a ``_`` in a field cannot fake a key."""
    m = dict(needs_ref=True, manipulation=True)
    q = dict(needs_ref=True, manipulation=False)
    table = {
        ("ADD", "IND", ""): Command(add_ind, ("individual",), 1, 1, **m),
        ("ADD", "CLASS", ""): Command(add_class, ("class",), 1, 1, **m),
        ("ADD", "IND", "CLASS"): Command(add_ind_class, ("individual", "class"), 2, 2, **m),
        ("ADD", "CLASS", "CLASS"): Command(add_class_class, ("subclass", "superclass"), 2, 2, **m),
        ("ADD", "DATAPROP", "IND"): Command(add_dataprop_ind, ("property", "individual", "type", "value"), 4, 4, **m),
        ("ADD", "OBJECTPROP", "IND"): Command(add_objectprop_ind, ("property", "individual", "value"), 3, 3, **m),
        ("ADD", "CARDINALITY", "MIN"): Command(
            add_cardinality_min, ("class", "property", "n", "value class"), 4, 4, **m
        ),
        ("ADD", "MIN", "CARDINALITY"): Command(
            add_cardinality_min, ("class", "property", "n", "value class"), 4, 4, **m
        ),
        ("DISJOINT", "IND", ""): Command(disjoint_ind, ("individual", "individual", "..."), 2, None, **m),
        ("DISJOINT", "CLASS", ""): Command(disjoint_class, ("class", "class", "..."), 2, None, **m),
        ("DISJOINT", "IND", "CLASS"): Command(disjoint_ind_class, ("class",), 1, 1, **m),
        ("DISJOINT", "CLASS", "CLASS"): Command(disjoint_class_class, ("class",), 1, 1, **m),
        ("MAKE", "EQUIVALENT", "CLASS"): Command(make_equivalent_class, ("class",), 1, 1, **m),
        ("REMOVE", "IND", ""): Command(remove_ind, ("individual",), 1, 1, **m),
        ("REMOVE", "CLASS", ""): Command(remove_class, ("class",), 1, 1, **m),
        ("REMOVE", "IND", "CLASS"): Command(remove_ind_class, ("individual", "class"), 2, 2, **m),
        ("REMOVE", "CLASS", "CLASS"): Command(remove_class_class, ("subclass", "superclass"), 2, 2, **m),
        ("REMOVE", "DATAPROP", "IND"): Command(
            remove_dataprop_ind, ("property", "individual", "type", "value"), 4, 4, **m
        ),
        ("REMOVE", "OBJECTPROP", "IND"): Command(remove_objectprop_ind, ("property", "individual", "value"), 3, 3, **m),
        ("REPLACE", "DATAPROP", "IND"): Command(
            replace_dataprop_ind, ("property", "individual", "type", "new", "old"), 5, 5, **m
        ),
        ("REPLACE", "OBJECTPROP", "IND"): Command(
            replace_objectprop_ind, ("property", "individual", "new", "old"), 4, 4, **m
        ),
        ("APPLY", "", ""): Command(apply_buffer, (), 0, 0, **m),
        ("REASON", "", ""): Command(reason, (), 0, 0, **m),
        ("QUERY", "IND", ""): Command(query_ind, ("individual",), 1, 1, **q),
        ("QUERY", "IND", "CLASS"): Command(query_ind_class, ("class",), 1, 1, **q),
        ("QUERY", "DATAPROP", "IND"): Command(query_dataprop_ind, ("property", "individual"), 2, 2, **q),
        ("QUERY", "OBJECTPROP", "IND"): Command(query_objectprop_ind, ("property", "individual"), 2, 2, **q),
        ("QUERY", "CLASS", "IND"): Command(query_class_ind, ("individual", "bottom"), 1, 2, **q),
        ("QUERY", "CLASS", "CLASS"): Command(query_class_class, ("class",), 1, 1, **q),
        ("QUERY", "CLASS", "RESTRICTIONS"): Command(query_class_restrictions, ("class",), 1, 1, **q),
        ("QUERY", "IND", "DATAPROP"): Command(query_ind_dataprop, ("individual",), 1, 1, **q),
        ("QUERY", "IND", "OBJECTPROP"): Command(query_ind_objectprop, ("individual",), 1, 1, **q),
        ("QUERY", "SPARQL", ""): Command(query_sparql, ("query", "timeout ms"), 1, 4, **q),
        ("QUERY", "SPARQL", "FORMATTED"): Command(query_sparql_formatted, ("query", "timeout ms"), 1, 4, **q),
        ("INVALID", "COMMAND", ""): Command(invalid_command, (), 0, None, needs_ref=False),
        ("MOUNT", "", ""): Command(mount, (), 0, 0),
        ("UNMOUNT", "", ""): Command(unmount, (), 0, 0),
        ("SAVE", "", ""): Command(save(False), ("path",), 1, 1),
        ("SAVE", "INFERENCE", ""): Command(save(True), ("path",), 1, 1),
        ("GET", "ALL", "REFS"): Command(get_all_refs, (), 0, 0, needs_ref=False),
        ("GET", "REF", "CLIENT"): Command(get_ref_client, ("reference",), 1, 1, needs_ref=False),
        ("DROP", "", ""): Command(drop, (), 0, 0, needs_ref=False),
        ("LOG", "FILE", "ON"): Command(log_file_on, ("path",), 1, 1, needs_ref=False),
        ("LOG", "FILE", "OFF"): Command(log_file_off, (), 0, 0, needs_ref=False),
        ("LOG", "SCREEN", "ON"): Command(log_screen(True), (), 0, 0, needs_ref=False),
        ("LOG", "SCREEN", "OFF"): Command(log_screen(False), (), 0, 0, needs_ref=False),
    }
    load_args = ("path or url", "ontology iri", "buffered manipulation", "reasoner", "buffered reasoner")
    for source in ("FILE", "WEB"):
        table[("LOAD", source, "")] = Command(load(source, False), load_args, 5, 5, needs_ref=False)
        table[("LOAD", source, "MOUNTED")] = Command(load(source, True), load_args, 5, 5, needs_ref=False)
    for kind in ("IND", "CLASS", "DATAPROP", "OBJECTPROP"):
        table[("RENAME", kind, "")] = Command(rename(kind), ("old", "new"), 2, 2, **m)
    return table


#: every command topostore answers: aRMOR's (spec §3) and QUERY EXPLAIN, ADD/REMOVE/QUERY SWRL
COMMANDS: dict[tuple[str, str, str], Command] = {**_table(), **live_commands()}

__all__ = ["Command", "Context", "Reply", "Handler", "COMMANDS", "run_select", "most_specific"]
