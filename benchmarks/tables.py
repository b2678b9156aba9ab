"""The tables after the step table: drift, remote store, full REASON (with their targets, met or missed).

Rows come from :mod:`benchmarks.drift`, :mod:`benchmarks.remote` and :mod:`benchmarks.full`; the
targets are those of issue 20 (drift, requests per step) and issue 21 (full REASON at scale, the
TBox-heavy file against Pellet).
"""

from __future__ import annotations

from typing import Any

from .report import ms, verdict

#: issue 20: late/early step median; HTTP requests per example step
DRIFT_MAX, REQUESTS_MAX = 1.5, 3
#: issue 21: full REASON at 10,000 (s); load + full at 100,000 (s) and its peak RSS (MiB); growth law; TBox (s)
FULL_10K_S, FULL_100K_S, FULL_100K_MIB, GROWTH_MAX, TBOX_S = 1.0, 10.0, 1536, 12.0, 0.3


def extra_tables(rows: list[dict[str, Any]]) -> str:
    """Every table the rows call for, each followed by its targets; '' when there are no rows."""
    parts = []
    for kind, render in (("drift", drift_table), ("remote", remote_table), ("full", full_table),
                         ("tbox_steps", tbox_steps_table)):
        mine = [r for r in rows if r["kind"] == kind]
        if mine:
            parts.append(render(mine))
    return "\n\n".join(parts)


def drift_table(rows: list[dict[str, Any]]) -> str:
    lines = ["Drift (topostore, one long walk per map; issue 20: steps 3,900-4,000 within 1.5x of steps 10-100):", "",
             "| map | steps | median, steps 10-100 | median, last 100 steps | ratio | longest step (at) | answers |",
             "|---|---|---|---|---|---|---|"]
    verdicts = []
    for r in rows:
        if r.get("error") or r.get("killed"):
            lines.append(f"| {r['label']} | – | – | – | – | – | run {r.get('killed') or 'failed'} |")
            continue
        ratio = r.get("drift")
        lines.append(f"| {r['label']} | {r['steps']:,} | {ms(r['early_ms'])} | {ms(r['late_ms'])} | "
                     f"{'–' if ratio is None else f'{ratio:.2f}'} | {ms(r['longest_ms'])} (step {r['longest_step']}) | "
                     f"{_answers(r)} |")
        if ratio is not None:
            verdicts.append(verdict(f"drift ≤ {DRIFT_MAX} on {r['label']}", f"{ratio:.2f}", ratio <= DRIFT_MAX))
    return "\n".join(lines + ["", "Targets:", *(verdicts or ["- not measured in this run"])])


def remote_table(rows: list[dict[str, Any]]) -> str:
    lines = ["Remote store (the same step through ArmorService on a real `oxigraph serve`; HTTP requests counted "
             "at the transport):", "",
             "| map | HTTP requests per step, median / most | by endpoint (last step) | by command (median) | "
             "LOAD requests | step median / p95 | answers |", "|---|---|---|---|---|---|---|"]
    verdicts = []
    for r in rows:
        if r.get("error") or r.get("killed"):
            lines.append(f"| {r['label']} | – | – | – | – | – | run {r.get('killed') or 'failed: ' + str(r['error'])[:200]} |")
            continue
        ends = ", ".join(f"{k} {v}" for k, v in sorted(r["last_step_requests"].items()))
        commands = ", ".join(f"{c} {_num(n)}" for c, n in r.get("requests_by_command", {}).items()) or "–"
        lines.append(f"| {r['label']} | {_num(r['requests_median'])} / {_num(r['requests_max'])} | {ends} | "
                     f"{commands} | {r['load_requests']} | {ms(r['median_ms'])} / {ms(r['p95_ms'])} | {_answers(r)} |")
        if r["size"] == "example" and r["requests_median"] is not None:
            verdicts.append(verdict(f"HTTP requests per step ≤ {REQUESTS_MAX} on the example map",
                                    _num(r["requests_median"]), r["requests_median"] <= REQUESTS_MAX))
    return "\n".join(lines + ["", "Targets:", *(verdicts or ["- not measured in this run"])])


def full_table(rows: list[dict[str, Any]]) -> str:
    """Load, REASON and peak RSS per engine and input; the TBox answers held against Pellet's."""
    pellet = next((r.get("types") for r in rows if r["engine"] == "pellet" and r.get("types")), None)
    lines = ["Full REASON (each engine in its own process on the same N-Triples file; reasonable and owlrl are "
             "OWL 2 RL without SWRL, Pellet runs through Owlready2 and its time includes the JVM start):", "",
             "| input | engine | load | REASON | load + REASON | peak RSS | answers |", "|---|---|---|---|---|---|---|"]
    for r in rows:
        if "reason_s" not in r:
            why = r.get("killed") or f"failed: {str(r.get('error'))[:200]}"
            lines.append(f"| {r['label']} | {r['engine']} | – | – | – | – | {why} |")
            continue
        lines.append(f"| {r['label']} | {r['engine']} | {_s(r['load_s'])} | {_s(r['reason_s'])} | "
                     f"{_s(r['load_s'] + r['reason_s'])} | {_mib(r['peak_rss_mib'])} | {_full_answers(r, pellet)} |")
    return "\n".join(lines + ["", "Growth and targets:", *full_targets(rows, pellet)])


def full_targets(rows: list[dict[str, Any]], pellet: dict[str, list[str]] | None) -> list[str]:
    """Issue 21's targets for topostore, and the growth law full(100,000) / full(10,000)."""
    topo = {r["size"]: r for r in rows if r["engine"] == "topostore" and "reason_s" in r}
    out = []
    if (ten := topo.get("10000")) is not None:
        out.append(verdict(f"full REASON ≤ {FULL_10K_S:g} s at 10,000", _s(ten["reason_s"]), ten["reason_s"] <= FULL_10K_S))
    if (big := topo.get("100000")) is not None:
        both = big["load_s"] + big["reason_s"]
        out.append(verdict(f"load + full REASON ≤ {FULL_100K_S:g} s at 100,000", _s(both), both <= FULL_100K_S))
        out.append(verdict("peak RSS ≤ 1.5 GiB at 100,000", _mib(big["peak_rss_mib"]), big["peak_rss_mib"] <= FULL_100K_MIB))
    for engine in sorted({r["engine"] for r in rows}):
        mine = {r["size"]: r for r in rows if r["engine"] == engine and "reason_s" in r}
        if "10000" in mine and "100000" in mine:
            law = mine["100000"]["reason_s"] / mine["10000"]["reason_s"]
            what = f"growth law, {engine}: full(100,000) / full(10,000)"
            out.append(verdict(f"{what} ≤ {GROWTH_MAX:g}", f"{law:.1f}", law <= GROWTH_MAX) if engine == "topostore"
                       else f"- {what}: {law:.1f}")
    tb = next((r for r in rows if r["engine"] == "topostore" and r.get("input_kind") == "tbox" and "reason_s" in r), None)
    if tb is not None:
        out.append(verdict(f"TBox-heavy file ≤ {TBOX_S:g} s", _s(tb["reason_s"]), tb["reason_s"] <= TBOX_S))
        if pellet is not None:
            diff = type_differences(tb.get("types", {}), pellet)
            out.append(verdict("TBox answers (named types of every individual) equal to Pellet's",
                               "equal" if not diff else f"{len(diff)} individuals differ: " + "; ".join(diff[:4]),
                               not diff))
    return out or ["- not measured in this run"]


def tbox_steps_table(rows: list[dict[str, Any]]) -> str:
    """Robot-like steps on the TBox-heavy file: the first apart, then the median and p95 of the others."""
    lines = ["Steps on the TBox-heavy file (topostore: type individuals, add and remove a property value, REASON; "
             "every step's answers held against a full REASON from scratch):", "",
             "| input | LOAD + full REASON | steps | first step | median | p95 | REASON modes | answers |",
             "|---|---|---|---|---|---|---|---|"]
    for r in rows:
        if "median_ms" not in r:
            why = r.get("killed") or f"failed: {str(r.get('error'))[:200]}"
            lines.append(f"| {r['label']} | – | – | – | – | – | – | {why} |")
            continue
        modes = ", ".join(f"{m} {n}" for m, n in r["modes"].items())
        answers = f"**MISMATCH** ({len(r['mismatches'])}): {r['mismatches'][0]}" if r["mismatches"] else \
            f"equal to full REASON ({r['answers']} triples)"
        lines.append(f"| {r['label']} | {_s(r['load_and_full_s'])} | {r['steps']} | {ms(r['first_ms'])} | "
                     f"{ms(r['median_ms'])} | {ms(r['p95_ms'])} | {modes} | {answers} |")
    return "\n".join(lines)


def type_differences(mine: dict[str, list[str]], pellet: dict[str, list[str]]) -> list[str]:
    """Per individual, the types only one side gives ('x: +A -B': A only here, B only Pellet's)."""
    out = []
    for name in sorted(set(mine) | set(pellet)):
        extra, missing = sorted(set(mine.get(name, [])) - set(pellet.get(name, []))), \
            sorted(set(pellet.get(name, [])) - set(mine.get(name, [])))
        if extra or missing:
            out.append(f"{name}: " + " ".join([f"+{c}" for c in extra] + [f"-{c}" for c in missing]))
    return out


def _full_answers(row: dict[str, Any], pellet: dict[str, list[str]] | None) -> str:
    if row.get("mismatches"):
        return f"**MISMATCH**: {row['mismatches'][0]}"
    if row.get("input_kind") == "map":
        return "canReach as expected" if "can_reach" in row else "OWL part only (no SWRL)"
    if row["engine"] == "pellet" or pellet is None:
        return "the reference" if row["engine"] == "pellet" else "Pellet not run"
    diff = type_differences(row.get("types", {}), pellet)
    return "types equal to Pellet's" if not diff else f"{len(diff)} individuals differ from Pellet ({diff[0]})"


def _answers(row: dict[str, Any]) -> str:
    return f"**MISMATCH** ({len(row['mismatches'])})" if row.get("mismatches") else "as expected"


def _num(x: float | None) -> str:
    return "–" if x is None else f"{x:g}"


def _s(x: float | None) -> str:
    return "–" if x is None else f"{x:.2f} s" if x < 10 else f"{x:,.1f} s"


def _mib(x: float | None) -> str:
    return "–" if x is None else f"{x:,.0f} MiB" if x < 1024 else f"{x / 1024:.2f} GiB"
