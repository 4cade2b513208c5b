#!/usr/bin/env python3
"""Draws docs/stability/levers/{curvature_floor,pdf_smoothing}.png from the measured tables beside them.

GKPCD2 against its curvature floor (--curvature-floor), and every keypoint function against the PDFs'
kernel width (--pdf-smoothing): the stability ratio on the 38 real crops (lower is steadier; PCL ESF's
in the same session as a line) beside the accuracy it costs, so each lever's trade-off is seen at once.
The figures are measurements (each CSV's header says how each was made); this script only draws them.

usage: python3 scripts/plot-stability-levers.py [docs/stability/levers]
"""
import csv
import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

ESF_RATIO = 0.162  # PCL ESF on the same crops, same session (docs/descriptors.md)
PAPER_FLOOR = 1e-4


def read_rows(source: Path) -> list:
    rows = [r for r in csv.DictReader(line for line in source.open() if not line.startswith("#"))]
    if not rows:
        raise SystemExit(f"plot-stability-levers: {source}: no rows")
    return rows


def draw_smoothing(folder: Path) -> Path:
    rows = read_rows(folder / "pdf_smoothing.csv")
    fig, (left, right) = plt.subplots(1, 2, figsize=(11, 4.2), dpi=110)
    functions = ("kpd2", "kpd3", "kpa3", "gkpd1", "gkpd2", "gkpcd2", "s_kpd2")
    for name in functions:
        pts = [(float(r["sigma"]), float(r[name])) for r in rows if r[name]]
        left.plot([p[0] for p in pts], [p[1] for p in pts], "o-", label=name)
    esf = next(float(r["esf"]) for r in rows if r["esf"])
    left.axhline(esf, color="black", linestyle=":", label=f"PCL ESF ({esf})")
    left.set_xlabel("kernel σ (bins; 0: the histogram as binned)")
    left.set_ylabel("stability ratio on 38 real crops (lower is steadier)")
    left.legend(fontsize=7.5, ncol=2)
    left.set_title("Steadier under noise with a wider kernel", fontsize=10)
    for key, name, marker in (("mosd", "real mOSD objects (change)", "s-"), ("li27", "27 simulated, leave-instance", "o--"),
                              ("le27", "27 simulated, leave-elevation", "^--")):
        base = float(rows[0][key])
        pts = [(float(r["sigma"]), float(r[key]) - base) for r in rows if r[key]]
        right.plot([p[0] for p in pts], [p[1] for p in pts], marker, label=name)
    right.axhline(0, color="grey", linewidth=0.6)
    right.set_ylim(-6, 3)
    right.set_xlabel("kernel σ (bins)")
    right.set_ylabel("mean accuracy change, points")
    right.legend(fontsize=7.5, loc="lower left")
    right.set_title("What it costs (one real view is 2.6 points)", fontsize=10)
    fig.tight_layout()
    out = folder / "pdf_smoothing.png"
    fig.savefig(out)
    return out


def main() -> int:
    folder = Path(sys.argv[1] if len(sys.argv) > 1 else "docs/stability/levers")
    print(draw_smoothing(folder))
    rows = read_rows(folder / "curvature_floor.csv")
    floor = [float(r["floor"]) for r in rows]
    ratio = [float(r["ratio"]) for r in rows]

    fig, left = plt.subplots(figsize=(7.5, 4.2), dpi=110)
    left.plot(floor, ratio, "o-", color="tab:blue", label="GKPCD2 stability ratio (38 real crops)")
    left.axhline(ESF_RATIO, color="tab:blue", linestyle=":", label=f"PCL ESF ratio ({ESF_RATIO})")
    left.set_xscale("log")
    left.set_xlabel("curvature floor ε (log scale; the paper's 10⁻⁴ at the left)")
    left.set_ylabel("stability ratio (lower is steadier)", color="tab:blue")
    left.set_ylim(0, max(ratio) * 1.25)

    right = left.twinx()
    for key, colour, name in (("xgboost", "tab:orange", "XGBoost"), ("mlp", "tab:green", "network")):
        xs = [f for f, r in zip(floor, rows) if r[key]]
        ys = [float(r[key]) for r in rows if r[key]]
        right.plot(xs, ys, "s--", color=colour, label=f"real mOSD accuracy, {name}")
    right.axhline(55.3, color="grey", linestyle=":", label="majority class (55.3 %)")
    right.set_ylabel("leave-one-object-out accuracy %")
    right.set_ylim(40, 100)

    lines = left.get_legend_handles_labels()
    more = right.get_legend_handles_labels()
    left.legend(lines[0] + more[0], lines[1] + more[1], loc="lower left", fontsize=7.5, framealpha=0.9)
    left.axvline(PAPER_FLOOR, color="black", linewidth=0.5)
    left.set_title("GKPCD2: steadier with a higher curvature floor, until it is GKPD2", fontsize=10)
    fig.tight_layout()
    out = folder / "curvature_floor.png"
    fig.savefig(out)
    print(out)
    return 0


if __name__ == "__main__":
    sys.exit(main())
