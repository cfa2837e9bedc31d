#!/usr/bin/env python3
"""tm-leadfield's EEG lead field as an MNE-Python forward solution, and a dipole localised with it.

Compute the lead field on a grid of sources in the brain, then run this with Debian's Python (python3-mne):

    tm-leadfield -i head.msh --sensors cap.csv --source-grid-mm 5 --source-tissues brain \\
        --source-min-distance-mm 5 -o eeg.npy
    /usr/bin/python3 python/examples/mne_forward.py eeg.npy --dipole 21.5,-9,46.5,3e-8,0,4e-8 --dipole ...

make_forward(npy) reads eeg.npy and its sidecar eeg.json and returns an mne.Forward with free source
orientations and the channel info it belongs to: anything in MNE that takes a forward solution (minimum norm,
dSPM, sLORETA, beamformers, simulation) then uses our FE lead field. Coordinates: the mesh's RAS millimetres,
divided by 1000, are MNE's head frame (no MRI transform); units are MNE's (V per A*m). MNE builds forwards
itself, so the wrapper lets MNE lay out a forward for the same channels and sources with a sphere model and
puts our matrix in its place.

The example run simulates the EEG of each dipole with MNE's own 4-shell sphere model (the spheres4 phantom's
radii and conductivities; the data owe nothing to our FEM), adds white noise, computes eLORETA with our lead
field and prints, as JSON, the peak and its distance from the dipole, and how our lead field at the peak
compares with MNE's sphere model there.
"""
import argparse
import json
import pathlib
import sys
import warnings

import mne
import numpy as np

# The spheres4 phantom (tm-phantom spheres4): brain, CSF, skull, scalp to these radii (mm), conductivities S/m.
SPHERES4_RADII_MM = (78.0, 80.0, 86.0, 92.0)
SPHERES4_SIGMAS = (0.33, 1.79, 0.01, 0.43)


def read_lead_field(npy):
    """The matrix (channels x 3 sources, V per A*m) and its sidecar."""
    npy = pathlib.Path(npy)
    matrix = np.load(npy)
    sidecar = json.loads(npy.with_suffix(".json").read_text())
    if sidecar.get("kind") != "eeg":
        raise ValueError(f"{npy}: not an EEG lead field of tm-leadfield (kind {sidecar.get('kind')!r})")
    if any(source["orientation"] is not None for source in sidecar["sources"]):
        raise ValueError(f"{npy}: sources with fixed orientations; this example takes free ones (three columns each)")
    return matrix, sidecar


def sphere_model(radii_mm=SPHERES4_RADII_MM, sigmas=SPHERES4_SIGMAS):
    return mne.make_sphere_model(r0=(0.0, 0.0, 0.0), head_radius=radii_mm[-1] / 1000,
                                 relative_radii=[r / radii_mm[-1] for r in radii_mm], sigmas=sigmas, verbose=False)


def channel_info(sidecar):
    """EEG channels at the electrodes' positions on the scalp (the projections tm-leadfield used)."""
    names = [sensor["name"] for sensor in sidecar["sensors"]]
    positions = np.array([sensor["projected_mm"] for sensor in sidecar["sensors"]]) / 1000
    info = mne.create_info(names, sfreq=1000.0, ch_types="eeg")
    info.set_montage(mne.channels.make_dig_montage(ch_pos=dict(zip(names, positions)), coord_frame="head"))
    return info


def discrete_sources(positions_mm):
    rr = np.asarray(positions_mm, dtype=float).reshape(-1, 3) / 1000
    nn = np.tile([0.0, 0.0, 1.0], (len(rr), 1))
    return mne.setup_volume_source_space(pos=dict(rr=rr, nn=nn), verbose=False)


def make_forward(npy, sphere=None):
    """Our EEG lead field as an mne.Forward (free orientations, head frame) and its mne.Info."""
    matrix, sidecar = read_lead_field(npy)
    info = channel_info(sidecar)
    src = discrete_sources([source["position_mm"] for source in sidecar["sources"]])
    with warnings.catch_warnings():  # MNE's sphere series divides by zero for a source at the centre: not our values
        warnings.simplefilter("ignore", RuntimeWarning)
        forward = mne.make_forward_solution(info, trans=None, src=src, bem=sphere or sphere_model(), meg=False, eeg=True,
                                            verbose=False)
    if forward["sol"]["data"].shape != matrix.shape or forward["nsource"] != len(sidecar["sources"]):
        raise ValueError(f"{npy}: MNE laid out {forward['sol']['data'].shape} for {forward['nsource']} sources, the lead "
                         f"field is {matrix.shape}; MNE dropped sources outside its sphere model")
    forward["sol"]["data"] = matrix.copy()
    forward["_orig_sol"] = matrix.copy()
    return forward, info


def simulate(info, position_mm, moment_am):
    """The EEG (V) of a dipole by MNE's own 4-shell sphere model, average referenced, and the 3 columns there."""
    with warnings.catch_warnings():  # MNE's sphere series divides by zero at the centre
        warnings.simplefilter("ignore", RuntimeWarning)
        forward = mne.make_forward_solution(info, trans=None, src=discrete_sources([position_mm]), bem=sphere_model(),
                                            meg=False, eeg=True, verbose=False)
    data = forward["sol"]["data"] @ np.asarray(moment_am, dtype=float)
    return data - data.mean(), forward["sol"]["data"]


def localise(npy, dipoles, noise=0.02, lambda2=1e-2, seed=29):
    """eLORETA with our lead field on the EEG of each dipole ((x, y, z, px, py, pz), mm and A*m) simulated with MNE's
    sphere model plus white noise (`noise` of the data's RMS). eLORETA, because it localises a single source
    exactly in the noise-free case (Pascual-Marqui 2007); MNE's sLORETA with free orientations did not, even on
    data made with the very same lead field."""
    forward, info = make_forward(npy)
    source_space = forward["src"][0]
    positions_mm = source_space["rr"][source_space["vertno"]] * 1000
    random = np.random.default_rng(seed)
    results = []
    for dipole in dipoles:
        position_mm, moment_am = np.asarray(dipole[:3], dtype=float), np.asarray(dipole[3:], dtype=float)
        data, _ = simulate(info, position_mm, moment_am)
        sigma = noise * np.sqrt(np.mean(data ** 2))
        evoked = mne.EvokedArray((data + random.normal(0.0, sigma, data.shape))[:, np.newaxis], info, tmin=0.0, verbose=False)
        evoked.set_eeg_reference("average", projection=True, verbose=False)
        covariance = mne.make_ad_hoc_cov(info, std=dict(eeg=sigma), verbose=False)
        inverse = mne.minimum_norm.make_inverse_operator(evoked.info, forward, covariance, loose=1.0, depth=None,
                                                         verbose=False)
        estimate = mne.minimum_norm.apply_inverse(evoked, inverse, lambda2=lambda2, method="eLORETA", verbose=False)
        peak = int(np.argmax(np.abs(estimate.data[:, 0])))
        # Our columns at the peak against MNE's sphere model there: two forward models of one head, RDM (0..2).
        _, theirs = simulate(info, positions_mm[peak], np.zeros(3))
        ours = forward["sol"]["data"][:, 3 * peak:3 * peak + 3]
        unit = lambda m: (m - m.mean(axis=0)) / np.linalg.norm(m - m.mean(axis=0), axis=0)
        results.append({"dipole_mm": position_mm.tolist(), "peak_mm": positions_mm[peak].tolist(),
                        "error_mm": float(np.linalg.norm(positions_mm[peak] - position_mm)),
                        "rdm_at_peak_vs_mne_sphere": np.linalg.norm(unit(ours) - unit(theirs), axis=0).tolist()})
    return {"channels": len(info["ch_names"]), "sources": int(forward["nsource"]), "method": "eLORETA",
            "lambda2": lambda2, "noise": noise, "dipoles": results}


def main(argv):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("leadfield", help="EEG lead field .npy of tm-leadfield (its .json next to it)")
    parser.add_argument("--dipole", required=True, action="append", help="X,Y,Z,PX,PY,PZ: position mm, moment A*m "
                        "(repeatable)")
    parser.add_argument("--noise", type=float, default=0.02, help="white noise, as a fraction of the data's RMS")
    args = parser.parse_args(argv)
    dipoles = []
    for text in args.dipole:
        values = [float(v) for v in text.split(",")]
        if len(values) != 6:
            parser.error(f"--dipole {text}: give X,Y,Z,PX,PY,PZ")
        dipoles.append(values)
    print(json.dumps(localise(args.leadfield, dipoles, args.noise), indent=1))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
