"""`lightsail-mbs optics`: optical force tables — a grating by RCWA, the built-in mirror and facet, and
what a table file holds::

    lightsail-mbs optics grating --design bigrating --out bigrating.npz
    lightsail-mbs optics grating --period 1.8e-6 --bar-height 0.4e-6 --bar-index Si --fill-factor 0.4 \\
        --film-thickness 0.3e-6 --film-index SiO2 --polarization mean --out table.npz
    lightsail-mbs optics grating --layer "0.4e-6,1.0,0.05:0.34=3.48,0.47:0.54=3.48" --layer "0.3e-6,1.45" ...
    lightsail-mbs optics grating --design symmetric --wavelengths 1.2e-6:1.5e-6:7 --out spectrum.npz
    lightsail-mbs optics mirror --out mirror.npz
    lightsail-mbs optics info table.npz

Refractive indices are numbers (``3.48``, ``3.48+0.01j``, κ ≥ 0 absorbing), permittivities (``eps=12.1``)
or material names of meent's tables (``Si``, ``SiO2``, …) evaluated at the wavelength (with ``--wavelengths``,
at each of them: model/optics_spectrum.py).
"""

from __future__ import annotations

import json
import math
import sys

from lightsail_mbs.base.validation import ParameterError, check


def register(sub) -> None:
    p = sub.add_parser("optics", help="optical force tables: a grating by RCWA, the mirror, the facet; table info")
    osub = p.add_subparsers(dest="optics_command", required=True, title="subcommands", metavar="SUBCOMMAND")

    g = osub.add_parser(
        "grating",
        help="the force table c_n(θ), c_t(θ) of a 1-D grating by RCWA (cached on disk)",
        description="The force table of a 1-D grating by RCWA. The stack: --design, or the bar layer "
        "(--bar-height, --bar-index, --gap-index, --fill-factor or --bars) on an optional --film, or --layer "
        "specifications (which replace the bar layer and film). Indices: numbers, eps=…, or material names.",
    )
    geo = g.add_argument_group("geometry (SI units; lengths in m)")
    from lightsail_mbs.model.rcwa import GRATINGS

    geo.add_argument("--design", choices=sorted(GRATINGS), help="a named grating (the other options override it)")
    geo.add_argument("--wavelength", type=float, help="vacuum wavelength λ (m) [default: design's, else 1.2e-6]")
    geo.add_argument(
        "--wavelengths",
        nargs="+",
        metavar="λ",
        help="tabulate at these vacuum wavelengths (m), or START:STOP:COUNT evenly spaced, into one table with "
        "a wavelength axis; --wavelength (the laser's, the table at rest) must lie in their range",
    )
    geo.add_argument("--period", type=float, help="grating period Λ (m) [default: design's]")
    geo.add_argument("--bar-height", type=float, help="thickness of the bar layer (m)")
    geo.add_argument("--bar-index", help="refractive index of the bars [default: 3.48]")
    geo.add_argument("--gap-index", default="1.0", help="refractive index between the bars [default: 1.0]")
    geo.add_argument("--fill-factor", type=float, help="one centred bar of this fraction of the period")
    geo.add_argument("--bars", help="bars as START:END fractions of the period, comma separated (0.05:0.34,0.47:0.54)")
    geo.add_argument(
        "--film-thickness", type=float, default=0.0, help="uniform film under the bars (m) [default: 0, none]"
    )
    geo.add_argument("--film-index", default="1.45", help="refractive index of the film [default: 1.45]")
    geo.add_argument(
        "--layer",
        action="append",
        metavar="SPEC",
        help="a layer from the laser side, THICKNESS,BACKGROUND[,START:END=INDEX…]; repeat for a stack",
    )
    tab = g.add_argument_group("table")
    tab.add_argument("--polarization", choices=("TE", "TM", "mean"), default="TE", help="TE, TM or mean [default: TE]")
    tab.add_argument("--harmonics", type=int, default=60, help="orders −N…N kept in the RCWA [default: 60]")
    tab.add_argument("--theta-max", type=float, default=85.0, help="table range ±θ_max (degrees) [default: 85]")
    tab.add_argument("--step", type=float, default=0.25, help="largest node spacing (degrees) [default: 0.25]")
    tab.add_argument(
        "--tolerance",
        type=float,
        default=1e-4,
        help="refine where an interval's midpoint is off the spline by more than this (0: none) [default: 1e-4]",
    )
    tab.add_argument(
        "--grade", type=int, default=12, help="nodes at step/2^k, k ≤ GRADE, beside each anomaly [default: 12]"
    )
    tab.add_argument("--backend", choices=("meent", "grcwa"), default="meent", help="RCWA package [default: meent]")
    tab.add_argument(
        "--cache-dir", help="cache folder [default: $LIGHTSAIL_MBS_CACHE/optics or ~/.cache/lightsail-mbs/optics]"
    )
    tab.add_argument("--no-cache", action="store_true", help="neither read nor write the cache")
    tab.add_argument("--progress", action="store_true", help="a progress bar on stderr")
    g.add_argument("--out", required=True, help="the table file to write (.npz)")
    g.add_argument("--json", action="store_true", help="print the table's summary as one JSON object")
    g.set_defaults(func=run_grating)

    m = osub.add_parser("mirror", help="the perfect mirror's table (the paper's Eq. 11)")
    m.add_argument("--out", required=True, help="the table file to write (.npz)")
    m.set_defaults(func=run_builtin)

    f = osub.add_parser("facet", help="the specular, absorbing facet's table (model/loads.py's law)")
    f.add_argument("--reflectivity", type=float, required=True, help="specular reflectivity R")
    f.add_argument("--absorptivity", type=float, default=0.0, help="absorptivity α [default: 0]")
    f.add_argument("--out", required=True, help="the table file to write (.npz)")
    f.set_defaults(func=run_builtin)

    i = osub.add_parser("info", help="what an optical table file holds and a few of its values")
    i.add_argument("table", help="a table written by `lightsail-mbs optics …`")
    i.add_argument(
        "--angles", default="0,1,2,5,10,20,40", help="angles (degrees) to print c_n, c_t at [default: %(default)s]"
    )
    i.add_argument("--json", action="store_true", help="print the summary and the values as one JSON object")
    i.set_defaults(func=run_info)


def parse_layer(spec: str, wavelength: float):
    """A Layer from THICKNESS,BACKGROUND[,START:END=INDEX…]."""
    from lightsail_mbs.model.rcwa import Bar, Layer, refractive_index

    parts = [s.strip() for s in spec.split(",")]
    check("--layer", spec, len(parts) >= 2, "THICKNESS,BACKGROUND[,START:END=INDEX…]")
    try:
        thickness = float(parts[0])
    except ValueError:
        raise ParameterError(f"--layer={spec!r} is invalid: allowed a thickness in m first") from None
    bars = []
    for item in parts[2:]:
        span, sep, index = item.partition("=")
        start, colon, end = span.partition(":")
        check("--layer", item, bool(sep and colon), "bars as START:END=INDEX")
        try:
            bars.append(Bar(float(start), float(end), refractive_index(index, wavelength, "--layer bar index")))
        except ValueError as exc:
            if isinstance(exc, ParameterError):
                raise
            raise ParameterError(f"--layer={spec!r} is invalid: allowed bars as START:END=INDEX") from None
    return Layer(thickness, refractive_index(parts[1], wavelength, "--layer background"), tuple(bars))


def grating_from_args(args):
    """The Grating the options describe."""
    from lightsail_mbs.model.rcwa import GRATINGS, WAVELENGTH, Bar, Grating, Layer, refractive_index

    base = GRATINGS[args.design] if args.design else None
    wavelength = args.wavelength or (base.wavelength if base else WAVELENGTH)
    period = args.period or (base.period if base else None)
    check("--period", period, period is not None, "a period in m (or --design)")
    if args.layer:
        layers = tuple(parse_layer(spec, wavelength) for spec in args.layer)
    elif args.bar_height is not None or base is None:
        check("--bar-height", args.bar_height, args.bar_height is not None, "a thickness in m (or --layer, --design)")
        check(
            "--fill-factor",
            args.fill_factor,
            (args.fill_factor is None) != (args.bars is None),
            "exactly one of --fill-factor and --bars",
        )
        if args.fill_factor is not None:
            f = args.fill_factor
            check("--fill-factor", f, 0 < f <= 1, "0 < fill factor ≤ 1")
            spans = [(0.5 - f / 2, 0.5 + f / 2)]
        else:
            try:
                spans = [tuple(float(v) for v in item.split(":")) for item in args.bars.split(",")]
                assert all(len(s) == 2 for s in spans)
            except (ValueError, AssertionError):
                raise ParameterError(f"--bars={args.bars!r} is invalid: allowed START:END,START:END,…") from None
        bar_index = refractive_index(args.bar_index or "3.48", wavelength, "--bar-index")
        gap = refractive_index(args.gap_index, wavelength, "--gap-index")
        layers = (Layer(args.bar_height, gap, tuple(Bar(a, b, bar_index) for a, b in spans)),)
        if args.film_thickness:
            layers += (Layer(args.film_thickness, refractive_index(args.film_index, wavelength, "--film-index")),)
    else:
        layers = base.layers
    name = base.name if base and not args.layer and args.bar_height is None else "grating"
    return Grating(wavelength, period, layers, name)


def _writable(path: str):
    from lightsail_mbs.cli.options import writable_file

    check("--out", path, path.endswith(".npz"), "a file name ending in .npz")
    return writable_file(path, "--out", ".npz")


def run_grating(args) -> int:
    from lightsail_mbs.model import optics

    out = _writable(args.out)
    g = grating_from_args(args)
    progress = None
    bar = None
    if args.progress:
        from tqdm import tqdm

        bar = tqdm(desc="RCWA", unit="solve", file=sys.stderr, mininterval=0.5)

        def progress(i, total):
            bar.n = i
            bar.refresh()

    cache = False if args.no_cache else args.cache_dir
    settings = dict(
        harmonics=args.harmonics,
        theta_max=math.radians(args.theta_max),
        step=math.radians(args.step),
        backend=args.backend,
        cache_dir=cache,
        progress=progress,
        tolerance=args.tolerance,
        grade=args.grade,
    )
    try:
        if args.wavelengths:
            spectrum = grating_spectrum_from_args(args, g, settings)
            table = spectrum.rest()
        else:
            spectrum, table = None, optics.grating_table(g, args.polarization, **settings)
    finally:
        if bar is not None:
            bar.close()
    (spectrum or table).save(out)
    summary = (spectrum or table).summary()
    if args.json:
        print(json.dumps(summary | {"out": str(out)}))
        return 0
    if spectrum is not None:
        lo, hi = spectrum.range
        print(
            f"{out}: a wavelength axis of {spectrum.wavelengths.size} wavelengths, {lo:.6g} … {hi:.6g} m, linear "
            f"in λ between them; at rest (the laser's λ = {spectrum.wavelength:.6g} m):"
        )
    print(
        f"{out}: {g.name or 'grating'} ({summary['polarization']}), {summary['nodes']} nodes on "
        f"±{args.theta_max:g}°, {args.harmonics} harmonics ({args.backend}), "
        f"RCWA CPU {summary['rcwa_cpu_seconds']:.1f} s"
    )
    print(f"  c_n(0) = {summary['c_n(0)']:.6f}, c_t(0) = {summary['c_t(0)']:+.6f} (mirror: 2, 0)")
    print(
        f"  refinement: {summary['refinement_nodes']} nodes added in {summary['refinement_passes']} passes; "
        f"last midpoint error {summary['refinement_last_error']:.1e} (tolerance {args.tolerance:g})"
    )
    anomalies = ", ".join(f"{math.degrees(a):+.3f}°" for a in summary["rayleigh_anomalies"])
    print(f"  Rayleigh anomalies (spline breaks): {anomalies or 'none in range'}")
    if g.lossless:
        worst = max(float(abs(v).max()) for k, v in table.extra.items() if k.startswith("A_"))
        print(f"  lossless: max |1 − ΣR − ΣT| over the nodes = {worst:.1e}")
    return 0


def wavelength_grid(specs) -> list[float]:
    """The wavelengths of --wavelengths: numbers (m), or one START:STOP:COUNT (COUNT ≥ 2, evenly spaced)."""
    allowed = "wavelengths in m, increasing (λ1 λ2 …), or START:STOP:COUNT"
    try:
        if len(specs) == 1 and ":" in specs[0]:
            start, stop, count = specs[0].split(":")
            count = int(count)
            check("--wavelengths", specs[0], count >= 2, "START:STOP:COUNT with COUNT ≥ 2")
            values = [float(start) + (float(stop) - float(start)) * k / (count - 1) for k in range(count - 1)]
            values.append(float(stop))
        else:
            values = [float(v) for v in specs]
    except ValueError:
        raise ParameterError(f"--wavelengths={' '.join(specs)!r} is invalid: allowed {allowed}") from None
    ok = len(values) >= 2 and all(math.isfinite(v) and v > 0 for v in values)
    check("--wavelengths", " ".join(specs), ok and all(b > a for a, b in zip(values, values[1:])), allowed)
    return values


def grating_spectrum_from_args(args, g, settings):
    """The SpectralTable the options describe: the grating built at each of --wavelengths (material names
    evaluated there), the laser's wavelength g.wavelength inside their range."""
    import argparse

    from lightsail_mbs.model.optics_spectrum import grating_spectrum

    grid = wavelength_grid(args.wavelengths)
    check(
        "--wavelength",
        g.wavelength,
        grid[0] <= g.wavelength <= grid[-1],
        f"the laser's wavelength inside the range of --wavelengths, {grid[0]:g} … {grid[-1]:g} m",
    )
    gratings = [grating_from_args(argparse.Namespace(**(vars(args) | {"wavelength": lam}))) for lam in grid]
    return grating_spectrum(gratings, g.wavelength, polarization=args.polarization, **settings)


def run_builtin(args) -> int:
    from lightsail_mbs.model import optics

    out = _writable(args.out)
    table = optics.mirror() if args.optics_command == "mirror" else optics.facet(args.reflectivity, args.absorptivity)
    table.save(out)
    print(
        f"{out}: {table.kind}, c_n = {table.normal_constant:g} cos²θ, c_t = {table.tangential_constant:g} cos θ sin θ"
    )
    return 0


def run_info(args) -> int:
    import numpy as np

    from lightsail_mbs.model import optics
    from lightsail_mbs.model.optics_spectrum import read_spectrum

    try:
        table = optics.OpticalTable.load(args.table)
        spectrum = read_spectrum(args.table, single=True)
    except optics.OpticsFileError as exc:
        raise ParameterError(f"table={args.table!r} is invalid: {exc}") from None
    try:
        angles = [float(a) for a in args.angles.split(",")]
    except ValueError:
        raise ParameterError(f"--angles={args.angles!r} is invalid: allowed degrees, comma separated") from None
    cn, ct = table.coefficients(np.radians(angles))
    summary = (spectrum or table).summary()
    values = [{"theta_deg": a, "c_n": float(n), "c_t": float(t)} for a, n, t in zip(angles, cn, ct)]
    if args.json:
        print(json.dumps(summary | {"values": values}, default=str))
        return 0
    lo, hi = summary["theta_range_deg"]
    where = f"θ ∈ [{lo:g}°, {hi:g}°] (NaN outside)" if table.bounded else "every angle (a closed form)"
    print(f"{args.table}: {summary['kind']} table, polarization {summary['polarization']}, {summary['nodes']} nodes")
    print(f"  defined on {where}; format version {summary['format_version']}")
    if spectrum is not None:
        lo, hi = spectrum.range
        print(
            f"  wavelength axis: {spectrum.wavelengths.size} wavelengths, {lo:.6g} … {hi:.6g} m (linear in λ between "
            f"them); the values below at the laser's λ = {spectrum.wavelength:.6g} m"
        )
    if summary["kind"] == "grating":
        grating = summary["grating"]
        print(
            f"  λ = {grating['wavelength']:.6g} m, Λ = {grating['period']:.6g} m, {len(grating['layers'])} layers; "
            f"{summary['backend']} {summary['backend_version']}, {summary['harmonics']} harmonics, "
            f"step {math.degrees(summary['step']):g}°, RCWA CPU {summary['rcwa_cpu_seconds']:.1f} s"
        )
        print(
            f"  refinement: tolerance {summary['tolerance']:g}, {summary['refinement_nodes']} nodes added, last "
            f"midpoint error {summary['refinement_last_error']:.1e}; {summary['grade']} graded nodes beside each "
            "Rayleigh anomaly"
        )
        for k, layer in enumerate(grating["layers"]):
            bars = ", ".join(f"[{b['start']:g}, {b['end']:g}) n = {complex(*b['index']):g}" for b in layer["bars"])
            print(
                f"    layer {k}: {layer['thickness']:.4g} m, background n = {complex(*layer['background']):g}; {bars}"
            )
    print("  θ (deg)      c_n          c_t")
    for v in values:
        print(f"  {v['theta_deg']:7.2f}  {v['c_n']:11.6f}  {v['c_t']:+11.6f}")
    return 0
