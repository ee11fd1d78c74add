#!/usr/bin/env python3
"""Observed spread of each pixel's depth over repeated reconstructions against its predicted standard deviation.

Reads points.ply of each reconstruction directory given (rfrecon reconstruct's output: z and the depth_sigma*
properties per camera pixel u v), keeps the pixels every reconstruction has, and prints, over those pixels, the RMS of
the observed standard deviation of z (over the reconstructions, n - 1 in the denominator), the RMS of the predicted
sigma (the property named by --sigma, its mean square over the reconstructions) and their ratio, overall and by
quartile of the prediction. One JSON line with --json.
Usage: scripts/depth_sigma_spread.py --sigma depth_sigma_observation DIR DIR [DIR ...]
"""
import argparse
import json
import sys

import numpy as np

PLY_TYPES = {"float": "<f4", "uchar": "u1", "int": "<i4", "double": "<f8"}


def read_ply(path):
    with open(path, "rb") as f:
        names, types, count = [], [], 0
        while True:
            line = f.readline().decode("ascii").strip()
            if line.startswith("element vertex"):
                count = int(line.split()[2])
            elif line.startswith("property"):
                _, kind, name = line.split()
                names.append(name)
                types.append(PLY_TYPES[kind])
            elif line == "end_header":
                break
        return np.frombuffer(f.read(), dtype=np.dtype(list(zip(names, types))), count=count)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--sigma", default="depth_sigma", help="the PLY property of the prediction")
    parser.add_argument("--json", action="store_true")
    parser.add_argument("dirs", nargs="+")
    args = parser.parse_args()
    if len(args.dirs) < 3:
        sys.exit("give at least three reconstructions")
    clouds = [read_ply(f"{d}/points.ply") for d in args.dirs]
    width = int(max(c["u"].max() for c in clouds)) + 1
    keys = [c["v"].astype(np.int64) * width + c["u"].astype(np.int64) for c in clouds]
    common = keys[0]
    for k in keys[1:]:
        common = np.intersect1d(common, k)
    z = np.empty((len(clouds), common.size))
    sigma = np.empty_like(z)
    for i, (cloud, k) in enumerate(zip(clouds, keys)):
        at = np.searchsorted(k, common) if np.all(k[:-1] <= k[1:]) else np.argsort(k)[np.searchsorted(np.sort(k), common)]
        z[i] = cloud["z"][at]
        sigma[i] = cloud[args.sigma][at]
    finite = np.all(np.isfinite(sigma), axis=0)
    z, sigma = z[:, finite], sigma[:, finite]
    observed = z.std(axis=0, ddof=1)
    predicted = np.sqrt((sigma ** 2).mean(axis=0))
    rms = lambda a: float(np.sqrt(np.mean(a ** 2)))
    result = {"reconstructions": len(clouds), "pixels": int(predicted.size), "observed_rms_mm": rms(observed),
              "predicted_rms_mm": rms(predicted), "ratio": rms(observed) / rms(predicted), "quartiles": []}
    edges = np.quantile(predicted, [0, 0.25, 0.5, 0.75, 1.0])
    for q in range(4):
        inside = (predicted >= edges[q]) & (predicted <= edges[q + 1])
        result["quartiles"].append({"predicted_rms_mm": rms(predicted[inside]), "observed_rms_mm": rms(observed[inside]),
                                    "ratio": rms(observed[inside]) / rms(predicted[inside])})
    if args.json:
        print(json.dumps(result))
        return
    print(f"{result['pixels']} pixels in all {len(clouds)}: observed {result['observed_rms_mm']:.5f} mm RMS, "
          f"predicted ({args.sigma}) {result['predicted_rms_mm']:.5f} mm, ratio {result['ratio']:.3f}")
    for q, r in enumerate(result["quartiles"]):
        print(f"  quartile {q + 1} of the prediction: predicted {r['predicted_rms_mm']:.5f} observed "
              f"{r['observed_rms_mm']:.5f} ratio {r['ratio']:.3f}")


if __name__ == "__main__":
    main()
