"""The machine description, the results table, the CSV and the plot."""

from __future__ import annotations

import csv
import os
import platform
from pathlib import Path

import pyoxigraph

PEER_LABELS = {"owlrl": "owlrl (OWL RL only, no SWRL)", "pellet": "Owlready2 + Pellet"}


def machine() -> dict[str, str]:
    """CPU model, cores, RAM, Python and pyoxigraph versions: what the numbers depend on."""
    cpu = platform.processor() or "unknown CPU"
    ram = "unknown"
    try:
        for line in Path("/proc/cpuinfo").read_text().splitlines():
            if line.startswith("model name"):
                cpu = line.split(":", 1)[1].strip()
                break
        for line in Path("/proc/meminfo").read_text().splitlines():
            if line.startswith("MemTotal"):
                ram = f"{int(line.split()[1]) / 1024 / 1024:.1f} GiB"
                break
    except OSError:
        pass
    return {"CPU": cpu, "cores": str(os.cpu_count()), "RAM": ram,
            "Python": platform.python_version(), "pyoxigraph": pyoxigraph.__version__,
            "OS": f"{platform.system()} {platform.release()}"}


def peer_cell(result: dict | None) -> str:
    if not result:
        return "-"
    if result["status"] == "ok":
        return f"{result['reason_s']:.2f} s"
    return result["status"]


def size_label(row: dict) -> str:
    return f"seed map ({row['locations']})" if row["size"] == "seed" else f"{int(row['size']):,}"


def full_step(row: dict) -> str:
    if not row["full_steps"]:
        return "not run"
    return f"{row['full_median_ms']:.0f} / {row['full_p95_ms']:.0f} ms ({row['full_steps']})"


def ratio(a: float, b: float) -> str:
    return f"{a / b:.0f}×" if b > 0 else "-"


def table(rows: list[dict], info: dict[str, str]) -> str:
    """A Markdown table: one row per size."""
    head = ("| locations | asserted | inferred | load | full reason | RSS after reason | peak RSS | "
            "step incremental median / p95 | step full median / p95 (n) | full/incremental | "
            "owlrl closure | owlrl/topostore full | Pellet | Pellet/topostore full | verified |")
    lines = [f"Machine: {', '.join(f'{k} {v}' for k, v in info.items())}", "", head,
             "|" + "|".join("---" for _ in head.split("|")[1:-1]) + "|"]
    for r in rows:
        peers = []
        for name in ("owlrl", "pellet"):
            p = r.get(name)
            peers.append(peer_cell(p))
            peers.append(ratio(p["reason_s"], r["full_reason_s"]) if p and p["status"] == "ok" else "-")
        lines.append(
            f"| {size_label(r)} | {r['asserted']:,} | {r['inferred']:,} | "
            f"{r['load_s']:.2f} s | {r['full_reason_s']:.2f} s | {r['rss_after_reason_mib']:.0f} MiB | "
            f"{r['rss_peak_mib']:.0f} MiB | {r['inc_median_ms']:.1f} / {r['inc_p95_ms']:.1f} ms | "
            f"{full_step(r)} | {ratio(r['full_median_ms'], r['inc_median_ms']) if r['full_steps'] else '-'} | {' | '.join(peers)} | {r['verified'] or '-'} |"
        )
    lines.append("")
    for r in rows:
        for name in ("owlrl", "pellet"):
            p = r.get(name, {})
            if p.get("status") in ("skipped", "error", "timeout"):
                lines.append(f"- {PEER_LABELS[name]} on {size_label(r)}: {p['status']} ({p.get('why', '')})")
    return "\n".join(lines)


FIELDS = ["size", "locations", "asserted", "inferred", "load_s", "full_reason_s", "rss_after_reason_mib",
          "rss_peak_mib", "inc_steps", "inc_median_ms", "inc_p95_ms", "inc_fallbacks", "full_steps",
          "full_median_ms", "full_p95_ms", "verified"]


def write_csv(rows: list[dict], path: Path) -> None:
    with path.open("w", newline="") as f:
        writer = csv.writer(f)
        writer.writerow(FIELDS + ["owlrl_s", "owlrl_status", "pellet_s", "pellet_status"])
        for r in rows:
            peers = []
            for name in ("owlrl", "pellet"):
                p = r.get(name) or {"status": "not run"}
                peers += [p.get("reason_s", ""), p["status"]]
            writer.writerow([r[k] for k in FIELDS] + peers)


def write_plot(rows: list[dict], path: Path) -> Path | None:
    """Log-log plot of the times against map size; None when matplotlib is not installed."""
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        return None
    xs = [r["locations"] for r in rows]
    fig, ax = plt.subplots(figsize=(8, 5))
    series = {
        "load": [r["load_s"] for r in rows],
        "full reason": [r["full_reason_s"] for r in rows],
        "robot step, full rematerialisation (median)": [r["full_median_ms"] / 1000 for r in rows],
        "robot step, incremental (median)": [r["inc_median_ms"] / 1000 for r in rows],
    }
    for label, ys in series.items():
        pts = [(x, y) for x, y in zip(xs, ys) if y > 0]  # steps not run have no time
        if pts:
            ax.plot(*zip(*pts), marker="o", label=label)
    for name, label in PEER_LABELS.items():
        pts = [(r["locations"], r[name]["reason_s"]) for r in rows if r.get(name, {}).get("status") == "ok"]
        if pts:
            ax.plot(*zip(*pts), marker="s", linestyle="--", label=f"{label}: reason")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("locations in the map")
    ax.set_ylabel("seconds")
    ax.set_title("topostore reasoning latency")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)
    return path
