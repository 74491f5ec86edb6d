"""`lightsail-mbs render`: a saved Result as numbered PNG frames (and an MP4/GIF), headless."""

from __future__ import annotations

from pathlib import Path

from lightsail_mbs.cli.options import writable_folder

RENDERERS = ("auto", "matplotlib", "exudyn")  # viz.frames.RENDERERS
COLOR_CHOICES = {"curvature": "curvature", "moment": "moment", "none": None}


def register(sub) -> None:
    p = sub.add_parser(
        "render",
        help="render a saved run (.npz) as PNG frames and optionally a movie, no display (a sheet run: "
        "deflection map and 3-D view)",
    )
    p.add_argument("run", help="a Result saved by `lightsail-mbs simulate --out RUN.npz`")
    p.add_argument("--out", required=True, help="output folder: frame_0000.png, ... (and RUN.mp4 / RUN.gif)")
    which = p.add_mutually_exclusive_group()
    which.add_argument("--frames", type=int, help="number of frames, evenly spaced in time [default: 100]")
    which.add_argument("--every-seconds", type=float, help="one frame per this much simulated time (s)")
    p.add_argument(
        "--size", default=None, help="WIDTHxHEIGHT in pixels [default: 800x400; 800x800 with --compare; sheet 1000x450]"
    )
    p.add_argument("--exaggeration", type=float, help="deflection factor [default: automatic, printed on each frame]")
    p.add_argument(
        "--renderer",
        choices=RENDERERS,
        default="auto",
        help="exudyn (raytracer) or matplotlib (Agg); auto: the faster, exudyn [default: auto]",
    )
    p.add_argument(
        "--color-by",
        choices=sorted(COLOR_CHOICES),
        default="curvature",
        help="colour the slices by hinge curvature Δθ/l or bending moment k_T Δθ [default: curvature]",
    )
    p.add_argument(
        "--color-scale",
        choices=("frame", "run"),
        default=None,
        help="colour range: each frame its own (where it concentrates) or one for the run (growth) "
        "[default: frame; run for a sheet]",
    )
    p.add_argument(
        "--no-arrows", dest="arrows", action="store_false", help="omit the radiation-load and boundary-tension arrows"
    )
    p.add_argument(
        "--frame",
        default="inertial",
        help="a sheet run: inertial (the run's own) or rotating (about the sail's normal through its centre of "
        "mass at the tiles' mean spin rate) [default: inertial]",
    )
    p.add_argument("--compare", metavar="RUN2", help="a second run drawn below the first at the same times")
    p.add_argument("--labels", nargs=2, metavar=("LABEL1", "LABEL2"), help="panel labels with --compare")
    p.add_argument("--movie", choices=("mp4", "gif", "both"), help="also encode the frames into OUT/RUN.mp4/.gif")
    p.add_argument("--fps", type=float, default=20.0, help="movie frame rate [default: 20]")
    p.add_argument("--quiet", action="store_true", help="no progress bar on stderr")
    p.set_defaults(func=run)


def run(args) -> int:
    from lightsail_mbs.base.validation import ParameterError
    from lightsail_mbs.result import Result
    from lightsail_mbs.viz.frames import check_fps, make_movie, parse_size, render_comparison, render_frames

    result = Result.load(args.run)
    if result.is_sheet:
        return run_sheet(args, result)
    if args.frame != "inertial":
        raise ParameterError(f"--frame={args.frame!r} is invalid for a chain run: allowed inertial (sheet runs only)")
    other = Result.load(args.compare) if args.compare else None
    size = parse_size(args.size or ("800x800" if args.compare else "800x400"))
    if args.movie:
        check_fps(args.fps)
    writable_folder(args.out, "--out")
    options = dict(
        frames=args.frames,
        every_seconds=args.every_seconds,
        exaggeration=args.exaggeration,
        renderer=args.renderer,
        color_by=COLOR_CHOICES[args.color_by],
        color_scale=args.color_scale or "frame",
        arrows=args.arrows,
        progress=not args.quiet,
    )
    if other is not None:
        labels = args.labels or (Path(args.run).stem, Path(args.compare).stem)
        paths = render_comparison(result, other, args.out, labels=labels, size=size, **options)
    else:
        paths = render_frames(result, args.out, size=size, **options)
    print(f"wrote {len(paths)} frames of {size[0]}x{size[1]} px to {args.out}/")
    kinds = {"mp4": ["mp4"], "gif": ["gif"], "both": ["mp4", "gif"], None: []}[args.movie]
    for kind in kinds:
        movie = make_movie(paths, Path(args.out) / f"{Path(args.run).stem}.{kind}", fps=args.fps)
        print(f"wrote {movie}")
    return 0


def run_sheet(args, result) -> int:
    """A sheet run: deflection map and 3-D view per frame (viz.sheet), matplotlib only."""
    from lightsail_mbs.base.validation import ParameterError
    from lightsail_mbs.viz.frames import check_fps, make_movie, parse_size
    from lightsail_mbs.viz.sheet import render_sheet_frames
    from lightsail_mbs.viz.spin_frame import check_frame, in_frame

    if args.compare:
        raise ParameterError("--compare is invalid for a sheet run: allowed for chain runs only")
    if args.renderer == "exudyn":
        raise ParameterError("--renderer=exudyn is invalid for a sheet run: allowed auto or matplotlib")
    check_frame(args.frame)
    size = parse_size(args.size or "1000x450")
    if args.movie:
        check_fps(args.fps)
    writable_folder(args.out, "--out")
    paths = render_sheet_frames(
        in_frame(result, args.frame),
        args.out,
        frames=args.frames,
        every_seconds=args.every_seconds,
        size=size,
        exaggeration=args.exaggeration,
        color_scale=args.color_scale or "run",
        progress=not args.quiet,
    )
    views = f"deflection map and 3-D view, {args.frame} frame"
    print(f"wrote {len(paths)} frames of {size[0]}x{size[1]} px to {args.out}/ ({views})")
    kinds = {"mp4": ["mp4"], "gif": ["gif"], "both": ["mp4", "gif"], None: []}[args.movie]
    for kind in kinds:
        movie = make_movie(paths, Path(args.out) / f"{Path(args.run).stem}.{kind}", fps=args.fps)
        print(f"wrote {movie}")
    return 0
