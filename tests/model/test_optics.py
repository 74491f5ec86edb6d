"""Optics as data: the built-in laws against model/loads.py, the table's spline, files and cache, and the
RCWA gratings against thin-film optics, energy conservation and mirror symmetry."""

import json
import math

import numpy as np
import pytest

from lightsail_mbs import ParameterError, SailParameters
from lightsail_mbs.model import optics, rcwa
from lightsail_mbs.model.loads import radiation_forces

rng = np.random.default_rng(18)
FAST = 8  # harmonics for the default suite (the tables use 60; validation/optics.py converges them)


def relative_force_error(a, b):
    """max |f_a − f_b| / |f_b| over slices, vector norm."""
    num = np.hypot(a[0] - b[0], a[1] - b[1])
    return float(np.max(num / np.hypot(b[0], b[1])))


# ---- the built-in laws ------------------------------------------------------------------------------
def test_mirror_is_eq11_at_every_angle():
    p = SailParameters(n=40, intensity=3e9, width=0.7)
    theta = np.concatenate([rng.uniform(-np.pi / 2, np.pi / 2, 200), rng.uniform(-7, 7, 40)])
    x = rng.uniform(0, 1, theta.size)
    table = optics.mirror()
    err = relative_force_error(table.forces(p, x, theta), radiation_forces(p, x, theta))
    assert err < 1e-14
    cn, ct = table.coefficients(theta)
    np.testing.assert_allclose(cn, 2 * np.cos(theta) ** 2, rtol=1e-15, atol=0)
    assert not np.any(ct)


@pytest.mark.parametrize("seed", range(4))
def test_facet_is_the_loads_law(seed):
    r = np.random.default_rng(seed)
    R = r.uniform(0, 1)
    a = r.uniform(0, 1 - R)
    p = SailParameters(n=30, reflectivity=R, absorptivity=a, beam_waist=r.uniform(0.2, 2), beam_centre=r.uniform(0, 1))
    theta = r.uniform(-1.5, 1.5, 300)
    x = r.uniform(-0.5, 1.5, 300)
    table = optics.facet(R, a)
    assert relative_force_error(table.forces(p, x, theta), radiation_forces(p, x, theta)) < 1e-14
    assert optics.for_case(p).normal_constant == 2 * R + a


def test_nominal_acceleration_of_the_builtins_is_the_cases():
    for p in (SailParameters(), SailParameters(reflectivity=0.5, absorptivity=0.3, beam_waist=0.5)):
        assert optics.for_case(p).nominal_acceleration(p) == pytest.approx(p.nominal_acceleration, rel=1e-15)


def test_facet_rejects_impossible_optics():
    with pytest.raises(ParameterError, match="absorptivity"):
        optics.facet(0.7, 0.5)
    with pytest.raises(ParameterError, match="reflectivity"):
        optics.facet(1.2, 0.0)


def test_momentum_balance_by_hand():
    """A single specular order: the mirror (R₀ = 1) and the facet (R₀ = R, T₀ = 1 − R − α)."""
    th = 0.37
    one = dict(m=np.array([0]), sigma=np.array([math.sin(th)]))
    mirror = rcwa.Orders(th, "TE", reflected=np.array([1.0]), transmitted=np.array([0.0]), **one)
    assert rcwa.force_coefficients(mirror) == pytest.approx((2 * math.cos(th) ** 2, 0.0), abs=1e-15)
    R, a = 0.55, 0.3
    facet = rcwa.Orders(th, "TE", reflected=np.array([R]), transmitted=np.array([1 - R - a]), **one)
    cn, ct = rcwa.force_coefficients(facet)
    assert cn == pytest.approx((2 * R + a) * math.cos(th) ** 2, rel=1e-14)
    assert ct == pytest.approx(a * math.cos(th) * math.sin(th), rel=1e-14)


def test_first_order_diffraction_pushes_sideways():
    """All light into the transmitted order −1 at normal incidence (σ = −λ/Λ): c_t = λ/Λ, c_n = −cos θ₋₁ + 1."""
    ratio = 0.6
    o = rcwa.Orders(
        0.0,
        "TE",
        m=np.array([-1, 0]),
        sigma=np.array([-ratio, 0.0]),
        reflected=np.zeros(2),
        transmitted=np.array([1.0, 0.0]),
    )
    cn, ct = rcwa.force_coefficients(o)
    assert ct == pytest.approx(ratio, rel=1e-15)
    assert cn == pytest.approx(1 - math.sqrt(1 - ratio**2), rel=1e-15)


# ---- the table --------------------------------------------------------------------------------------
def smooth_table(breaks=(0.3,)):
    theta = optics.node_grid(1.2, 0.02, breaks)
    kink = np.sqrt(np.abs(np.sin(theta) - math.sin(0.3)))  # a square-root kink at the break
    c2 = np.cos(theta) ** 2
    return optics.OpticalTable.from_samples(
        theta, c2 * (1.2 + 0.3 * np.sin(theta) + kink), c2 * np.sin(2 * theta), breaks, "TE", {"kind": "test"}
    )


def test_spline_reproduces_nodes_and_converges_between_them():
    table = smooth_table()
    cn, ct = table.coefficients(table.theta)
    np.testing.assert_allclose(table.c_n, cn, rtol=1e-14)
    mid = 0.5 * (table.theta[1:] + table.theta[:-1])
    exact = 1.2 + 0.3 * np.sin(mid) + np.sqrt(np.abs(np.sin(mid) - math.sin(0.3)))
    sn, st = table.tabulated(mid)
    assert np.max(np.abs(sn - exact)) < 3e-2  # the intervals beside the kink, where √ is not cubic
    far = np.abs(mid - 0.3) > 0.1
    assert np.max(np.abs(sn - exact)[far]) < 1e-4
    assert np.max(np.abs(st - np.sin(2 * mid))) < 1e-6
    assert np.median(np.abs(sn - exact)) < 1e-8


def test_bounded_table_is_nan_outside_and_builtins_are_not():
    table = smooth_table()
    cn, ct = table.coefficients(np.array([-1.21, 1.2000001, np.nan, 0.0]))
    assert np.isnan(cn[:3]).all() and np.isnan(ct[:3]).all() and np.isfinite(cn[3])
    assert np.isfinite(optics.mirror().coefficients(np.array([-4.0, 3.0]))[0]).all()
    assert optics.mirror().theta_range == (-math.inf, math.inf)


def test_mirrored_slice_sees_the_table_turned_over():
    table = smooth_table()
    th = rng.uniform(-1.1, 1.1, 50)
    cn, ct = table.coefficients(th, mirrored=True)
    cn_m, ct_m = table.coefficients(-th)
    np.testing.assert_array_equal(cn, cn_m)
    np.testing.assert_array_equal(ct, -ct_m)
    flags = rng.uniform(size=50) < 0.5
    cn_f, _ = table.coefficients(th, mirrored=flags)
    np.testing.assert_array_equal(cn_f, np.where(flags, cn, table.coefficients(th)[0]))


@pytest.mark.parametrize("mirrored", [False, True])
def test_compiled_kernel_equals_numpy(mirrored):
    for table in (smooth_table(), optics.mirror(), optics.facet(0.4, 0.5)):
        packed = table.packed()
        th = np.concatenate([rng.uniform(-1.3, 1.3, 60), table.theta[:3]])
        cn, ct = table.coefficients(th, mirrored)
        p = SailParameters(intensity=2e9)
        x = np.full(th.size, 0.5)
        fx, fy = table.forces(p, x, th, mirrored)
        scale = p.intensity * p.slice_length * p.width / optics.SPEED_OF_LIGHT
        for i, t in enumerate(th):
            a, b = optics.packed_coefficients(packed, t, mirrored)
            assert (a, b) == pytest.approx((cn[i], ct[i]), rel=1e-14, abs=1e-15, nan_ok=True)
            f = optics.packed_force(packed, scale, t, mirrored)
            assert f == pytest.approx((fx[i], fy[i]), rel=1e-13, abs=1e-25, nan_ok=True)


def test_node_grid_symmetric_with_breaks_and_step():
    breaks = [-0.4, 0.4, 0.9]
    th = optics.node_grid(1.3, 0.03, breaks)
    np.testing.assert_array_equal(th, -th[::-1])
    assert 0.0 in th and {0.4, -0.4, 0.9, -0.9} <= set(th)
    assert np.max(np.diff(th)) <= 0.03 + 1e-15 and th[0] == -1.3 and th[-1] == 1.3


def test_table_file_round_trip_and_errors(tmp_path):
    table = smooth_table()
    path = table.save(tmp_path / "t.npz")
    back = optics.OpticalTable.load(path)
    th = rng.uniform(-1.3, 1.3, 100)
    np.testing.assert_array_equal(np.array(back.coefficients(th)), np.array(table.coefficients(th)))
    assert back.polarization == "TE" and back.kind == "test" and back.metadata["format_version"] == 1
    builtin = optics.OpticalTable.load(optics.facet(0.3, 0.2).save(tmp_path / "f.npz"))
    assert not builtin.bounded and builtin.tangential_constant == 0.2
    with pytest.raises(optics.OpticsFileError, match="no such"):
        optics.OpticalTable.load(tmp_path / "missing.npz")
    np.savez(tmp_path / "other.npz", metadata=np.array(json.dumps({"format": "something else"})))
    with pytest.raises(optics.OpticsFileError, match="not an optical table"):
        optics.OpticalTable.load(tmp_path / "other.npz")
    with np.load(path) as d:
        arrays = dict(d)
    meta = json.loads(str(arrays["metadata"]))
    arrays["metadata"] = np.array(json.dumps({**meta, "format_version": 99}))
    np.savez(tmp_path / "future.npz", **arrays)
    with pytest.raises(optics.OpticsFileError, match="version"):
        optics.OpticalTable.load(tmp_path / "future.npz")
    (tmp_path / "junk.npz").write_bytes(b"not a zip")
    with pytest.raises(optics.OpticsFileError, match="readable"):
        optics.OpticalTable.load(tmp_path / "junk.npz")


# ---- RCWA ------------------------------------------------------------------------------------------
def test_airy_and_abeles_agree_and_conserve_energy():
    for pol in rcwa.POLARIZATIONS:
        for th in (0.0, 0.5, 1.2):
            lossless = rcwa.airy_rt(2.1, 0.37e-6, 1.2e-6, th, pol)
            assert sum(lossless) == pytest.approx(1.0, abs=1e-14)
            lossy = rcwa.airy_rt(2.0 + 0.3j, 0.5e-6, 1.2e-6, th, pol)
            assert lossy == pytest.approx(rcwa.abeles_rt([2.0 + 0.3j], [0.5e-6], 1.2e-6, th, pol), abs=1e-14)
            assert sum(lossy) < 0.95
    # normal incidence: the textbook quarter-wave antireflection minimum and the half-wave absentee layer
    n, lam = 1.5, 1e-6
    assert rcwa.airy_rt(n, lam / (2 * n), lam, 0.0, "TE")[0] == pytest.approx(0.0, abs=1e-15)
    assert rcwa.airy_rt(n, lam / (4 * n), lam, 0.0, "TE")[0] == pytest.approx(
        ((n * n - 1) / (n * n + 1)) ** 2, rel=1e-13
    )


@pytest.mark.parametrize("index", [3.48, 3.48 + 0.05j])
def test_zero_contrast_grating_is_the_airy_film(index):
    """Bars of the film's own index: RCWA must give the film's R and T (the lossy case checks the sign
    convention of the absorption, e^(−iωt) here, e^(+iωt) in meent)."""
    g = rcwa.Grating(1.2e-6, 1.8e-6, (rcwa.Layer(0.4e-6, index, (rcwa.Bar(0.05, 0.34, index),)),))
    for th in (-0.9, 0.0, 0.3, 1.1):
        for pol in rcwa.POLARIZATIONS:
            o = rcwa.orders(g, th, pol, FAST)
            R, T = rcwa.airy_rt(index, 0.4e-6, 1.2e-6, th, pol)
            assert o.reflected.sum() == pytest.approx(R, abs=1e-12)
            assert o.transmitted.sum() == pytest.approx(T, abs=1e-12)


def test_zero_contrast_stack_is_abeles():
    g = rcwa.GRATINGS["bigrating"].filled(rcwa.N_SI)
    for th in (0.0, 0.7):
        for pol in rcwa.POLARIZATIONS:
            o = rcwa.orders(g, th, pol, FAST)
            R, T = rcwa.abeles_rt([rcwa.N_SI, rcwa.N_SIO2], [0.4e-6, 0.3e-6], g.wavelength, th, pol)
            assert (o.reflected.sum(), o.transmitted.sum()) == pytest.approx((R, T), abs=1e-12)


def test_grcwa_cross_check_reproduces_the_film():
    pytest.importorskip("grcwa")
    g = rcwa.GRATINGS["bigrating"].zero_contrast()  # air gaps and air bars on the silica film
    for pol in rcwa.POLARIZATIONS:
        o = rcwa.orders(g, 0.4, pol, 5, backend="grcwa")
        R, T = rcwa.abeles_rt([1.0, rcwa.N_SIO2], [0.4e-6, 0.3e-6], g.wavelength, 0.4, pol)
        assert (o.reflected.sum(), o.transmitted.sum()) == pytest.approx((R, T), abs=1e-12)


def test_lossless_grating_conserves_energy():
    g = rcwa.GRATINGS["bigrating"]
    for th in (-0.6, 0.0, 0.2, 0.34):
        for pol in rcwa.POLARIZATIONS:
            o = rcwa.orders(g, th, pol, FAST)
            assert abs(o.absorbed) < 1e-10
            assert np.count_nonzero(o.reflected + o.transmitted) > 2  # it diffracts


def test_symmetric_grating_has_odd_tangential_force_and_the_bigrating_not():
    sym, big = rcwa.GRATINGS["symmetric"], rcwa.GRATINGS["bigrating"]
    for pol in rcwa.POLARIZATIONS:
        a = rcwa.force_coefficients(rcwa.orders(sym, 0.25, pol, FAST))
        b = rcwa.force_coefficients(rcwa.orders(sym, -0.25, pol, FAST))
        assert a[1] == pytest.approx(-b[1], abs=1e-11) and abs(a[1]) > 1e-2
        assert a[0] == pytest.approx(b[0], abs=1e-11)
    a = rcwa.force_coefficients(rcwa.orders(big, 0.25, "TE", FAST))
    b = rcwa.force_coefficients(rcwa.orders(big, -0.25, "TE", FAST))
    assert abs(a[1] + b[1]) > 0.05
    # mirroring the cell mirrors the law: c(θ) of the mirrored grating = (c_n(−θ), −c_t(−θ))
    c = rcwa.force_coefficients(rcwa.orders(big.mirrored(), 0.25, "TE", FAST))
    assert c == pytest.approx((b[0], -b[1]), abs=1e-11)


def test_rcwa_converges_in_harmonics():
    g = rcwa.GRATINGS["bigrating"]
    ref = np.array(rcwa.force_coefficients(rcwa.orders(g, 0.05, "TE", 40)))
    errs = [np.max(np.abs(np.array(rcwa.force_coefficients(rcwa.orders(g, 0.05, "TE", N))) - ref)) for N in (5, 10, 20)]
    assert errs[0] > errs[1] > errs[2] and errs[2] < 5e-3


def test_rayleigh_anomalies_are_where_orders_graze():
    g = rcwa.Grating(1.0e-6, 3.3e-6, rcwa.GRATINGS["symmetric"].layers)
    angles = g.rayleigh_anomalies()
    np.testing.assert_array_equal(angles, -angles[::-1])
    for a in angles:
        sigma = math.sin(a) + np.arange(-7, 8) * g.wavelength / g.period
        assert np.min(np.abs(np.abs(sigma) - 1)) < 1e-14
    assert rcwa.GRATINGS["bigrating"].rayleigh_anomalies() == pytest.approx([-math.asin(1 / 3), math.asin(1 / 3)])


def test_grating_table_cached_and_exact_at_nodes(tmp_path):
    g = rcwa.GRATINGS["bigrating"]
    step = math.radians(7.5)
    kw = dict(harmonics=FAST, step=step, cache_dir=tmp_path, tolerance=0.0, grade=0)
    first = optics.grating_table(g, "mean", **kw)
    assert first.theta.size > 20 and set(first.metadata["rayleigh_anomalies"]) <= set(first.theta)
    k = int(np.argmin(np.abs(first.theta - 0.2)))
    th = float(first.theta[k])
    direct = np.mean([rcwa.force_coefficients(rcwa.orders(g, th, p, FAST)) for p in rcwa.POLARIZATIONS], axis=0)
    assert (first.c_n[k], first.c_t[k]) == pytest.approx(tuple(direct), rel=1e-13)
    assert np.max(np.abs(first.extra["A_TE"])) < 1e-10 and np.max(np.abs(first.extra["A_TM"])) < 1e-10
    files = sorted(tmp_path.glob("rcwa-*.npz"))
    assert len(files) == 2  # one per polarisation
    stamps = [f.stat().st_mtime_ns for f in files]
    te = optics.grating_table(g, "TE", **kw)
    assert sorted(tmp_path.glob("rcwa-*.npz")) == files  # served from the cache, nothing recomputed or rewritten
    assert [f.stat().st_mtime_ns for f in files] == stamps
    assert te.metadata["cache_keys"][0] == first.metadata["cache_keys"][0]
    other = optics.grating_table(g, "TE", **(kw | {"harmonics": FAST + 1}))
    assert len(list(tmp_path.glob("rcwa-*.npz"))) == 3 and other.metadata["cache_keys"] != te.metadata["cache_keys"]


def test_refinement_brings_the_table_within_its_tolerance(tmp_path):
    """Midpoints off the spline by more than the tolerance become nodes: the error at points that were never
    sampled (interval quarter points) falls, the node set stays symmetric, the anomalies stay breaks."""
    g = rcwa.GRATINGS["bigrating"]
    kw = dict(harmonics=5, theta_max=math.radians(30), step=math.radians(3), cache_dir=tmp_path)
    plain = optics.grating_table(g, "TE", tolerance=0.0, grade=0, **kw)
    fine = optics.grating_table(g, "TE", tolerance=1e-4, **kw)
    assert fine.metadata["refinement_nodes"] > 0 and fine.metadata["refinement_last_error"] <= 1e-4
    np.testing.assert_array_equal(fine.theta, -fine.theta[::-1])
    assert set(plain.theta) <= set(fine.theta)

    def quarter_error(table):
        q = (table.theta[:-1] + 0.25 * np.diff(table.theta))[::2]
        exact = np.array([rcwa.force_coefficients(rcwa.orders(g, float(t), "TE", 5)) for t in q])
        cn, ct = table.coefficients(q)
        return np.maximum(np.abs(exact[:, 0] - cn), np.abs(exact[:, 1] - ct)).max()

    assert quarter_error(fine) < 0.1 * quarter_error(plain)


def test_refractive_index_specs():
    assert rcwa.refractive_index("3.48") == 3.48
    assert rcwa.refractive_index("2+0.1j") == 2 + 0.1j
    assert rcwa.refractive_index("eps=12.25") == pytest.approx(3.5)
    assert rcwa.refractive_index("eps=-20+2j").imag > 0  # a metal's root with κ > 0
    si = rcwa.refractive_index("Si", 1.2e-6)
    assert 3.4 < si.real < 3.6 and 0 <= si.imag < 1e-5
    assert rcwa.refractive_index("SiO2", 1.2e-6) == pytest.approx(1.448, abs=2e-3)
    for spec, wavelength, match in (
        ("3-0.1j", None, "κ"),
        ("unobtainium", 1e-6, "material"),
        ("Si", 5e-6, "wavelength"),
        ("Si", None, "needs the wavelength"),
    ):
        with pytest.raises(ParameterError, match=match):
            rcwa.refractive_index(spec, wavelength)


def test_grating_geometry_is_validated():
    film = rcwa.Layer(1e-7, 1.45)
    with pytest.raises(ParameterError, match="bars"):
        rcwa.Layer(1e-7, 1.0, (rcwa.Bar(0.1, 0.5, 3.5), rcwa.Bar(0.4, 0.6, 3.5)))
    with pytest.raises(ParameterError, match="bar"):
        rcwa.Bar(0.6, 0.5, 3.5)
    with pytest.raises(ParameterError, match="period"):
        rcwa.Grating(1e-6, 0.0, (film,))
    with pytest.raises(ParameterError, match="layer thickness"):
        rcwa.Layer(-1e-7, 1.45)
    with pytest.raises(ParameterError, match="theta"):
        rcwa.orders(rcwa.Grating(1e-6, 2e-6, (film,)), 1.6)
    g = rcwa.GRATINGS["bigrating"]
    assert rcwa.Grating.from_dict(g.to_dict()) == g and g.key() == rcwa.Grating.from_dict(g.to_dict()).key()
    assert g.mirrored().mirrored().key() == g.key() != g.mirrored().key()


# ---- the table as both solvers' slice load -------------------------------------------------------------
def coarse_grating_file(tmp_path, polarization="TE"):
    """The bigrating's table at FAST harmonics on 7.5° nodes, written to a file (a second or two of RCWA)."""
    g = rcwa.GRATINGS["bigrating"]
    table = optics.grating_table(
        g, polarization, harmonics=FAST, step=math.radians(7.5), cache_dir=tmp_path, tolerance=0.0, grade=0
    )
    return str(table.save(tmp_path / "bigrating.npz"))


def test_case_reads_and_validates_its_table(tmp_path):
    path = coarse_grating_file(tmp_path)
    p = SailParameters(optics=path, optics_layout="mirrored-halves")
    table = p.optical_table()
    assert table.kind == "grating" and p.optical_table() is table  # read once
    assert p.nominal_acceleration == pytest.approx(table.nominal_acceleration(p), rel=1e-15)
    assert p.nominal_acceleration < SailParameters().nominal_acceleration  # c_n(0) ≈ 1.3 < 2
    assert SailParameters.from_dict(p.to_dict()) == p
    assert "optics" not in SailParameters().to_dict()  # records of cases without a table are unchanged
    assert list(optics.slice_flags(p.replace(n=5))) == [0, 0, 0, 1, 1]
    (tmp_path / "junk.npz").write_bytes(b"not a table")
    for bad, name in [
        (dict(optics=str(tmp_path / "missing.npz")), "optics="),
        (dict(optics=str(tmp_path / "junk.npz")), "junk.npz"),
        (dict(optics=path, reflectivity=0.9), "reflectivity="),
        (dict(optics=path, optics_layout="sideways"), "optics_layout="),
        (dict(optics_layout="mirrored-halves"), "optics_layout="),
        (dict(optics=""), "optics="),
    ]:
        with pytest.raises(ParameterError, match=name) as info:
            SailParameters(**bad)
        assert "\n" not in str(info.value)


@pytest.mark.parametrize("model", ["torsion", "tnt"])
def test_mirror_table_load_is_eq11_to_the_bit_in_both_solvers(model):
    """The built-in mirror through the table path gives the Eq. (11) path's loads bit for bit (uniform beam)."""
    from lightsail_mbs.solvers.exudyn.tree import ChainLayout, generalized_force
    from lightsail_mbs.solvers.reduced.dynamics import ChainDynamics
    from lightsail_mbs.solvers.reduced.kinematics import ChainModel

    p = SailParameters(model=model, n=13, tension=1e-4 if model == "tnt" else 0.0, youngs_modulus=1e11)
    table = p.replace(optics="mirror")
    layout = ChainLayout.of(p)
    reduced, reduced_table = (ChainDynamics(ChainModel.from_params(c)) for c in (p, table))
    for _ in range(5):
        q = rng.normal(0, 0.3, layout.size)
        assert np.array_equal(generalized_force(p, layout)(q), generalized_force(table, layout)(q))
        y = rng.normal(0, 0.3, 2 * reduced.model.dof)
        assert np.array_equal(reduced.rhs(0.0, y), reduced_table.rhs(0.0, y))


@pytest.mark.parametrize("solver", ["reduced", "exudyn"])
def test_mirror_table_run_reproduces_eq11(solver):
    from lightsail_mbs import RunSettings, solve

    p = SailParameters(n=12, youngs_modulus=4.5e12, defect_amplitude=1e-4)
    settings = RunSettings(t_final=0.05, stop_at_failure=False)
    a, b = solve(p, solver, settings), solve(p.replace(optics="mirror"), solver, settings)
    assert b.params.optics == "mirror" and a.error is None and b.error is None
    for name in ("x", "y", "theta"):
        u, v = getattr(a, name), getattr(b, name)
        assert np.max(np.abs(u - v)) <= 1e-12 * np.max(np.abs(u))


def test_both_solvers_agree_on_a_grating_table_run(tmp_path):
    """Bigrating halves turned over (each half pushes outward): the two solvers' angles agree while the
    load is a grating's, not a mirror's (its c_n has a first-order slope term)."""
    from lightsail_mbs import RunSettings, solve

    p = SailParameters(
        n=10, youngs_modulus=4.5e13, optics=coarse_grating_file(tmp_path), optics_layout="mirrored-halves"
    )
    settings = RunSettings(t_final=0.01, output_interval=1e-3, stop_at_failure=False)
    exudyn = solve(p, "exudyn", settings, step_size=2e-6)
    reduced = solve(p, "reduced", settings, rtol=1e-10)
    mirror = solve(p.replace(optics="mirror", optics_layout="uniform"), "reduced", settings, rtol=1e-10)
    scale = np.max(np.abs(reduced.theta - reduced.theta[0]))
    assert np.max(np.abs(mirror.theta - reduced.theta)) > 0.1 * scale  # the grating moves the sail differently
    assert np.max(np.abs(exudyn.theta - reduced.theta)) < 1e-6 * scale  # measured 2.8e-9
    np.testing.assert_allclose(exudyn.x, reduced.x, rtol=0, atol=1e-9)


def test_net_force_form_cancels_the_frame_force_analytically(tmp_path):
    """packed_net_force: for the mirror, the analytic net force of Eq. (11) (the formula written out here) to the
    bit; for a grating table, radiation minus c_n(0) Ī A/c to round-off of f₀; exactly zero on a flat slice in
    the mean intensity, where the plain sum leaves round-off."""
    p = SailParameters(intensity=3e9, beam_waist=0.8)
    area_c = p.slice_length * p.width / optics.SPEED_OF_LIGHT
    mirror = optics.mirror().packed()
    for theta in rng.uniform(-1.2, 1.2, 50):
        c, s, local = math.cos(theta), math.sin(theta), rng.uniform(0.2, 1.0) * p.intensity
        push = local * area_c
        half = math.sin(0.5 * theta)
        omc = 2.0 * half * half
        expected_x = -push * 2.0 * c * c * s
        expected_y = -push * (2.0 * omc * (1.0 + c + c * c) + 0.0 * omc) + 2.0 * area_c * (local - p.mean_intensity)
        got = optics.packed_net_force(mirror, local, p.mean_intensity, area_c, c, s, theta, False, 2.0)
        assert got == (expected_x, expected_y)
    table = optics.read_table(coarse_grating_file(tmp_path))
    packed, q0 = table.packed(), table.normal_at_zero
    f0 = 2 * p.intensity * area_c
    for theta in rng.uniform(-0.5, 0.5, 50):
        for mirrored in (False, True):
            c, s = math.cos(theta), math.sin(theta)
            local = rng.uniform(0.2, 1.0) * p.intensity
            fx, fy = optics.packed_force(packed, local * area_c, theta, mirrored)
            nx, ny = optics.packed_net_force(packed, local, p.mean_intensity, area_c, c, s, theta, mirrored, q0)
            assert abs(nx - fx) < 1e-15 * f0 and abs(ny - (fy - q0 * p.mean_intensity * area_c)) < 1e-15 * f0
    mean = p.mean_intensity
    assert optics.packed_net_force(packed, mean, mean, area_c, 1.0, 0.0, 0.0, False, q0)[1] == 0.0
