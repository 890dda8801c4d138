"""A wedge with knuckles dropped into water: hullslice against a published drop test.

    python examples/drop_test.py [--plot drop_test.png] [--slices 8]

The test: Zhao, R., Faltinsen, O. M. and Aarsnes, J. V. (1996), "Water entry of arbitrary
two-dimensional sections with and without flow separation", Proc. 21st Symposium on
Naval Hydrodynamics, Trondheim, National Academy Press. At MARINTEK, a 30-degree wedge
with knuckles, 0.50 m wide (the knuckles 0.144 m above the keel, vertical sides above
them), was dropped into calm water. The rig, 1.0 m long and 241 kg, is a 0.20 m
force-measuring section between two 0.40 m dummy sections of the same shape. Its
Figure 15 shows the measured vertical force on the measuring section (15a, solid line),
the authors' fully nonlinear 2D computation with flow separation (15a, dashed) and the
measured drop velocity (15b), over the first 25 ms from first contact.

The paper gives these as figures only. The numbers below were read by eye off the
published figure (a digitisation shared in the public repository
``github.com/Ryu0523/rowbot_sim``, file ``studies/exp_slam_wedge.py``): take them as
+-250 N and +-0.05 m/s. The script checks them against each other first: the rig's loss of
momentum in the measured velocity (with gravity), times the measuring section's share of
its length, is an estimate of the section's impulse that does not use the force curve.

The main model is the Modified Logvinovich Model (``mlm``): Wagner's contact with the
pressure on the real body, and past the knuckles the contact continued on a fictitious
straight body and the pressure integrated over the real one. The strip theory ``zarnick``
(Wagner's flat-plate force, frozen added mass and a cross-flow drag after the knuckles)
and the paper's solver are shown beside it.

hullslice's model of the test is a 1.0 m prism of the same section and the rig's mass
(``hullslice.shapes.wedge_prism`` with sides), level, so every slice is the 2D section;
the force on the measuring section is the total force times 0.20 / 1.0. Two runs per
solver:

- **measured motion**: the force along the measured velocity (a cubic spline through it;
  the draft is its integral and the acceleration its derivative), ``hullslice.prescribed``;
- **free drop**: the 241 kg rig from 6.15 m/s at first contact, ``hullslice.simulate``
  (its velocity is then a prediction too).

It prints the data check, the force history side by side, and for each run the peak
force, its time and the force after the flow has separated at the knuckles (20 and 25 ms),
next to the measurement. ``--plot`` draws the histories (needs matplotlib).
"""

from __future__ import annotations

import argparse
import math
import sys

import numpy as np
from scipy.interpolate import CubicSpline

import hullslice as hs
from hullslice import shapes
from hullslice.progress import terminal_progress

#: The drop test (Zhao, Faltinsen & Aarsnes 1996, Section 5 and Figure 15).
TEST = {
    "deadrise_deg": 30.0,
    "breadth": 0.50,  # m, between the knuckles
    "rig_length": 1.0,  # m: two 0.40 m dummy sections and the measuring section
    "measuring_length": 0.20,  # m
    "mass": 241.0,  # kg, the whole drop rig
    "rho": 1000.0,  # kg/m^3, fresh water (not stated in the paper)
    "g": 9.81,  # m/s^2
}
#: Height of the prism's vertical sides above the knuckles, m (never reached in 25 ms).
SIDES = 0.35

# Figure 15, read by eye (+-250 N, +-0.05 m/s): time from first contact (s), the measured
# vertical force on the 0.2 m measuring section and the authors' fully nonlinear 2D
# computation of it (N), and the measured drop velocity (m/s, positive down).
T_FORCE = np.array([0.0, 2.5, 5.0, 7.5, 10.0, 12.5, 14.5, 15.5, 17.5, 20.0, 22.5, 25.0]) * 1e-3
F_MEASURED = np.array(
    [0.0, 1400.0, 2800.0, 3900.0, 4500.0, 4900.0, 5150.0, 5100.0, 3700.0, 2600.0, 2300.0, 1900.0]
)
F_NONLINEAR = np.array(
    [0.0, 1400.0, 2850.0, 4200.0, 5500.0, 6200.0, 6550.0, 6650.0, 5000.0, 3500.0, 3100.0, 2800.0]
)
T_VELOCITY = np.array([0.0, 2.5, 5.0, 7.5, 10.0, 12.5, 15.0, 17.5, 20.0, 22.5, 25.0]) * 1e-3
V_MEASURED = np.array([6.15, 6.14, 6.08, 5.97, 5.80, 5.58, 5.35, 5.15, 5.02, 4.94, 4.90])
#: The end of the figures, s.
T_END = 0.025
#: Times of the printed history, s; after separation: the force once the flow has left
#: the knuckles (the measured force has fallen from its peak by then).
SHOWN = np.array([2.5, 5.0, 7.5, 10.0, 12.5, 15.0, 17.5, 20.0, 22.5, 25.0]) * 1e-3
AFTER = (0.020, 0.025)

#: The runs: (label, solver name, solver options). The MLM's continuation past the
#: knuckles is its default (the deadrise whose late drag is Zarnick's cross-flow drag,
#: 57.5 deg), Keuning's drag (53.4 deg) and the bottom's tangent (30 deg).
SOLVERS = (
    ("mlm", "mlm", {}),
    ("mlm, continuation for C_D,c = 1.33", "mlm", {"continuation": 53.4}),
    ("mlm, tangent continuation", "mlm", {"continuation": "tangent"}),
    ("zarnick", "zarnick", {}),
    ("zarnick, Dobrovol'skaya pile-up", "zarnick", {"pile_up": "dobrovolskaya"}),
    ("zarnick, C_D,c = 1.33", "zarnick", {"cross_flow_drag": 1.33}),
    ("extended-von-karman", "extended-von-karman", {}),
)


def knuckle_height() -> float:
    """Height of the knuckles above the keel, m (0.144 m)."""
    return TEST["breadth"] / 2 * math.tan(math.radians(TEST["deadrise_deg"]))


def rig() -> hs.Hull:
    """The drop rig: a prism of the test's section, the rig's length and mass."""
    v, f = shapes.wedge_prism(
        length=TEST["rig_length"],
        beam=TEST["breadth"],
        deadrise_deg=TEST["deadrise_deg"],
        stations=3,
        sides=SIDES,
    )
    return hs.Hull.from_arrays(v, f, mass=TEST["mass"], name="Zhao et al. (1996) drop rig")


def measured_motion(steps: int = 250) -> dict[str, np.ndarray]:
    """The measured drop as a kinematics table (hullslice's signs: velocity negative down,
    acceleration positive up), from just after first contact to :data:`T_END`."""
    spline = CubicSpline(T_VELOCITY, V_MEASURED)
    t = np.linspace(T_END / steps, T_END, steps)
    return {
        "t": t,
        "draft": spline.antiderivative()(t),
        "velocity": -spline(t),
        "acceleration": -spline(t, 1),
    }


def fluid() -> hs.Fluid:
    return hs.Fluid(rho=TEST["rho"], g=TEST["g"])


def share() -> float:
    """The measuring section's share of the rig's force."""
    return TEST["measuring_length"] / TEST["rig_length"]


def rig_impulse_from_velocity(t: float) -> float:
    """The measuring section's impulse from first contact to ``t`` (s) implied by the
    measured velocity alone, N s: the rig's ``mass (g t - (V(t) - V(0)))`` (V positive
    down) times the section's share of its length."""
    dv = float(np.interp(t, T_VELOCITY, V_MEASURED)) - V_MEASURED[0]
    return TEST["mass"] * (TEST["g"] * t - dv) * share()


def measured_impulse(t: float) -> float:
    """The impulse of the measured force from first contact to ``t`` (s), N s."""
    grid = np.linspace(0.0, t, 501)
    force = np.interp(grid, T_FORCE, F_MEASURED)
    return float(np.sum(0.5 * (force[1:] + force[:-1]) * np.diff(grid)))


def runs(slices: int) -> dict[str, dict[str, hs.History]]:
    """For each solver of :data:`SOLVERS`, its history along the measured motion and in a
    free drop of the rig."""
    body, water = rig(), fluid()
    kin = measured_motion()
    dt = float(kin["t"][0])
    out = {}
    for label, name, options in SOLVERS:
        solver = hs.get_solver(name, **options)
        # a progress line on a terminal's stderr (nothing when it is not one)
        with terminal_progress(f"{label}, measured motion") as progress:
            measured = hs.prescribed(
                body, kin, slices=slices, solver=solver, fluid=water, progress=progress
            )
        with terminal_progress(f"{label}, free drop") as progress:
            drop = hs.simulate(
                body, -V_MEASURED[0], T_END, dt=dt, slices=slices, solver=solver, fluid=water,
                stop_on=(), progress=progress,
            )  # fmt: skip
        out[label] = {"measured motion": measured, "free drop": drop}
    return out


def section_force(history: hs.History) -> np.ndarray:
    """The force on the measuring section along a history, N."""
    return np.asarray(history.force) * share()


def peak(t: np.ndarray, force: np.ndarray) -> tuple[float, float]:
    """The largest force (N) and its time (s)."""
    i = int(np.argmax(force))
    return float(force[i]), float(t[i])


def summary(name: str, t: np.ndarray, force: np.ndarray, v_end: float | None = None) -> None:
    """One row of the summary: the peak force (N), its time, the force after the flow's
    separation and, for a free drop, the velocity at the end (m/s, positive down)."""
    p, tp = peak(t, force)
    after = "".join(f"  {np.interp(ta, t, force):9.0f}" for ta in AFTER)
    end = f"  {v_end:16.2f}" if v_end is not None else ""
    print(f"  {name:<50}  {p:8.0f}  {tp * 1e3:7.1f}{after}{end}")


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument(
        "--slices",
        type=int,
        default=8,
        help="slices over the wetted length (default 8; the rig is a prism: every slice is alike)",
    )
    parser.add_argument("--plot", metavar="FILE", help="draw the force histories into FILE")
    args = parser.parse_args(argv)

    print("Drop test of a 30 deg wedge with knuckles (Zhao, Faltinsen & Aarsnes 1996, Fig. 15)")
    print(f"knuckles {knuckle_height():.4f} m above the keel; force on the 0.2 m section [N]")
    print("\nthe data checked against themselves: the rig's momentum x 0.2 / 1.0 [N s]")
    for t in (0.015, 0.020, 0.025):
        implied, measured = rig_impulse_from_velocity(t), measured_impulse(t)
        print(
            f"  0 to {t * 1e3:4.1f} ms: from the velocity {implied:5.1f}, measured force "
            f"{measured:5.1f} ({measured / implied - 1:+.0%})"
        )

    histories = runs(args.slices)
    heads = ("measured", "nonlinear 2D (paper)", "mlm, measured motion", "mlm, free drop")
    print("\n  t [ms]  " + "  ".join(heads))
    main_runs = histories["mlm"]
    for t in SHOWN:
        row = [np.interp(t, T_FORCE, F_MEASURED), np.interp(t, T_FORCE, F_NONLINEAR)]
        row += [np.interp(t, h.t, section_force(h)) for h in main_runs.values()]
        cells = (f"{f:{len(w)}.0f}" for f, w in zip(row, heads, strict=True))
        print(f"  {t * 1e3:6.1f}  " + "  ".join(cells))

    print(f"\n  {'run':<50}  peak [N]  at [ms]  20 ms [N]  25 ms [N]  V at 25 ms [m/s]")
    summary("measured", T_FORCE, F_MEASURED, V_MEASURED[-1])
    summary("nonlinear 2D (paper)", T_FORCE, F_NONLINEAR)
    for label, pair in histories.items():
        for kind, h in pair.items():
            end = -float(h.velocity[-1]) if kind == "free drop" else None
            summary(f"{label}, {kind}", np.asarray(h.t), section_force(h), end)
    if args.plot:
        plot(histories, args.plot)
        print(f"\nwrote {args.plot}")
    return 0


def plot(histories: dict[str, dict[str, hs.History]], path: str) -> None:
    """The force on the measuring section and the drop velocity over time."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, (ax_f, ax_v) = plt.subplots(1, 2, figsize=(11, 5.6))
    ax_f.plot(T_FORCE * 1e3, F_MEASURED, "ko-", label="measured (Zhao et al. 1996)")
    ax_f.plot(T_FORCE * 1e3, F_NONLINEAR, "k--", label="their nonlinear 2D computation")
    ax_v.plot(T_VELOCITY * 1e3, V_MEASURED, "ko-")
    colours = ("C0", "C1", "C2", "C3", "C4", "C5", "C6")
    for (label, pair), colour in zip(histories.items(), colours, strict=False):
        for kind, style in (("measured motion", "-"), ("free drop", ":")):
            h = pair[kind]
            t = np.asarray(h.t) * 1e3
            ax_f.plot(t, section_force(h), style, color=colour, label=f"{label}, {kind}")
            if kind == "free drop":
                ax_v.plot(t, -np.asarray(h.velocity), style, color=colour)
    ax_f.set(xlabel="time from first contact [ms]", ylabel="force on the 0.2 m section [N]")
    ax_v.set(xlabel="time from first contact [ms]", ylabel="drop velocity [m/s] (free drops)")
    for ax in (ax_f, ax_v):
        ax.grid(alpha=0.3)
    fig.legend(*ax_f.get_legend_handles_labels(), loc="lower center", ncol=3, fontsize=8)
    fig.tight_layout(rect=(0, 0.2, 1, 1))
    fig.savefig(path, dpi=110)
    plt.close(fig)


if __name__ == "__main__":
    sys.exit(main())
