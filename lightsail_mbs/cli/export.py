"""`lightsail-mbs export`: a saved sheet run as a time series of tile polygons for ParaView (viz.export)."""

from __future__ import annotations

FORMATS = ("xdmf", "vtu")  # viz.export.FORMATS
FRAMES = ("inertial", "rotating")  # viz.spin_frame.FRAMES
SUFFIX = {"xdmf": ".xdmf", "vtu": ".pvd"}


def register(sub) -> None:
    p = sub.add_parser(
        "export",
        help="export a saved sheet run (.npz) as a time series of moving tiles that ParaView opens "
        "(XDMF, or VTU files with a PVD index), with deflection, z, velocity, angular velocity and load per tile",
    )
    p.add_argument("run", help="a sheet Result saved by `lightsail-mbs simulate --out RUN.npz`")
    p.add_argument(
        "--format",
        default="xdmf",
        help=f"{' or '.join(FORMATS)}: one RUN.xdmf, or RUN.pvd indexing RUN/RUN_00000.vtu, ... [default: xdmf]",
    )
    p.add_argument(
        "--frame",
        default="inertial",
        help="inertial (the run's own) or rotating (about the sail's normal through its centre of mass at the "
        "tiles' mean spin rate) [default: inertial]",
    )
    p.add_argument("--out", help="output file [default: beside the run, its name with .xdmf or .pvd]")
    p.set_defaults(func=run)


def run(args) -> int:
    from lightsail_mbs.cli.options import writable_file
    from lightsail_mbs.result import Result
    from lightsail_mbs.viz.export import check_format, export
    from lightsail_mbs.viz.spin_frame import check_frame, require_sheet_run

    check_format(args.format)
    check_frame(args.frame)
    out = writable_file(args.out or args.run, "--out", SUFFIX[args.format])
    result = Result.load(args.run)
    require_sheet_run(result, "export")
    files = export(result, out, args.format, args.frame)
    extra = f" and {len(files) - 1} .vtu files in {out.with_suffix('')}/" if len(files) > 1 else ""
    print(f"wrote {out}{extra}: {len(result.time)} time steps, {args.frame} frame")
    return 0
