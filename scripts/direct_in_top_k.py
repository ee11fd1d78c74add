"""Whether T's top-K window holds the direct light where interreflection fools the decoding (docs/accuracy.md,
"Results: interreflection"): given T of a scene rendered with interreflection and T of the same scene and seed
without it (whose decoded projector pixel is the direct light's), counts the pixels whose correspondence moved by
more than 2 projector pixels or was lost ("fooled"), and the share of those whose direct pixel lies within 1.5 px of
one of the K entries of T with interreflection, with its rank among them (0 = strongest).
Usage: PYTHONPATH=build/python python3 scripts/direct_in_top_k.py T_WITH.h5 T_WITHOUT.h5
"""
import sys

import numpy as np

import rfrecon


def main(with_path, without_path):
    bounce = rfrecon.read_transport(with_path)
    direct = rfrecon.read_transport(without_path)
    k = bounce.entries_per_pixel
    width = bounce.projector_size[0]
    indices = np.asarray(bounce.indices).reshape(-1, k)
    truth = np.asarray(direct.correspondence).reshape(-1, 2)
    decoded = np.asarray(bounce.correspondence).reshape(-1, 2)
    seen = np.isfinite(truth[:, 0])
    with np.errstate(invalid="ignore"):
        fooled = seen & ~(np.hypot(*(decoded - truth).T) <= 2.0)
    distance = np.hypot(indices % width - truth[:, :1], indices // width - truth[:, 1:2])
    distance[indices < 0] = np.inf
    near = distance <= 1.5
    held = near.any(axis=1)
    rank = np.argmax(near, axis=1)
    print(f"K {k}: {seen.sum()} pixels decoded without interreflection, {fooled.sum()} fooled with it")
    print(f"  direct pixel among the top K: {100.0 * held[fooled].mean():.1f} % of the fooled")
    if (fooled & held).any():
        print(f"  its rank there: median {np.median(rank[fooled & held]):.0f}, "
              f"strongest {100.0 * (rank[fooled & held] == 0).mean():.1f} %")


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    main(sys.argv[1], sys.argv[2])
