"""What the Snakefile needs besides its rules: the Makefile's parameters, the subjects, label tables, memory.

Kept out of the Snakefile so that it reads as the chain; plain Python 3 (Debian 12), no third-party module.
"""
import csv
import glob
import gzip
import json
import math
import os
import re
import shlex
import struct
import subprocess
from pathlib import Path

# The Makefile's variables that hold a step's flags, the rule that takes each, and the per-subject settings
# that are not flags. A variable the Makefile prints and no rule takes (or the reverse) means the two chains
# have drifted apart: the Snakefile refuses to run rather than run a different chain.
STEP_ARGS = {
    "PREP_ARGS": "prep", "EXTRACT_ARGS": "extract", "SMOOTH_ARGS": "smooth", "DECIMATE_ARGS": "decimate",
    "REMESH_ARGS": "remesh", "TETRA_ARGS": "tetra", "ASSESS_ARGS": "assess", "REFINE_ARGS": "refine",
    "CHECK_ARGS": "check-mesh", "SOLVE_ARGS": "solve", "RENDER_SURFACE_ARGS": "render-surface",
    "RENDER_SECTION_ARGS": "render-section", "RENDER_QUALITY_ARGS": "render-quality",
    "RENDER_CONVERGENCE_ARGS": "render-convergence", "RENDER_POTENTIAL_ARGS": "render-potential",
    "RENDER_FIELD_ARGS": "render-field",
}
SETTINGS = ("EXTRACT_METHOD", "SMOOTH", "TOOL_FLAGS", "STOP_AFTER", "REPORT_TITLE")
# Variables a config may set that only shape the flags above (the Makefile derives REMESH_ARGS and DECIMATE_ARGS
# from the remeshing target edge, REMESH_ARGS from the edges per layer thickness and the voxels' sides too,
# DECIMATE_ARGS from the distance bound and the contraction's cubes in voxels, EXTRACT_ARGS and ASSESS_ARGS from the priority, TETRA_ARGS and
# REFINE_ARGS from the improver's voxel sides).
DERIVING = ("REMESH_EDGE_MM", "EDGE_PER_THICKNESS", "PRIORITY", "DECIMATE_DISTANCE_VOXELS", "DECIMATE_CONTRACT_VOXELS",
            "REMESH_KEEP_VOXEL_SIDES", "IMPROVE_KEEP_VOXEL_SIDES")
# Environment variables that would change what make prints (make reads its variables from the environment).
_MAKE_ENVIRONMENT = re.compile(r"^(.*_ARGS|EXTRACT_METHOD|SMOOTH|REMESH_EDGE_MM|EDGE_PER_THICKNESS|DECIMATE_DISTANCE_VOXELS|DECIMATE_CONTRACT_VOXELS|REMESH_KEEP_VOXEL_SIDES|IMPROVE_KEEP_VOXEL_SIDES|PRIORITY|TOOL_FLAGS|STOP_AFTER|REPORT_TITLE|BIN|DATA|OUT|IMAGE|LABELS|PRESET|PHANTOM.*|"
                               r"COHORT.*|MAKEFLAGS|MFLAGS|MAKELEVEL|MAKEFILES|GNUMAKEFLAGS)$")


class CohortError(Exception):
    """A mistake in the cohort's configuration or inputs; the message says which and what to do."""


def check_value(name, value):
    if isinstance(value, (int, float)) and not isinstance(value, bool) and name in DERIVING:
        value = str(value)  # REMESH_EDGE_MM: 2
    if not isinstance(value, str):
        raise CohortError(f"{name}: give the flags as one string (got {value!r})")
    if "'" in value or "\n" in value:
        raise CohortError(f"{name}: {value!r}: parameters may not contain single quotes or line breaks (as in the Makefile)")
    return value


def make_params(makefile_dir, preset="", overrides=None):
    """Every step's flags and the per-subject settings as `make -C makefile_dir` would use them.

    Asks the Makefile itself (`make print-params`), with `preset` and `overrides` ({NAME: flags}) as command-line
    variables, so presets, defaults and derived values come from the one place they are written.
    Returns {"params": {NAME: value}, "bin": folder of the programs}.
    """
    unknown = sorted(set(overrides or {}) - set(STEP_ARGS) - set(SETTINGS) - set(DERIVING))
    if unknown:
        raise CohortError(f"params: {', '.join(unknown)} are no parameters of the Makefile (known: "
                          f"{', '.join(sorted(STEP_ARGS) + list(SETTINGS) + list(DERIVING))})")
    command = ["make", "-s", "--no-print-directory", "-C", str(makefile_dir), "print-params", "IMAGE="]
    if preset:
        command.append(f"PRESET={check_value('preset', preset)}")
    for name, value in sorted((overrides or {}).items()):
        command.append(f"{name}={check_value(name, value)}")
    environment = {k: v for k, v in os.environ.items() if not _MAKE_ENVIRONMENT.match(k)}
    done = subprocess.run(command, capture_output=True, text=True, env=environment)
    if done.returncode != 0:
        raise CohortError(f"{' '.join(map(shlex.quote, command))} failed: {done.stderr.strip()}")
    printed = dict(line.split("=", 1) for line in done.stdout.splitlines() if "=" in line)
    step_names = {name for name in printed if name.endswith("_ARGS")}
    if step_names != set(STEP_ARGS):
        behind = sorted(step_names - set(STEP_ARGS))
        gone = sorted(set(STEP_ARGS) - step_names)
        raise CohortError(
            f"{makefile_dir}/Makefile and the Snakefile disagree on the steps: "
            + (f"the Makefile has {', '.join(behind)}, which no rule here takes" if behind else "")
            + ("; " if behind and gone else "")
            + (f"the Makefile no longer has {', '.join(gone)}" if gone else "")
            + ". Bring data/workflows/snakemake (Snakefile, cohort.py) in step with the Makefile and run tests/cohort_cli.")
    if printed.get("SMOOTH", "") not in ("yes", "no"):
        raise CohortError(f"SMOOTH={printed.get('SMOOTH', '')}: yes (tm-smooth after tm-extract) or no (surface nets)")
    if printed.get("STOP_AFTER", "") not in ("", "remesh"):
        raise CohortError(f"STOP_AFTER={printed['STOP_AFTER']}: only \"remesh\" (or nothing, for the whole chain) is known")
    return {"params": {k: printed[k] for k in list(STEP_ARGS) + list(SETTINGS)}, "bin": printed["BIN"]}


def chain(params):
    """The steps of one subject, in order (each step's target is SUBJECT/<step>.json), as the Makefile runs them."""
    surfaces = ["prep", "extract"] + (["smooth"] if params["SMOOTH"] == "yes" else []) + ["decimate", "remesh"]
    if params["STOP_AFTER"] == "remesh":
        return surfaces + ["render-surface", "report"]
    steps = surfaces + ["tetra", "assess", "refine", "check-mesh"]
    if params["SOLVE_ARGS"].strip():
        steps.append("solve")
    steps += ["render-surface", "render-section", "render-quality", "render-convergence"]
    if params["SOLVE_ARGS"].strip():
        steps += ["render-potential", "render-field"]
    return steps + ["report"]


# ---- subjects ------------------------------------------------------------------------------------------------

def _labels_beside(image, bids_root):
    """A BIDS look-up table for `image`: IMAGE.tsv beside it (sub-01_dseg.nii.gz -> sub-01_dseg.tsv), else
    dseg.tsv at the root of the tree (BIDS inheritance), else nothing."""
    name = image.name[:-len(".nii.gz")] if image.name.endswith(".nii.gz") else image.stem
    for candidate in (image.with_name(name + ".tsv"), bids_root / "dseg.tsv" if bids_root else None):
        if candidate and candidate.is_file():
            return candidate
    return None


def _bids_subjects(root, pattern):
    subjects = {}
    for anat in sorted(glob.glob(str(root / "sub-*" / "anat")) + glob.glob(str(root / "sub-*" / "ses-*" / "anat"))):
        anat = Path(anat)
        images = sorted(Path(p) for p in glob.glob(str(anat / pattern)))
        if not images:
            continue
        key = "/".join(anat.relative_to(root).parts[:-1])  # sub-01 or sub-01/ses-1
        if len(images) > 1:
            raise CohortError(f"{anat}: {len(images)} files match '{pattern}' ({', '.join(p.name for p in images)}); "
                              f"narrow the pattern with the config key dseg, e.g. dseg: '*_desc-tissues_dseg.nii.gz'")
        subjects[key] = {"image": images[0], "labels": _labels_beside(images[0], root), "params": {}}
    if not subjects:
        raise CohortError(f"{root}: no sub-*/anat/{pattern} nor sub-*/ses-*/anat/{pattern}; is this the BIDS root?")
    return subjects


def _table_subjects(table):
    """A tab-separated table: participant_id (sub-<label>), image, and optionally session_id, labels and any of
    the Makefile's XXX_ARGS (that subject's flags: electrode positions, say). Relative paths: from the table."""
    with open(table, newline="", encoding="utf-8-sig") as handle:
        rows = list(csv.DictReader(handle, delimiter="\t"))
    if not rows or not {"participant_id", "image"} <= set(rows[0]):
        raise CohortError(f"{table}: a tab-separated table with the columns participant_id and image is needed "
                          f"(optional: session_id, labels, and XXX_ARGS columns)")
    unknown = sorted(set(rows[0]) - {"participant_id", "session_id", "image", "labels"} - set(STEP_ARGS))
    if unknown:
        raise CohortError(f"{table}: unknown columns {', '.join(unknown)}")
    subjects = {}
    for line, row in enumerate(rows, start=2):
        subject, session = row["participant_id"].strip(), (row.get("session_id") or "").strip()
        if not re.fullmatch(r"sub-[A-Za-z0-9]+", subject) or (session and not re.fullmatch(r"ses-[A-Za-z0-9]+", session)):
            raise CohortError(f"{table}:{line}: participant_id must be sub-<letters and digits> and session_id "
                              f"ses-<letters and digits> (got '{subject}', '{session}')")
        key = f"{subject}/{session}" if session else subject
        if key in subjects:
            raise CohortError(f"{table}:{line}: {key} is listed twice")
        resolve = lambda text: (Path(table).parent / text).resolve() if text else None
        image = resolve(row["image"].strip())
        if image is None:
            raise CohortError(f"{table}:{line}: no image for {key}")
        params = {k: check_value(f"{table}:{line}: {k}", v) for k, v in row.items() if k in STEP_ARGS and v is not None and v != ""}
        subjects[key] = {"image": image, "labels": resolve((row.get("labels") or "").strip()), "params": params}
    return subjects


def discover_subjects(config):
    """{subject key: {"image", "labels" (a .json or BIDS .tsv, or None), "params" (that subject's flags)}}."""
    bids, table = config.get("bids") or "", config.get("subjects") or ""
    if bool(bids) == bool(table):
        raise CohortError("give either bids (the root of a BIDS tree) or subjects (a table), e.g. "
                          "snakemake --config bids=/abs/bids, or subjects=/abs/subjects.tsv")
    subjects = _bids_subjects(Path(bids).resolve(), config.get("dseg") or "*_dseg.nii.gz") if bids else \
        _table_subjects(Path(table).resolve())
    default_labels = Path(config["labels"]).resolve() if config.get("labels") else None
    for subject in subjects.values():
        subject["labels"] = subject["labels"] or default_labels
        if subject["labels"] and subject["labels"].suffix not in (".json", ".tsv"):
            raise CohortError(f"{subject['labels']}: label names are read from a JSON {{\"1\": \"scalp\"}} or a BIDS dseg.tsv")
    return subjects


def labels_json_from_tsv(tsv, json_path):
    """Writes a BIDS look-up table (columns index and name) as the JSON {"index": "name"} the programs read."""
    with open(tsv, newline="", encoding="utf-8-sig") as handle:
        rows = list(csv.DictReader(handle, delimiter="\t"))
    if not rows or not {"index", "name"} <= set(rows[0]):
        raise CohortError(f"{tsv}: a BIDS dseg.tsv needs the columns index and name")
    names = {}
    for line, row in enumerate(rows, start=2):
        if not re.fullmatch(r"\d+", row["index"].strip()):
            raise CohortError(f"{tsv}:{line}: index '{row['index']}' is not a label number")
        names[str(int(row["index"]))] = row["name"].strip()
    temporary = Path(str(json_path) + ".tmp")
    temporary.write_text(json.dumps(names, indent=1) + "\n")
    os.replace(temporary, json_path)


def write_description(description_path, ignore_path, tm_prep, source):
    """The BIDS-derivatives dataset_description.json (with the programs' version) and a .bidsignore for the rest."""
    version = subprocess.run([tm_prep, "--version"], capture_output=True, text=True).stdout.split()[-1:]
    description = {"Name": "tissuemesh tetrahedral models", "BIDSVersion": "1.8.0", "DatasetType": "derivative",
                   "GeneratedBy": [{"Name": "tissuemesh", "Version": "".join(version),
                                    "Description": "data/workflows/snakemake: the chain of data/workflows/Makefile"}],
                   "SourceDatasets": [{"URL": Path(source).resolve().as_uri()}]}
    Path(description_path).write_text(json.dumps(description, indent=2) + "\n")
    Path(ignore_path).write_text("# tissuemesh's own file names inside each subject folder, its logs and the summary\n"
                                 "sub-*/**\nlogs/\nsummary/\nlabels/\n")


# ---- resources -------------------------------------------------------------------------------------------------

def nifti_voxels(path):
    """Voxel count and bytes per voxel from a NIfTI-1 header (.nii or .nii.gz), or None for other formats."""
    name = str(path)
    if not (name.endswith(".nii") or name.endswith(".nii.gz")):
        return None
    try:
        with (gzip.open if name.endswith(".gz") else open)(name, "rb") as handle:
            header = handle.read(348)
        for order in "<>":
            if len(header) == 348 and struct.unpack(order + "i", header[:4])[0] == 348:
                dims = struct.unpack(order + "8h", header[40:56])
                bits = struct.unpack(order + "h", header[72:74])[0]
                return math.prod(max(1, d) for d in dims[1:1 + max(1, min(dims[0], 7))]), max(1, bits // 8)
    except (OSError, EOFError, struct.error):
        pass  # a broken image: tm-prep says what is wrong with it
    return None


# MiB per unit of the count that drives each step's peak, and MiB for the program: the tools' own estimates where
# they make one (docs/robustness.md: tm-tetra 1.9 kB per triangle and 3.4 tets of 165 B each, tm-solve 3 kB
# per node), else the --json peak_memory_mb of the usc19-5 head at 4 and 6 mm and spheres4 at 4 mm (2026-12-04),
# divided by the count and rounded up: smooth 0.25-0.41 kB per triangle, decimate 0.22-0.24, remesh 0.41 per
# triangle in, assess 0.29-0.45 kB per tet, refine 1.06-1.09, check-mesh 0.26-0.36, pictures 0.15 kB per tet.
MEMORY = {
    # step: (json of the step before, key of the count, MiB per unit, MiB for the program)
    "extract": ("prep.json", "dims", 6e-6, 30),  # voxels of the clean image (the .ply is streamed)
    "smooth": ("extract.json", "triangles", 4.5e-4, 20),
    "decimate": ("smooth.json", "triangles", 2.5e-4, 20),  # or extract.json without a smoothing step
    "remesh": ("decimate.json", "triangles_after", 5e-4, 20),
    "tetra": ("remesh.json", "triangles_after", 2.5e-3, 20),
    "assess": ("tetra.json", "tets", 4.5e-4, 20),
    "refine": ("tetra.json", "tets", 1.1e-3, 20),
    "check-mesh": ("refine.json", "tets", 4e-4, 20),
    "solve": ("refine.json", "nodes", 3e-3, 20),
    "render": ("refine.json", "tets", 2e-4, 30),
}


def _count(json_path, key):
    """A count from a step's --json summary (a list of dimensions counts as their product), or None."""
    try:
        value = json.loads(Path(json_path).read_text())[key]
        return float(math.prod(value)) if isinstance(value, list) else float(value)
    except (OSError, ValueError, KeyError, TypeError):
        return None


def memory_mb(step, folder, image=None, floor_mb=256):
    """The memory to ask the scheduler for (MiB): the step's estimated peak and a quarter more, at least floor_mb."""
    if step == "prep":
        size = nifti_voxels(image) if image else None
        # tm-prep's own estimate: the file's bytes per voxel + 14 B to read, 12 B per voxel where clean-ups run
        estimate = size[0] * (size[1] + 26) / 2**20 + 20 if size else None
    elif step in MEMORY:
        source, key, per_unit, program = MEMORY[step]
        count = _count(Path(folder) / source, key)
        if count is None and step == "decimate":  # no smoothing step: decimation reads tm-extract's surfaces
            count = _count(Path(folder) / "extract.json", key)
        estimate = count * per_unit + program if count is not None else None
    else:
        estimate = None
    return max(floor_mb, math.ceil(1.25 * estimate)) if estimate else floor_mb
