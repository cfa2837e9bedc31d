#!/usr/bin/env python3
"""The cohort at a glance: per subject the step times, tets, smallest dihedral angle, Dice per tissue, fit for FEM
or not and why, or the step that failed and its one-line error; as CSV and as one self-contained HTML page.

Reads what the steps left in each subject's folder (their --json summaries) and, for a step that did not finish,
its log (OUT/logs/<subject>/<step>.log, written by the Snakefile). Also works on the folders of the Makefile's
cohort target (no logs there: a failed step shows as where the subject stopped):

    python3 data/workflows/snakemake/cohort_summary.py /abs/out/cohort     # writes cohort.csv and cohort.html there
"""
import argparse
import csv
import html
import io
import json
import os
import sys
from pathlib import Path

CHAIN = ["prep", "extract", "smooth", "decimate", "remesh", "tetra", "assess", "refine", "check-mesh", "solve",
         "render-surface", "render-section", "render-quality", "render-convergence", "render-potential",
         "render-field", "report"]
SOLVE_STEPS = ("solve", "render-potential", "render-field")
COLOURS = ["#4e79a7", "#f28e2b", "#e15759", "#76b7b2", "#59a14f", "#edc948", "#b07aa1", "#ff9da7", "#9c755f",
           "#bab0ac", "#86bcb6", "#d37295", "#a0cbe8", "#ffbe7d", "#8cd17d", "#f1ce63", "#499894"]


def _read_json(path):
    try:
        return json.loads(Path(path).read_text())
    except (OSError, ValueError):
        return None


def _log_lines(path):
    try:
        return [line.strip() for line in Path(path).read_text(errors="replace").splitlines() if line.strip()]
    except OSError:
        return None


def summarise_subject(root, subject, chain):
    """One row: what the subject's folder and logs say about its chain of steps (`chain`, in order)."""
    folder, row = Path(root) / subject, {"subject": subject, "status": "done", "failed_step": "", "error": "",
                                         "fit_for_fem": "", "why": ""}
    seconds, peak = {}, 0.0
    for step in chain:
        if step == "labels":  # the Snakefile's conversion of a dseg.tsv: a file, no summary
            if (Path(root) / "labels" / f"{subject}.json").is_file():
                continue
            summary = None
        else:
            summary = _read_json(folder / f"{step}.json")
        if summary is not None and summary.get("status") == "ok":
            seconds[step] = float(summary.get("seconds", 0))
            peak = max(peak, float(summary.get("peak_memory_mb", 0)))
            continue
        row["failed_step"] = step
        lines = _log_lines(Path(root) / "logs" / subject / f"{step}.log")
        defects = [line[len("defect: "):] for line in lines or [] if line.startswith("defect: ")]
        errors = [line for line in lines or [] if ": error: " in line]
        if summary is not None and summary.get("error"):
            row["status"], row["error"] = "failed", summary["error"]
        elif step == "check-mesh" and (defects or summary is not None):
            row["status"], row["fit_for_fem"] = "failed", "no"
            row["why"] = "; ".join(defects) or "see logs"
            row["error"] = "not fit for FEM: " + row["why"]
        elif errors or lines:
            row["status"], row["error"] = "failed", (errors or lines)[-1]
        elif lines is not None:
            row["status"] = "failed"
            row["error"] = f"{step} ended without a message (stopped from outside: a time or memory limit?)"
        else:
            row["status"] = "not run"
            row["error"] = f"{step} has not run (an earlier run stopped, or its turn has not come)"
        break
    # Figures only from steps of the finished part of the chain (files of an earlier run may lie further on).
    check = _read_json(folder / "check-mesh.json") if "check-mesh" in seconds else None
    if check is not None:
        row["fit_for_fem"] = "yes" if check.get("ok") else "no"
        row["tets"], row["nodes"] = check.get("tets", ""), check.get("nodes", "")
        row["min_dihedral_deg"] = round(float(check.get("min_dihedral_deg", 0)), 3)
        for tissue in (check.get("tissues") or {}).values():
            row[f"dice_{tissue.get('name')}"] = round(float(tissue.get("dice", 0)), 4)
    else:
        tetra = (_read_json(folder / "tetra.json") if "tetra" in seconds else None) or {}
        row["tets"], row["nodes"] = tetra.get("tets", ""), tetra.get("nodes", "")
    row["seconds_all_steps"] = round(sum(seconds.values()), 2)
    row["peak_memory_mb"] = round(peak, 1)
    for step, value in seconds.items():
        row[f"seconds_{step}"] = round(value, 2)
    return row


def _columns(rows):
    fixed = ["subject", "status", "failed_step", "error", "fit_for_fem", "why", "tets", "nodes", "min_dihedral_deg",
             "seconds_all_steps", "peak_memory_mb"]
    dice = sorted({key for row in rows for key in row if key.startswith("dice_")})
    steps = [f"seconds_{step}" for step in CHAIN if any(f"seconds_{step}" in row for row in rows)]
    return fixed + dice + steps


def _bar_chart(rows):
    """Seconds per step, one stacked bar per subject (SVG)."""
    steps = [step for step in CHAIN if any(f"seconds_{step}" in row for row in rows)]
    longest = max([row["seconds_all_steps"] for row in rows] + [1e-9])
    width, left, bar = 640, 150, 18
    height = 40 + bar * 1.5 * len(rows) + 20 * ((len(steps) + 3) // 4)
    parts = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{width + left + 60}" height="{height:.0f}" font-size="11">',
             f'<text x="{left}" y="14">seconds per step (longest subject: {longest:.1f} s)</text>']
    for i, row in enumerate(rows):
        y, x = 26 + i * bar * 1.5, left
        parts.append(f'<text x="{left - 6}" y="{y + bar * 0.75:.1f}" text-anchor="end">{html.escape(row["subject"])}</text>')
        for k, step in enumerate(steps):
            w = width * row.get(f"seconds_{step}", 0) / longest
            if w > 0:
                parts.append(f'<rect x="{x:.1f}" y="{y:.1f}" width="{w:.1f}" height="{bar}" fill="{COLOURS[k % len(COLOURS)]}">'
                             f'<title>{html.escape(row["subject"])} {step}: {row[f"seconds_{step}"]} s</title></rect>')
                x += w
        parts.append(f'<text x="{x + 4:.1f}" y="{y + bar * 0.75:.1f}">{row["seconds_all_steps"]} s</text>')
    legend_y = 36 + bar * 1.5 * len(rows)
    for k, step in enumerate(steps):
        x, y = left + (k % 4) * 160, legend_y + 20 * (k // 4)
        parts.append(f'<rect x="{x}" y="{y - 10}" width="10" height="10" fill="{COLOURS[k % len(COLOURS)]}"/>'
                     f'<text x="{x + 14}" y="{y}">{step}</text>')
    return "\n".join(parts + ["</svg>"])


def _dice_chart(rows):
    """Dice per tissue: one line per tissue, a dot per subject (SVG)."""
    tissues = sorted({key[len("dice_"):] for row in rows for key in row if key.startswith("dice_")})
    if not tissues:
        return "<p>No subject reached the mesh check yet: no Dice to show.</p>"
    low = min(min(row[f"dice_{t}"] for row in rows if f"dice_{t}" in row) for t in tissues)
    low = min(0.9, max(0.0, low - 0.02))
    width, left, line = 500, 150, 22
    scale = lambda value: left + width * (value - low) / (1 - low)
    parts = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{left + width + 40}" height="{60 + line * len(tissues)}" font-size="11">',
             f'<text x="{left}" y="14">Dice per tissue (mesh against voxels), one dot per subject</text>']
    for tick in (low, (low + 1) / 2, 1.0):
        parts.append(f'<line x1="{scale(tick):.1f}" y1="22" x2="{scale(tick):.1f}" y2="{30 + line * len(tissues)}" stroke="#ccc"/>'
                     f'<text x="{scale(tick):.1f}" y="{45 + line * len(tissues)}" text-anchor="middle">{tick:.2f}</text>')
    for i, tissue in enumerate(tissues):
        y = 36 + i * line
        parts.append(f'<text x="{left - 6}" y="{y + 4}" text-anchor="end">{html.escape(tissue)}</text>')
        for row in rows:
            if f"dice_{tissue}" in row:
                parts.append(f'<circle cx="{scale(row[f"dice_{tissue}"]):.1f}" cy="{y}" r="4" fill="#4e79a7" fill-opacity="0.7">'
                             f'<title>{html.escape(row["subject"])}: {row[f"dice_{tissue}"]}</title></circle>')
    return "\n".join(parts + ["</svg>"])


def _html(rows, columns):
    failed = [row for row in rows if row["status"] != "done"]
    counts = ", ".join(f"{sum(row['status'] == s for row in rows)} {s}" for s in ("done", "failed", "not run")
                       if any(row["status"] == s for row in rows))
    table = ["<table><tr>" + "".join(f"<th>{html.escape(c)}</th>" for c in columns) + "</tr>"]
    for row in rows:
        cls = "" if row["status"] == "done" else ' class="failed"'
        table.append(f"<tr{cls}>" + "".join(f"<td>{html.escape(str(row.get(c, '')))}</td>" for c in columns) + "</tr>")
    failures = "".join(f"<li><b>{html.escape(r['subject'])}</b> ({html.escape(r['status'])} at {html.escape(r['failed_step'])}): "
                       f"{html.escape(r['error'])}</li>" for r in failed)
    return f"""<!DOCTYPE html>
<html><head><meta charset="utf-8"><title>tissuemesh cohort</title><style>
body {{ font-family: sans-serif; margin: 1.5em; }} table {{ border-collapse: collapse; font-size: 12px; }}
td, th {{ border: 1px solid #ccc; padding: 2px 6px; text-align: left; }} tr.failed {{ background: #fde2e2; }}
</style></head><body>
<h1>tissuemesh cohort: {len(rows)} subjects</h1>
<p>{counts}. Per subject folder: report.html with its pictures.</p>
{"<h2>Subjects that did not finish</h2><ul>" + failures + "</ul>" if failed else ""}
<h2>Time per step</h2>
{_bar_chart(rows)}
<h2>Agreement with the voxels</h2>
{_dice_chart(rows)}
<h2>All figures (also in the CSV)</h2>
{"".join(table)}</table>
</body></html>
"""


def _write_atomically(path, text):
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    temporary = path.with_name(path.name + ".tmp")
    temporary.write_text(text, encoding="utf-8")
    os.replace(temporary, path)


def write_summary(root, chains, csv_path, html_path):
    """Summarises every subject of `chains` ({subject: its steps in order}); returns the two paths written."""
    rows = [summarise_subject(root, subject, chain) for subject, chain in sorted(chains.items())]
    columns = _columns(rows)
    text = io.StringIO(newline="")
    writer = csv.DictWriter(text, fieldnames=columns, extrasaction="ignore", lineterminator="\n")
    writer.writeheader()
    writer.writerows(rows)
    _write_atomically(csv_path, text.getvalue())
    _write_atomically(html_path, _html(rows, columns))
    return [Path(csv_path), Path(html_path)]


def _makefile_chains(root):
    """The subjects of a Makefile cohort (folders with params/) and the steps their parameters ask for."""
    chains = {}
    for params in sorted(Path(root).glob("*/params")):
        solve = (params / "solve.args").is_file() and (params / "solve.args").read_text().strip()
        stop = (params.parent / "remesh.json").exists() and not (params.parent / "tetra.json").exists() and \
            (params.parent / "report.json").exists()
        smooth = (params / "smooth.args").is_file() and (params / "smooth.args").read_text().split()[:1] != ["no"]
        chain = [s for s in CHAIN if (solve or s not in SOLVE_STEPS) and (smooth or s != "smooth")]
        if stop:
            chain = [s for s in ["prep", "extract", "smooth", "decimate", "remesh", "render-surface", "report"]
                     if smooth or s != "smooth"]
        chains[params.parent.name] = chain
    return chains


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("root", help="the cohort's output folder (the Makefile's COHORT_OUT)")
    parser.add_argument("--csv", help="CSV to write (default ROOT/cohort.csv)")
    parser.add_argument("--html", help="HTML page to write (default ROOT/cohort.html)")
    args = parser.parse_args()
    chains = _makefile_chains(args.root)
    if not chains:
        print(f"cohort_summary: {args.root}: no subject folders (with params/) found", file=sys.stderr)
        return 2
    paths = write_summary(args.root, chains, args.csv or Path(args.root) / "cohort.csv", args.html or Path(args.root) / "cohort.html")
    print(f"[cohort] {len(chains)} subjects: {paths[0]}, {paths[1]}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
