"""tvf.convergence: catalog ids and a Python builder through the convergence study against the
unit sphere's exact spectrum; the P1 / Crouzeix–Raviart builder converges at order 2 like the
catalog's conforming entry, and bad requests are refused with a reason."""

import pytest
import scipy.sparse as sp

import tvf
from reference import p1_cr_complex


def p1_cr_builder(V, F):
    ref = p1_cr_complex(V, F)
    return dict(d0=ref["d0"], d1=ref["d1"], M0=ref["M0"], M1=ref["M1"], M2=sp.diags(ref["M2"]),
                sampling="face-frames")


def test_a_builder_converges_like_the_catalog_entry():
    result = tvf.convergence(["conforming-barycentric", ("mine", p1_cr_builder)],
                             surfaces=("sphere",), levels=(2, 3, 4), eigenvalues=8)
    rows = result["rows"]
    assert len(rows) == 2 * 3
    assert {r["discretization"] for r in rows} == {"conforming-barycentric", "mine"}
    catalog = [r for r in rows if r["discretization"] == "conforming-barycentric"]
    mine = [r for r in rows if r["discretization"] == "mine"]
    # The reference builder assembles the same matrices as the catalog entry.
    for a, b in zip(catalog, mine):
        assert a["faces"] == b["faces"]
        assert abs(a["integrable_error"] - b["integrable_error"]) < 1e-9
        assert abs(a["cointegrable_error"] - b["cointegrable_error"]) < 1e-9
    orders = result["orders"]
    assert len(orders) == 2 * 2
    for o in orders:
        assert o["family"] in ("integrable", "cointegrable")
        assert abs(o["order"] - 2.0) <= 0.2, o


def test_the_hemisphere_runs_catalog_entries_under_both_conditions():
    result = tvf.convergence(["nonconforming-barycentric"], levels=(1, 2), eigenvalues=4)
    surfaces = {(r["surface"], r["boundary"]) for r in result["rows"]}
    assert surfaces == {("sphere", None), ("hemisphere", "tangential"), ("hemisphere", "normal")}
    errors = [r["integrable_error"] for r in result["rows"] if r["boundary"] == "normal"]
    assert errors[1] < errors[0]


def test_bad_requests_are_refused_with_a_reason():
    with pytest.raises(tvf.TvfError, match="closed meshes only"):
        tvf.convergence([p1_cr_builder], levels=(1,), eigenvalues=2)
    with pytest.raises(tvf.TvfError, match="unknown discretization"):
        tvf.convergence(["nope"], levels=(1,))
    with pytest.raises(tvf.TvfError, match="not a surface"):
        tvf.convergence(["conforming-barycentric"], surfaces=("torus",), levels=(1,))
    with pytest.raises(ValueError, match="ascending"):
        tvf.convergence(["conforming-barycentric"], levels=(3, 1))
    with pytest.raises(ValueError, match="names must differ"):
        tvf.convergence(["conforming-barycentric", "conforming-barycentric"])


def test_ctrl_c_in_a_builder_is_not_turned_into_a_tvf_error():
    def interrupted(V, F):
        raise KeyboardInterrupt

    with pytest.raises(KeyboardInterrupt):
        tvf.convergence([interrupted], surfaces=("sphere",), levels=(1, 2), eigenvalues=2)


def test_levels_and_eigenvalues_must_be_integers():
    with pytest.raises(TypeError, match="must be an integer"):
        tvf.convergence(["conforming-barycentric"], levels=(1, 2.5))
    with pytest.raises(TypeError, match="eigenvalues must be an integer"):
        tvf.convergence(["conforming-barycentric"], levels=(1, 2), eigenvalues=3.5)
