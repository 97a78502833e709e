"""Tilting-pad journal bearings solved by ross-rotordynamics 3.1's fluid-film engine
(`ross.bearings.tilting_pad.TiltingPad`, isoviscous: thermal_type=None, the journal's
place matched to the load): an independent code's eccentricity, attitude and
synchronously reduced coefficients for the bearings of BEARINGS, written to a JSON file
the tests compare shaftfem's pad films with (tests/data/tilting_pads_ross.json).

ross 3.1 is no dependency of shaftfem, and asks for Python 3.13; it runs on 3.11 in an
environment of its own:

    python3 -m venv .venv-ross3
    .venv-ross3/bin/pip install --ignore-requires-python --no-deps ross-rotordynamics==3.1.0
    .venv-ross3/bin/pip install "numpy>=2.2" "scipy>=1.15" toml "pandas>=2.3" \\
        "plotly>=5.15" xlrd "pint>=0.24.4" methodtools numba "ccp-performance>=0.4.1" \\
        prettytable control
    .venv-ross3/bin/python benchmarks/tilting_pad_reference.py tests/data/tilting_pads_ross.json
    .venv-ross3/bin/python benchmarks/tilting_pad_reference.py --whirl \
        tests/data/tilting_pads_ross_whirl.json

`--heat`: Fillon, Bligoud & Frene's (1992) 4-pad bearing (benchmarks/pad_heat.py) with
ross's thermohydrodynamic film (thermal_type="full": the film's 3D energy equation,
conduction in 20 mm pads, the journal at the films' mean temperature, hot-oil
carry-over 0.8), rigid pads, at 1,000 to 4,000 r/min. Its oil is shaftfem's ISO VG 32
(parts.oil) through ross's exponential law at 40 and 70 C, with shaftfem's specific heat
and conductivity; the film cells are those of ross's own test of this rig.

    .venv-ross3/bin/python benchmarks/tilting_pad_reference.py --heat tests/data/fillon_ross.json

`--heat --grown`: the same with ross's pads deformed by their pressure and heat (2D
plane-strain pads, 20 mm thick) and its journal and shell grown by their temperatures,
the shell at the supply's (deform_type "pad_mechanical_thermal_shaft_shell_thermal"),
at shaftfem's steel expansion (parts.pad_heat.EXPANSION). About 3 minutes.

    .venv-ross3/bin/python benchmarks/tilting_pad_reference.py --heat --grown \
        tests/data/fillon_ross_grown.json

`--whirl`: the first bearing at its first speed reduced at whirls of WHIRL_RATIOS times
the spin (ross's excitation_ratio), its pads massless (pad_density 1e-9: shaftfem's
film table takes massless pads).

ross's angles run from +x towards +y, the journal turning the same way; a pad's pivot
offset is its share of the arc from the leading edge. Its films here are finer than its
defaults (60 cells round each pad, 40 along it). About 5 minutes.
"""

from __future__ import annotations

import json
import sys
import warnings
from pathlib import Path

# SI; pivots in degrees from +x; the load on the journal along -y
BEARINGS = {
    "5 pads, load between pads": {
        "diameter": 0.1, "length": 0.05, "clearance": 100e-6, "pads": 5, "arc_deg": 60.0,
        "preload": 0.5, "offset": 0.5, "first_pivot_deg": 18.0, "viscosity": 0.02,
        "load": 5000.0, "speeds_rpm": [3000.0, 6000.0]},
    "4 pads, load on pad, offset 0.6": {
        "diameter": 0.12, "length": 0.09, "clearance": 90e-6, "pads": 4, "arc_deg": 80.0,
        "preload": 0.3, "offset": 0.6, "first_pivot_deg": 270.0, "viscosity": 0.015,
        "load": 8000.0, "speeds_rpm": [4000.0, 8000.0]},
}


WHIRL_RATIOS = (0.5, 2.0)


def solve(b: dict, **more) -> list[dict]:
    from ross.bearings.tilting_pad import TiltingPad
    from ross.units import Q_

    n = b["pads"]
    mu = b["viscosity"]
    # equal viscosities at both temperatures: the engine's viscosity law is constant
    oil = {"liquid_viscosity1": mu, "temperature1": 313.15, "liquid_viscosity2": mu,
           "temperature2": 373.15, "liquid_density": 860.0, "liquid_specific_heat": 1951.0,
           "liquid_thermal_conductivity": 0.13}
    bearing = TiltingPad(
        n=0, speed=Q_(b["speeds_rpm"], "RPM"), equilibrium_type="match_load",
        journal_diameter=b["diameter"], radial_clearance=b["clearance"], pad_thickness=0.02,
        pivot_angle=Q_([b["first_pivot_deg"] + k * 360.0 / n for k in range(n)], "deg"),
        pad_arc=Q_([b["arc_deg"]] * n, "deg"), pad_axial_length=[b["length"]] * n,
        preload=[b["preload"]] * n, offset=[b["offset"]] * n, lubricant=oil,
        oil_supply_temperature=Q_(40, "degC"), oil_flow_v=Q_(20, "l/min"),
        fxs_load=0.0, fys_load=-b["load"], thermal_type=None,
        total_ex_film=60, total_ez_film=40, **more)
    rows = []
    for i, rpm in enumerate(b["speeds_rpm"]):
        out = bearing._results.outputs[i]
        row = {"speed_rpm": rpm, "sommerfeld": float(out["x_som_m"][0]),
               "eccentricity": float(out["eccentricity"][0]),
               "x_over_c": float(out["xj_cb"][0]), "y_over_c": float(out["yj_cb"][0])}
        for k in ("kxx", "kxy", "kyx", "kyy", "cxx", "cxy", "cyx", "cyy"):
            row[k] = float(getattr(bearing, k)[i])
        rows.append(row)
    return rows


def whirl(path: str) -> int:
    """The --whirl file: the first bearing's coefficients at its first speed, reduced at
    each whirl ratio, massless pads."""
    import ross

    name, b = next(iter(BEARINGS.items()))
    b = {**b, "speeds_rpm": b["speeds_rpm"][:1]}
    rows = {str(r): solve(b, excitation_ratio=r, pad_density=1e-9)[0] for r in WHIRL_RATIOS}
    out = {"source": f"ross-rotordynamics {ross.__version__}, TiltingPad, thermal_type=None, "
                     "excitation_ratio, pad_density 1e-9, 60 x 40 film cells per pad",
           "bearing": name, **b, "whirl": rows}
    with open(path, "w") as f:
        json.dump(out, f, indent=1)
    print(json.dumps(rows, indent=1))
    return 0


# parts.heat.SPECIFIC_HEAT and parts.pad_heat.CONDUCTIVITY (tests/test_pad_heat.py
# checks the file against them); the pads' conductivity and edge convection are ross's
# Fillon case's
FILLON = {"diameter": 0.1, "length": 0.07, "pad_clearance": 148e-6, "preload": 0.47,
          "pads": 4, "arc_deg": 75.0, "offset": 0.5, "first_pivot_deg": 45.0, "load": 10e3,
          "grade": 32, "supply_c": 40.0, "specific_heat": 1900.0, "conductivity": 0.13,
          "carry_over": 0.8, "speeds_rpm": [1000.0, 2000.0, 3000.0, 4000.0]}


# --heat --grown: ross's pads deformed by their pressure and heat (its 2D plane-strain
# pads) and its journal and shell grown by theirs, the shell at the supply's temperature,
# at shaftfem's expansion (parts.pad_heat.EXPANSION) and with 20 mm pads
GROWN = "pad_mechanical_thermal_shaft_shell_thermal"


def heat(path: str, grown: bool = False) -> int:
    """The --heat file: ross's peak pad temperature, journal temperature, eccentricity
    and synchronously reduced K (N/m) and C (N s/m), its pads massless, on Fillon's
    bearing at each speed (`grown`: its pads, journal and shell deformed, GROWN)."""
    import ross
    from ross.bearings.tilting_pad import TiltingPad
    from ross.units import Q_

    sys.path.insert(0, str(Path(__file__).parents[1] / "src"))
    # numpy and scipy only, which ross has: no other shaftfem dependency is needed here
    from shaftfem.parts import oil
    from shaftfem.parts.pad_heat import EXPANSION

    b = FILLON
    g, n = b["grade"], b["pads"]
    deform = {"deform_type": GROWN, "pad_expansion": EXPANSION,
              "journal_expansion": EXPANSION, "shell_expansion": EXPANSION} if grown else {
              "deform_type": None}
    lubricant = {"liquid_viscosity1": oil.dynamic(g, 40.0), "temperature1": 313.15,
                 "liquid_viscosity2": oil.dynamic(g, 70.0), "temperature2": 343.15,
                 "liquid_density": oil.density(b["supply_c"]),
                 "liquid_specific_heat": b["specific_heat"],
                 "liquid_thermal_conductivity": b["conductivity"]}
    rows = []
    for rpm in b["speeds_rpm"]:
        bearing = TiltingPad(
            n=0, speed=Q_([rpm], "RPM"), equilibrium_type="match_load", thermal_type="full",
            **deform, journal_diameter=b["diameter"],
            radial_clearance=b["pad_clearance"] * (1 - b["preload"]), pad_thickness=0.02,
            pivot_angle=Q_([b["first_pivot_deg"] + k * 360.0 / n for k in range(n)], "deg"),
            pad_arc=Q_([b["arc_deg"]] * n, "deg"), pad_axial_length=[b["length"]] * n,
            preload=[b["preload"]] * n, offset=[b["offset"]] * n, lubricant=lubricant,
            oil_supply_temperature=Q_(b["supply_c"], "degC"), oil_flow_v=Q_(10, "gallon/min"),
            fxs_load=0.0, fys_load=-b["load"], hot_oil_lambda=b["carry_over"],
            pad_conductivity=50.0, edges_convection=73.59,
            journal_temperature=Q_(49, "degC"), pad_density=1e-9,
            total_ex_film=24, total_ez_film=10, total_ey_film=10, total_ey_pad=10)
        out = bearing._results.outputs[0]
        rows.append({"speed_rpm": rpm, "peak_c": float(out["tpad_max"][0]) - 273.15,
                     "journal_c": float(out["journal_temperature_output"][0]) - 273.15,
                     "eccentricity": float(out["eccentricity"][0]),
                     **{k: float(getattr(bearing, k)[0])
                        for k in ("kxx", "kxy", "kyx", "kyy", "cxx", "cxy", "cyx", "cyy")}})
        print(rows[-1], flush=True)
    with open(path, "w") as f:
        json.dump({"source": f"ross-rotordynamics {ross.__version__}, TiltingPad, "
                             f"thermal_type='full', deform_type={deform['deform_type']!r}, "
                             "24 x 10 x 10 film cells, 10 through each pad, massless pads"
                             + (f", expansion {EXPANSION:g} 1/K" if grown else ""),
                   "bearing": b, "results": rows}, f, indent=1)
    return 0


def main(argv: list[str]) -> int:
    import ross

    warnings.filterwarnings("ignore")
    if argv[0] == "--whirl":
        return whirl(argv[1])
    if argv[0] == "--heat":
        return heat(argv[-1], grown=argv[1] == "--grown")
    out = {"source": f"ross-rotordynamics {ross.__version__}, TiltingPad, thermal_type=None, "
                     "equilibrium_type='match_load', 60 x 40 film cells per pad",
           "bearings": {name: {**b, "results": solve(b)} for name, b in BEARINGS.items()}}
    with open(argv[0], "w") as f:
        json.dump(out, f, indent=1)
    for name, b in out["bearings"].items():
        for r in b["results"]:
            print(name, r)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
