"""Write paper_curves.csv: the paper's characteristic curves (Eqs. 5-6) as a table.

161 rows evenly spaced over the fitted range of z~ (-0.0387 to 0); linear interpolation
between them is within 1.4e-4 of the peak a~ and 3e-5 in v~ of the polynomials. Run:

    python plugins/curves/examples/make_paper_curves.py
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from hullslice.solvers import PAPER_CURVES

ROWS = 161


def main() -> None:
    lo, hi = PAPER_CURVES.z_range
    z = np.linspace(lo, hi, ROWS)
    lines = [
        "# The characteristic curves of the 2D+t paper (Eqs. 5-6): a free-falling wedge,",
        "# beta = 45 deg, M = 4.6842 kg/m, v_z0 = 5.5 m/s, water of 1000 kg/m^3.",
        "z_tilde,a_tilde,v_tilde",
    ]
    lines += [
        f"{zi!r},{ai!r},{vi!r}"
        for zi, ai, vi in zip(
            z.tolist(), PAPER_CURVES.a(z).tolist(), PAPER_CURVES.v(z).tolist(), strict=True
        )
    ]
    out = Path(__file__).with_name("paper_curves.csv")
    out.write_text("\n".join(lines) + "\n")
    print(f"wrote {out} ({ROWS} rows)")


if __name__ == "__main__":
    main()
