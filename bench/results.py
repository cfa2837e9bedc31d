#!/usr/bin/python3
"""bench/RESULTS.md from the records bench/run collects (one JSON object per line): timed steps (wall, CPU,
peak RSS from /usr/bin/time) and measures (--json summaries of the meshers, tm-check-mesh, interface distance)."""
import argparse
import datetime
import json
import statistics
from collections import defaultdict

INPUTS = {"extraction": "spheres4 4 mm, 0.11 M voxels", "smoothing": "its interfaces",
          "decimation": "the smoothed interfaces", "tetrahedralization": "the smoothed interfaces (tm-tetra defaults)",
          "assessment": "that mesh against the image", "solve": "that mesh, tDCS, AMG-CG"}
MESHERS = {"ours": "ours", "ours-refined": "ours, refined", "cgal": "CGAL (count-matched)",
           "cgal-acc": "CGAL (accuracy-matched)"}


def load(path):
    steps = defaultdict(lambda: defaultdict(list))  # (case, mesher) -> step -> [(wall, cpu, rss_mb)]
    measures = defaultdict(dict)                     # (case, mesher) -> kind -> data
    for line in open(path):
        r = json.loads(line)
        if "step" in r:
            step = r["step"].split("#")[0]
            steps[(r["case"], r["mesher"])][step].append((r["wall_s"], r["cpu_s"], r["rss_kb"] / 1024))
        else:
            measures[(r["case"], r["mesher"])][r["kind"]] = r["data"]
    return steps, measures


def totals(step_runs):
    """Median over repeats of the summed wall and CPU time; peak RSS is the largest of any step."""
    repeats = min(len(v) for v in step_runs.values())
    wall = statistics.median(sum(v[i][0] for v in step_runs.values()) for i in range(repeats))
    cpu = statistics.median(sum(v[i][1] for v in step_runs.values()) for i in range(repeats))
    return wall, cpu, max(x[2] for v in step_runs.values() for x in v)


def figures(case, mesher, steps, measures):
    m = measures.get((case, mesher), {})
    if "check" not in m:
        return None
    check = m["check"]
    # The refined mesh's time is ours and tm-refine's.
    timed = dict(steps[(case, mesher)])
    if mesher == "ours-refined":
        timed.update(steps[(case, "ours")])
    wall, cpu, rss = totals(timed)
    # Our summaries carry the improver's figures (the 1st percentile of the tets' smallest dihedral angle).
    after = m.get("mesh", {}).get("improvement", {}).get("after", {})
    tissues = {k: t for k, t in check["tissues"].items() if k != "0" and t["voxel_volume_mm3"] > 0}
    errors = [abs(t["volume_mm3"] / t["voxel_volume_mm3"] - 1) * 100 for t in tissues.values()]
    d = m.get("distance")
    e = m.get("eeg")
    return {"wall": wall, "cpu": cpu, "rss": rss, "tets": check["tets"], "nodes": check["nodes"],
            "dihedral": check["min_dihedral_deg"], "radius_edge": check["max_radius_edge_ratio"],
            "p1": f"{after['p1_min_dihedral_deg']:.1f}" if "p1_min_dihedral_deg" in after else "-",
            "volume_error": max(errors) if errors else float("nan"),
            "dice": min(t["dice"] for t in tissues.values()) if tissues else float("nan"),
            "pieces": "/".join(str(t["components"]) for t in tissues.values()),
            "fit": "yes" if check["ok"] else "no",
            "distance": f"{d['mean_mm']:.3f} / {d['p95_mm']:.3f} / {d['max_mm']:.2f}" if d else "-",
            "mean_distance": d["mean_mm"] if d else None,
            "eeg": f"{e['worst_rdm']:.4f} / {e['worst_mag_error']:.4f}" if e else "-",
            "rdm": e["worst_rdm"] if e else None}


def main_table(cases, steps, measures):
    print("| case | mesher | wall s | CPU s | peak MiB | tets | nodes | min dihedral | 1st pct dihedral | max radius-edge | "
          "worst volume error % | worst Dice | pieces per tissue | FEM-fit | interface distance mm (mean / p95 / max) | "
          "EEG worst RDM / abs(MAG - 1) |")
    print("|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|---|---|---|")
    for case in cases:
        for mesher, title in MESHERS.items():
            f = figures(case, mesher, steps, measures)
            if f:
                print(f"| {case} | {title} | {f['wall']:.1f} | {f['cpu']:.1f} | {f['rss']:.0f} | {f['tets']} | {f['nodes']} | "
                      f"{f['dihedral']:.1f} | {f['p1']} | {f['radius_edge']:.1f} | {f['volume_error']:.2f} | {f['dice']:.4f} | "
                      f"{f['pieces']} | {f['fit']} | {f['distance']} | {f['eeg']} |")


def ratio_table(cases, steps, measures):
    print("| case | wall | CPU | peak memory | tets | mean interface distance | EEG worst RDM | "
          "wall vs accuracy-matched CGAL | tets vs accuracy-matched CGAL |")
    print("|---|---:|---:|---:|---:|---:|---:|---:|---:|")
    for case in cases:
        o, c, a = (figures(case, m, steps, measures) for m in ("ours", "cgal", "cgal-acc"))
        if not (o and c):
            continue
        dist = f"{o['mean_distance'] / c['mean_distance']:.2f}" if o["mean_distance"] and c["mean_distance"] else "-"
        rdm = f"{o['rdm'] / c['rdm']:.2f}" if o["rdm"] and c["rdm"] else "-"
        acc_wall = f"{o['wall'] / a['wall']:.2f}" if a else "-"
        acc_tets = f"{o['tets'] / a['tets']:.2f}" if a else "-"
        print(f"| {case} | {o['wall'] / c['wall']:.2f} | {o['cpu'] / c['cpu']:.2f} | {o['rss'] / c['rss']:.2f} | "
              f"{o['tets'] / c['tets']:.2f} | {dist} | {rdm} | {acc_wall} | {acc_tets} |")


def stage_table(cases, steps):
    print("| case | step | wall s | CPU s | peak MiB |")
    print("|---|---|---:|---:|---:|")
    for case in cases:
        for mesher in ("both", "ours", "ours-refined", "cgal"):
            for step, runs in steps.get((case, mesher), {}).items():
                print(f"| {case} | {step} | {statistics.median(r[0] for r in runs):.2f} | "
                      f"{statistics.median(r[1] for r in runs):.2f} | {max(r[2] for r in runs):.0f} |")


def cgal_commands(cases, measures):
    """The CGAL command lines the searches chose (the clean image comes from tm-prep as in the stage table)."""
    for case in cases:
        for mesher in ("cgal", "cgal-acc"):
            m = measures.get((case, mesher), {}).get("mesh")
            if m:
                print(f"    {case} ({MESHERS[mesher]}): tm-bench-cgal-mesh3 -i clean.nii.gz -o cgal.msh --facet-size-mm "
                      f"{m['facet_size_mm']} --cell-size-mm {m['cell_size_mm']} --facet-distance-mm {m['facet_distance_mm']} "
                      f"--radius-edge {m['radius_edge']} --threads {m['threads']}")


def closing_note(cases, steps, measures):
    """Where we lose to count-matched CGAL, and the step that costs us most there."""
    for case in cases:
        o, c = figures(case, "ours", steps, measures), figures(case, "cgal", steps, measures)
        if not (o and c):
            continue
        ours = steps[(case, "ours")]
        worst = max(ours, key=lambda s: statistics.median(r[1] for r in ours[s]))
        share = statistics.median(r[1] for r in ours[worst]) / o["cpu"] * 100 if o["cpu"] > 0 else 0
        losses = [what for what, lost in (("CPU time", o["cpu"] > c["cpu"]), ("peak memory", o["rss"] > c["rss"]),
                                          ("min dihedral", o["dihedral"] < c["dihedral"]),
                                          ("interface distance", (o["mean_distance"] or 0) > (c["mean_distance"] or 0)),
                                          ("EEG RDM", (o["rdm"] or 0) > (c["rdm"] or 0)),
                                          ("worst Dice", o["dice"] < c["dice"])) if lost]
        print(f"- {case}: we lose on {', '.join(losses) if losses else 'nothing measured here'}; "
              f"our costliest step is {worst} ({share:.0f}% of our CPU time).")


def micro_table(path):
    try:
        benchmarks = json.load(open(path))["benchmarks"]
    except (OSError, ValueError, KeyError):
        print(f"(not measured: tm-bench-stages wrote no complete {path}; see its output next to it)")
        return
    print("Rates per CPU second of the benchmark thread (Google Benchmark's default), steadier than wall time on a "
          "shared machine; wall ms shown for reference.\n")
    print("| stage | input | CPU ms per run | wall ms per run | throughput |")
    print("|---|---|---:|---:|---:|")
    for b in benchmarks:
        rates = [f"{v / 1e6:.3g} M {k}" if v >= 1e5 else f"{v:.3g} {k}" for k, v in b.items() if k.endswith("/s")]
        print(f"| {b['name'].split('/')[0]} | {INPUTS.get(b['name'].split('/')[0], '')} | {b['cpu_time']:.1f} | "
              f"{b['real_time']:.1f} | {', '.join(rates)} |")


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("records")
    parser.add_argument("--micro")
    parser.add_argument("--elapsed", type=int)
    parser.add_argument("--repeats", type=int)
    parser.add_argument("--cases")
    parser.add_argument("--load")
    parser.add_argument("--jobs", type=int, default=1)
    a = parser.parse_args()
    cases = a.cases.split()
    steps, measures = load(a.records)
    print("# Benchmarks: tissuemesh against CGAL Mesh_3\n")
    print(f"Measured by `bench/run` on {datetime.date.today().isoformat()}, 2 cores (whatever else ran "
          f"shows in the load average at the end: {a.load}); {a.repeats} repeat(s) of every timed run (medians), "
          f"{a.elapsed} s in all, {a.jobs} case(s) at a time. Times are wall and CPU (user + system) seconds from `/usr/bin/time`; on a loaded "
          "machine CPU seconds are the steadier figure.\n")
    print("## Side by side\n")
    print("Ours: surface nets -> decimate -> remesh (edges by layer thickness) -> tm-tetra, the default chain of "
          "`data/workflows/Makefile`; \"ours, refined\": then tm-refine (3 iterations, as the workflow), its times "
          "those of the chain and tm-refine together; the comparison pairs ours (not refined) with CGAL. The 1st "
          "percentile is that of the tets' smallest dihedral angle, from our programs' summaries. "
          "CGAL: `tm-bench-cgal-mesh3`, Mesh_3 with 2 TBB threads and perturb only. Both from the same `tm-prep` "
          "clean image and judged by the same `tm-check-mesh --image` and `tm-bench-interface-distance`. "
          "Volume error and Dice against the voxels, worst tissue; interface distance to the exact phantom surfaces "
          "(area-weighted over face centroids; max over centroids and vertices). EEG (spheres4 only, `tm-bench-eeg`): "
          "radial and tangential dipoles at eccentricities 0.5 and 0.9 of the brain, subtraction approach, against the "
          "4-shell series on the mesh's outer surface nodes; RDM on the 0..2 scale, average reference; worst of the four.\n")
    main_table(cases, steps, measures)
    print("\n## Ratios ours / CGAL (pair by pair, same run)\n")
    print("Below 1: we are faster, smaller or closer. Count-matched pairs unless said otherwise.\n")
    ratio_table(cases, steps, measures)
    print("\n## Stages\n")
    stage_table(cases, steps)
    print("\n## Where we lose\n")
    closing_note(cases, steps, measures)
    if a.micro:
        print("\n## Stage micro-benchmarks (`tm-bench-stages`, Google Benchmark)\n")
        micro_table(a.micro)
    print("\n## Reproduce\n")
    print("```\nTM_BUILD_DIR=build scripts/build -DTM_BENCH=ON     # tm-bench-cgal-mesh3, tm-bench-interface-distance, tm-bench-eeg, tm-bench-stages")
    print(f"bench/run --skip-build --repeats {a.repeats} --jobs {a.jobs} --cases \"{a.cases}\"{' --micro' if a.micro else ''}")
    print("```\n\nThe CGAL runs the searches settled on:\n")
    cgal_commands(cases, measures)
    print("\nEvery command bench/run ran (and the sizes its search chose) is in the `[bench]` lines it prints; "
          "`bench/run --out DIR` keeps every mesh, summary and record.")


main()
