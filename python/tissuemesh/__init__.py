"""tissuemesh: a tissue-labelled voxel image to a boundary-conforming tetrahedral finite-element model.

numpy in, numpy out, one function per step:

    labels, affine, names = tissuemesh.read_label_image("seg.nii.gz", labels="names.json")   # or phantom("spheres4")
    surface = tissuemesh.extract_interfaces(labels, affine, names, priority={3: 1})            # interface complex
    mesh = tissuemesh.tetrahedralize(surface, max_volume_mm3=30)                               # labelled tets
    report = tissuemesh.assess(mesh, labels, affine)                                           # against the voxels
    phi = tissuemesh.solve(mesh, electrodes=[((-86.5, 0, 31.5), 10, 1e-3), ((86.5, 0, 31.5), 10, -1e-3)])

Images are arrays indexed [i, j, k] with a 4x4 voxel-to-world affine (RAS mm), as nibabel gives them. Surfaces and
meshes are dicts of arrays (see each function's help). Lengths in mm, currents in A, conductivities in S/m, potentials
in V. Errors: InputError (a ValueError: the data or options are wrong), IoError (an OSError: a file cannot be read or
written), AlgorithmError (a RuntimeError: valid input the method could not finish), with the library's one-line
message naming the problem and the fix.
"""

from ._tissuemesh import (
    AlgorithmError,
    InputError,
    IoError,
    assess,
    extract_interfaces,
    phantom,
    read_label_image,
    read_mesh,
    read_surface,
    solve,
    tetrahedralize,
    write_label_image,
    write_mesh,
    write_surface,
)

__all__ = [
    "AlgorithmError",
    "InputError",
    "IoError",
    "assess",
    "extract_interfaces",
    "phantom",
    "read_label_image",
    "read_mesh",
    "read_surface",
    "solve",
    "tetrahedralize",
    "write_label_image",
    "write_mesh",
    "write_surface",
]
