"""The machine, the step table with its ratios and issue 20's step targets, the CSV and the plot."""

from __future__ import annotations

import csv
import os
import platform
from pathlib import Path
from typing import Any

import pyoxigraph

from .warm_pellet import java_version

#: issue 20: speed-up over warm Pellet on every compared map, the example step, big-map steps, growth
SPEEDUP_MIN, EXAMPLE_MS, STEP_MS, GROWTH_MAX = 4.0, 1.0, {"10000": 10.0, "100000": 50.0}, 5.0


def machine() -> dict[str, str]:
    """What the numbers depend on: CPU, cores, memory, versions, and how busy the machine was."""
    cpu, ram = platform.processor() or "unknown CPU", "unknown"
    try:
        cpu = next((line.split(":", 1)[1].strip() for line in Path("/proc/cpuinfo").read_text().splitlines()
                    if line.startswith("model name")), cpu)
        kib = next(int(line.split()[1]) for line in Path("/proc/meminfo").read_text().splitlines()
                   if line.startswith("MemTotal"))
        ram = f"{kib / 1024 / 1024:.1f} GiB"
    except (OSError, StopIteration, ValueError):
        pass
    return {"CPU": cpu, "cores": str(os.cpu_count()), "memory": ram, "Python": platform.python_version(),
            "pyoxigraph": pyoxigraph.__version__, "Java": java_version(),
            "OS": f"{platform.system()} {platform.release()}",
            "load average at start": " ".join(f"{x:.2f}" for x in os.getloadavg())}


def summary(row: dict[str, Any]) -> dict[str, Any]:
    """One flat record per map size, whatever measured it (the table, the CSV and the plot read this)."""
    topo = row.get("topostore", row)  # compare rows nest topostore's figures; scale rows are flat
    pellet = row.get("pellet") or {}
    load_first_s = topo["load_first_ms"] / 1000 if "load_first_ms" in topo else row.get("load_first_s")
    out = {"kind": row["kind"], "size": row["size"], "label": row["label"], "locations": row["locations"],
           "doors": row["doors"], "triples": row["triples"],
           "pellet_status": pellet.get("status", "not run"), "pellet_steps": len(pellet.get("step_ms", [])),
           "pellet_median_ms": pellet.get("median_ms"), "pellet_p95_ms": pellet.get("p95_ms"),
           "pellet_load_ms": pellet.get("load_ms"), "pellet_first_reason_ms": pellet.get("first_ms"),
           "topostore_steps": len(topo.get("step_ms", [])), "topostore_median_ms": topo.get("median_ms"),
           "topostore_p95_ms": topo.get("p95_ms"), "load_first_reason_s": load_first_s,
           "full_reason_s": row.get("full_s"), "peak_rss_mib": topo.get("peak_rss_mib"),
           "compared_steps": row.get("compared_steps"), "mismatches": len(row.get("mismatches", []))}
    out["speedup"] = _ratio(out["pellet_median_ms"], out["topostore_median_ms"])
    out["full_over_step"] = _ratio(out["full_reason_s"] and out["full_reason_s"] * 1000, out["topostore_median_ms"])
    return out


def _ratio(a: float | None, b: float | None) -> float | None:
    return a / b if a and b else None


def ms(x: float | None) -> str:
    if x is None:
        return "–"
    return f"{x:.2f} ms" if x < 10 else f"{x:.1f} ms" if x < 100 else f"{x:,.0f} ms"


def times(x: float | None) -> str:
    return "–" if x is None else f"{x:.2f}×" if x < 10 else f"{x:,.0f}×"


def pellet_cell(s: dict[str, Any], row: dict[str, Any]) -> str:
    if row["kind"] == "scale":
        return "not run (topostore only)"
    p = row.get("pellet", {})
    if not s["pellet_steps"]:
        return f"{s['pellet_status']}: {p.get('why', '')}"
    cell = f"{ms(s['pellet_median_ms'])} / {ms(s['pellet_p95_ms'])} ({s['pellet_steps']}"
    if p.get("stopped"):
        cell += f" of {s['topostore_steps']}: {p['stopped']}"
    if s["pellet_status"] != "ok":
        cell += f"; then {s['pellet_status']}"
    return cell + ")"


def speedup_cell(s: dict[str, Any]) -> str:
    """The speed-up, marked against the target (compared maps only)."""
    if s["speedup"] is None:
        return "–"
    return f"{times(s['speedup'])} {'met' if s['speedup'] >= SPEEDUP_MIN else 'missed'}"


def warmup_note(row: dict[str, Any]) -> str:
    """How far the Pellet JVM was warmed before its measured load, and the JIT's curve during it."""
    p = row["pellet"]
    return (f"- {row['label']}, Pellet warm-up on a scratch copy: {p['warm_steps']} steps in {p['warm_s']:.1f} s, "
            f"median of its first 20 steps {ms(p['warm_first_ms'])}, of its last 20 {ms(p['warm_last_ms'])}")


def answers_cell(s: dict[str, Any], row: dict[str, Any]) -> str:
    if row.get("killed") or row.get("error"):
        return f"run {row.get('killed') or 'failed'}"
    if s["mismatches"]:
        return f"**MISMATCH** ({s['mismatches']})"
    if row["kind"] == "scale":
        return f"as expected ({s['topostore_steps']} steps)"
    if not s["compared_steps"]:
        return "as expected (Pellet not compared)"
    return f"equal ({s['compared_steps']} steps)"


def table(rows: list[dict[str, Any]], info: dict[str, str]) -> str:
    """The Markdown report: machine, one table, ratios, targets, notes."""
    sums = [summary(r) for r in rows]
    lines = ["Machine: " + ", ".join(f"{k} {v}" for k, v in info.items()), "",
             "| locations | map | topostore step median / p95 (steps) | warm Pellet step median / p95 (steps) | "
             f"speed-up (≥ {SPEEDUP_MIN:g}×) | answers | topostore load + first REASON | full REASON | full / step | "
             "peak RSS |",
             "|---|---|---|---|---|---|---|---|---|---|"]
    for s, r in zip(sums, rows):
        lines.append(
            f"| {s['locations']:,} | {s['label']} | "
            f"{ms(s['topostore_median_ms'])} / {ms(s['topostore_p95_ms'])} ({s['topostore_steps']}) | "
            f"{pellet_cell(s, r)} | {speedup_cell(s)} | {answers_cell(s, r)} | "
            f"{_seconds(s['load_first_reason_s'])} | {_seconds(s['full_reason_s'])} | {times(s['full_over_step'])} | "
            f"{_mib(s['peak_rss_mib'])} |")
    lines += ["", "Ratios:", *ratios(sums), "", "Targets (issue 20):", *targets(sums)]
    notes = [f"- {r['label']}: {m}" for r in rows for m in r.get("mismatches", [])[:5]]
    notes += [f"- {r['label']}, Pellet: {r['pellet']['why']}" for r in rows
              if r.get("pellet", {}).get("why") and r["pellet"]["status"] != "skipped"]
    notes += [warmup_note(r) for r in rows if r.get("pellet", {}).get("warm_steps")]
    notes += [f"- {r['label']}: full REASON not run ({r['full_skipped']})" for r in rows if r.get("full_skipped")]
    notes += [f"- {r['label']}: steps stopped at the {r['stopped']}" for r in rows if r.get("stopped")]
    notes += [f"- {r['label']}: {r['error']}" for r in rows if r.get("error")]
    notes += [f"- {r['label']}: {r['killed']}; the figures above are what it measured until then" for r in rows
              if r.get("killed")]
    return "\n".join(lines + (["", "Notes:", *notes] if notes else []))


def ratios(sums: list[dict[str, Any]]) -> list[str]:
    by_size = {s["size"]: s for s in sums}
    speedups = [f"{s['label']} {times(s['speedup'])}" for s in sums if s["speedup"]]
    out = [f"- topostore speed-up vs warm Pellet (Pellet step median / topostore step median): "
           f"{', '.join(speedups) or 'Pellet not run'}"]
    small, big = by_size.get("1000"), by_size.get("100000")
    if small and big and small["topostore_median_ms"] and big["topostore_median_ms"]:
        out.append(f"- step(100,000) / step(1,000): {big['topostore_median_ms'] / small['topostore_median_ms']:.1f}")
    if (ten := by_size.get("10000")) and ten["full_over_step"]:
        out.append(f"- full REASON / step at 10,000: {ten['full_over_step']:.0f}")
    return out


def targets(sums: list[dict[str, Any]]) -> list[str]:
    """Issue 20's step targets, each with what this run measured, met or missed."""
    by_size = {s["size"]: s for s in sums}
    compared = [s for s in sums if s["kind"] == "compare" and s["speedup"]]
    out = []
    if compared:
        worst = min(compared, key=lambda s: s["speedup"])
        out.append(verdict(f"step ≥ {SPEEDUP_MIN:g}× faster than warm Pellet on every compared map",
                           f"lowest {times(worst['speedup'])} ({worst['label']})", worst["speedup"] >= SPEEDUP_MIN))
    if (ex := by_size.get("example")) and ex["topostore_median_ms"]:
        out.append(verdict(f"step ≤ {EXAMPLE_MS:g} ms on the example map", ms(ex["topostore_median_ms"]),
                           ex["topostore_median_ms"] <= EXAMPLE_MS))
    for size, limit in STEP_MS.items():
        if (row := by_size.get(size)) and row["topostore_median_ms"]:
            out.append(verdict(f"step ≤ {limit:g} ms at {int(size):,}", ms(row["topostore_median_ms"]),
                               row["topostore_median_ms"] <= limit))
    big, one = by_size.get("100000"), by_size.get("1000")
    if big and one and big["topostore_median_ms"] and one["topostore_median_ms"]:
        r = big["topostore_median_ms"] / one["topostore_median_ms"]
        out.append(verdict(f"step(100,000) / step(1,000) ≤ {GROWTH_MAX:g}", f"{r:.1f}", r <= GROWTH_MAX))
    return out or ["- not measured in this run"]


def verdict(what: str, measured: str, met: bool) -> str:
    """'- what: measured — met' (or missed): one line per target."""
    return f"- {what}: {measured} — {'met' if met else 'missed'}"


def _seconds(x: float | None) -> str:
    return "–" if x is None else f"{x:.2f} s" if x < 10 else f"{x:,.1f} s"


def _mib(x: float | None) -> str:
    return "–" if x is None else f"{x:,.0f} MiB" if x < 1024 else f"{x / 1024:.2f} GiB"


def write_csv(rows: list[dict[str, Any]], path: Path) -> None:
    sums = [summary(r) for r in rows]
    with path.open("w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=list(sums[0]) if sums else ["size"])
        writer.writeheader()
        writer.writerows(sums)


def write_plot(rows: list[dict[str, Any]], path: Path) -> Path:
    """Step medians (both reasoners) and topostore's full REASON against map size, log-log."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    sums = [summary(r) for r in rows]
    series = {"warm Pellet: robot step (median)": ("pellet_median_ms", 1.0, "s--"),
              "topostore: robot step (median)": ("topostore_median_ms", 1.0, "o-"),
              "topostore: full REASON": ("full_reason_s", 1000.0, "^:")}
    fig, ax = plt.subplots(figsize=(8, 5))
    for label, (key, scale, style) in series.items():
        pts = [(s["locations"], s[key] * scale) for s in sums if s[key]]
        if pts:
            ax.plot(*zip(*pts), style, label=label)
    for s in sums:
        if s["speedup"]:
            ax.annotate(times(s["speedup"]), (s["locations"], s["topostore_median_ms"]), textcoords="offset points",
                        xytext=(4, -12), fontsize=8)
    ax.set(xscale="log", yscale="log", xlabel="locations in the map", ylabel="milliseconds",
           title="Robot step: topostore vs warm Pellet (labels: topostore speed-up)")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)
    return path
