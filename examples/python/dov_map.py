#!/usr/bin/env python3
"""Draw a map of the deflection of the vertical: ξ, η as arrows over the total
deflection √(ξ² + η²) in colour, and the geoid as contours (docs/python.md).

    PYTHONPATH=build/python python3 examples/python/dov_map.py -o dov.png
    PYTHONPATH=build/python python3 examples/python/dov_map.py --model egm96 \
        --region 5 16 45 48.5 --step 0.05 -o alps.png

--model takes a file (.gfc, .egm) or a name on GeographicLib's search path
(meridian.gravity.search_path()); without it a synthetic model of degree 360
(meridian.gravity.synthetic_model) stands in, so the script runs on a fresh
machine. Needs matplotlib (Debian python3-matplotlib), which Meridian itself
does not.
"""

import argparse

import matplotlib

matplotlib.use("Agg")  # files only, no display needed
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import meridian.gravity as mg  # noqa: E402


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--model", help="model file or name (default: synthetic, degree 360)")
    p.add_argument("--region", nargs=4, type=float, metavar=("W", "E", "S", "N"), default=(5, 16, 45, 48.5),
                   help="longitudes and latitudes of the map (degrees; default the Alps)")
    p.add_argument("--step", type=float, default=0.1, help="grid step (degrees)")
    p.add_argument("--height", type=float, default=0.0, help="ellipsoidal height of the grid (m)")
    p.add_argument("-o", "--output", default="dov.png", help="image file (png, pdf, svg)")
    a = p.parse_args()

    model = mg.GravityModel.open(a.model) if a.model else mg.synthetic_model(360, 1)
    w, e, s, n = a.region
    lat = np.arange(s, n + a.step / 2, a.step)
    lon = np.arange(w, e + a.step / 2, a.step)
    d = model.grid(lat, lon, a.height)  # arrays of shape (len(lat), len(lon))
    total = np.hypot(d.xi_arcsec, d.eta_arcsec)

    fig, ax = plt.subplots(figsize=(10, 10 * (n - s) / ((e - w) * np.cos(np.radians((s + n) / 2)))))
    mesh = ax.pcolormesh(lon, lat, total, shading="nearest", cmap="viridis")
    fig.colorbar(mesh, ax=ax, label="total deflection √(ξ² + η²) (″)", shrink=0.8)
    cs = ax.contour(lon, lat, d.geoid_m, colors="white", linewidths=0.6)
    ax.clabel(cs, fmt="%.1f m", fontsize=7)
    # The arrow points where the plumb line's zenith lies: η east, ξ north.
    k = max(1, len(lon) // 25)
    ax.quiver(lon[::k], lat[::k], d.eta_arcsec[::k, ::k], d.xi_arcsec[::k, ::k], color="black", width=0.002)
    ax.set_aspect(1 / np.cos(np.radians((s + n) / 2)))
    ax.set_xlabel("longitude (°E)")
    ax.set_ylabel("latitude (°N)")
    ax.set_title(f"Deflection of the vertical, {model.name} (degree {model.max_degree}), h = {a.height:g} m")
    fig.savefig(a.output, dpi=120, bbox_inches="tight")
    print(f"{a.output}: {lat.size} x {lon.size} points, |ξ, η| up to {total.max():.1f}″")


if __name__ == "__main__":
    main()
