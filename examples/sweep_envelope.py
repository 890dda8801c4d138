"""Draw the envelope of a sweep: the peak force against pitch and sink rate.

    hullslice sweep examples/ditching_sweep.toml -o ditching.nc
    python examples/sweep_envelope.py ditching.nc -o envelope.png

Reads the dataset (netCDF or Zarr) with xarray and draws the peak force (N) as filled
contours over the two swept keys. Cases whose peak is carried mostly (over half) by slices
outside the method's range are left blank, those with over a tenth are hatched, failed cases
are crossed, and every case is a dot. Needs 'hullslice[sweep]' and 'hullslice[plot]'.
"""

from __future__ import annotations

import argparse

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np
import xarray as xr


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("dataset", help="a sweep's output, .nc or .zarr")
    ap.add_argument("-o", "--output", default="envelope.png", help="the figure (PNG, SVG, PDF)")
    ap.add_argument("--x", default="pitch", help="swept key along x (default: pitch)")
    ap.add_argument("--y", default="velocity", help="swept key along y (default: velocity)")
    args = ap.parse_args()
    opener = xr.open_zarr if args.dataset.endswith(".zarr") else xr.open_dataset
    ds = opener(args.dataset).load()
    others = [d for d in ds["peak_force"].dims if d not in (args.x, args.y)]
    ds = ds.isel(dict.fromkeys(others, 0))  # any other swept key: its first value
    force = ds["peak_force"].transpose(args.y, args.x)
    share = ds["flagged_share"].transpose(args.y, args.x)
    x, y = ds[args.x], ds[args.y]
    fig, ax = plt.subplots(figsize=(7, 4.5))
    filled = ax.contourf(x, y, force.where(share <= 0.5) / 1e3, levels=12, cmap="viridis")
    fig.colorbar(filled, ax=ax, label=f"{force.attrs['long_name']} [k{force.attrs['units']}]")
    if bool((share > 0.1).any()):
        ax.contourf(x, y, (share > 0.1).astype(float), levels=[0.5, 1.5], hatches=["//"],
                    colors="none")  # fmt: skip
    failed = (ds["error"] != "").transpose(args.y, args.x).values
    xx, yy = np.meshgrid(x, y)
    ax.plot(xx.ravel(), yy.ravel(), "k.", ms=2)
    ax.plot(xx[failed], yy[failed], "rx")
    ax.set_xlabel(f"{x.attrs.get('long_name', args.x)} [{x.attrs.get('units', '')}]")
    ax.set_ylabel(f"{y.attrs.get('long_name', args.y)} [{y.attrs.get('units', '')}]")
    ax.set_title(f"{ds.attrs.get('title', '')}\nhatched: over 10 % of the peak on flagged "
                 "slices; blank: over half", fontsize=9)  # fmt: skip
    fig.savefig(args.output, dpi=120, bbox_inches="tight")
    print(f"wrote {args.output}")


if __name__ == "__main__":
    main()
