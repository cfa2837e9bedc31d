"""The Python package as a user calls it: the README's example runs, each step returns numpy arrays that mean what
they say (volumes, labels, potentials), files round-trip, and library errors arrive as Python exceptions with the
library's one-line message. Quick: one 6 mm sphere head for the whole module."""

import math
import pathlib
import re

import numpy as np
import pytest

import tissuemesh as tm

ROOT = pathlib.Path(__file__).resolve().parents[2]


@pytest.fixture(scope="module")
def head():
    labels, affine, names = tm.phantom("spheres4", voxel_mm=6)
    surface = tm.extract_interfaces(labels, affine, names, priority={3: 1})
    mesh = tm.tetrahedralize(surface, max_volume_mm3=200)
    return labels, affine, names, surface, mesh


def test_readme_example_runs_as_written(capsys):
    readme = (ROOT / "README.md").read_text()
    section = readme[readme.index("## Python"):]
    script = re.search(r"```python\n(.*?)```", section, re.S).group(1)
    assert len(script.strip().splitlines()) <= 12
    exec(compile(script, "README.md", "exec"), {})
    out = capsys.readouterr().out
    tets = int(re.search(r"(\d+) tets", out).group(1))
    low, high = map(float, re.search(r"potential (\S+) \.\. (\S+) V", out).groups())
    assert tets > 1000
    assert low < -0.01 and high > 0.01, "1 mA through the head: tenths of a volt either way"


def test_steps_return_arrays_that_mean_what_they_say(head):
    labels, affine, names, surface, mesh = head
    assert labels.ndim == 3 and labels.shape[0] == labels.shape[1] == labels.shape[2]
    assert labels.dtype == np.uint16 and affine.shape == (4, 4)
    assert np.allclose(np.linalg.norm(affine[:3, :3], axis=0), 6.0), "6 mm voxels"
    assert names == {0: "background", 1: "scalp", 2: "skull", 3: "csf", 4: "brain"}
    assert set(np.unique(labels)) == {0, 1, 2, 3, 4}
    assert surface["vertices"].shape[1] == 3 and surface["triangles"].shape == (len(surface["sides"]), 3)
    tets, vertices = mesh["tets"], mesh["vertices"]
    assert tets.shape[1] == 4 and len(mesh["tet_labels"]) == len(tets)
    p = vertices[tets]
    volumes = np.einsum("ij,ij->i", p[:, 1] - p[:, 0], np.cross(p[:, 2] - p[:, 0], p[:, 3] - p[:, 0])) / 6
    assert (volumes > 0).all(), "positively oriented tets"
    # The whole head is a ball of radius 92 mm: the voxel surface bounds it within a voxel or so.
    total = volumes.sum()
    assert abs(total - 4 / 3 * math.pi * 92 ** 3) / total < 0.08
    report = tm.assess(mesh, labels, affine)
    assert len(report["majority"]) == len(tets)
    assert report["tissues"][4]["dice"] > 0.9, "the brain matches its voxels"


def test_solve_gives_an_antisymmetric_potential(head):
    *_, mesh = head
    phi = tm.solve(mesh, electrodes=[((-92, 0, 0), 20, 1e-3), ((92, 0, 0), 20, -1e-3)])
    assert phi.shape == (len(mesh["vertices"]),)
    x = mesh["vertices"][:, 0]
    assert phi[x < -80].mean() > 0.01 > -0.01 > phi[x > 80].mean()
    assert abs(phi.mean()) < 1e-9, "zero-mean reference"


def test_files_round_trip(head, tmp_path):
    labels, affine, names, surface, mesh = head
    tm.write_mesh(mesh, tmp_path / "head.msh", binary=True)
    back = tm.read_mesh(tmp_path / "head.msh")
    assert np.array_equal(back["tet_labels"], mesh["tet_labels"])
    assert back["names"] == {1: "scalp", 2: "skull", 3: "csf", 4: "brain"}, "$PhysicalNames: the tissues with tets"
    tm.write_surface(surface, tmp_path / "s.ply", ascii=True)
    assert np.array_equal(tm.read_surface(tmp_path / "s.ply")["sides"], surface["sides"])
    tm.write_label_image(tmp_path / "l.nii.gz", labels, affine, names)
    labels2, affine2, _ = tm.read_label_image(tmp_path / "l.nii.gz")
    assert np.array_equal(labels2, labels) and np.allclose(affine2, affine, atol=1e-5)


def test_errors_are_python_exceptions_with_the_library_message(head, tmp_path):
    labels, affine, names, surface, mesh = head
    with pytest.raises(tm.IoError, match="missing.nii.gz"):
        tm.read_label_image(tmp_path / "missing.nii.gz")
    assert issubclass(tm.IoError, OSError) and issubclass(tm.InputError, ValueError)
    with pytest.raises(tm.InputError, match="integer array"):
        tm.extract_interfaces(labels.astype(float), affine)
    sheared = affine.copy()
    sheared[0, 1] = 1.0
    with pytest.raises(tm.InputError, match="orthonormal"):
        tm.extract_interfaces(labels, sheared)
    with pytest.raises(tm.InputError, match="no SimNIBS tag"):  # "brain": SimNIBS has grey and white matter
        tm.write_mesh(mesh, tmp_path / "simnibs.msh", tissue_numbering="simnibs")
    assert not (tmp_path / "simnibs.msh").exists()
    broken = dict(mesh, tets=mesh["tets"] + len(mesh["vertices"]))
    with pytest.raises(tm.InputError, match="mesh tets"):
        tm.assess(broken, labels, affine)
