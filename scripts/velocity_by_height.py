#!/usr/bin/env python3
"""RMS fluid speed in horizontal bands, per exported frame of a run.

Usage: scripts/velocity_by_height.py RUN_DIR [BAND_M]

RUN_DIR is the output directory of a run with `output.export = ["csv"]`; BAND_M the
band height in metres (default 0.5). Prints one line per frame: the RMS of |v| of the
particles whose y lies in each band, and vx^2 / vy^2 over the whole fluid (about 1 for
disordered motion, far below 1 for a vertical settling). Used for "The stable step of a
deep fluid" in docs/performance.md: it shows where a column at rest heats up first.
"""
import csv
import math
import pathlib
import sys


def main() -> int:
    if len(sys.argv) not in (2, 3):
        print(__doc__.strip().splitlines()[2], file=sys.stderr)
        return 2
    run = pathlib.Path(sys.argv[1])
    band = float(sys.argv[2]) if len(sys.argv) == 3 else 0.5
    if not band > 0:
        print(f"BAND_M must be > 0, got {band}", file=sys.stderr)
        return 2
    frames = sorted((run / "particles").glob("frame_*.csv"))
    if not frames:
        print(f"{run}/particles holds no frame_*.csv: run with output.export = [\"csv\"]", file=sys.stderr)
        return 2
    for path in frames:
        bands: dict[int, list[float]] = {}
        sx = sy = 0.0
        with path.open(newline="") as f:
            for row in csv.DictReader(f):
                vx, vy = float(row["vx"]), float(row["vy"])
                bands.setdefault(math.floor(float(row["y"]) / band), []).append(vx * vx + vy * vy)
                sx += vx * vx
                sy += vy * vy
        cells = " ".join(
            f"{k * band:.2f}-{(k + 1) * band:.2f} m: {math.sqrt(sum(v) / len(v)):.3f}" for k, v in sorted(bands.items()))
        ratio = sx / sy if sy > 0 else float("inf")
        print(f"{path.stem}  {cells}  | vx2/vy2 {ratio:.2f}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
