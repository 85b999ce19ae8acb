"""What a tuning records in its model: the reference described, the loops tuned on, where mu came from."""

from microslip import Cylinder, MDRModel, Sphere, loops, mdr, tune, tune_on_loops
from microslip.loops.synthetic import dataset_files
from microslip.reference.profiles import RoundedPunch
from microslip.tuning._record import describe_reference


def test_tune_on_loops_records_the_files_the_normal_law_and_the_fitted_mu():
    files = dataset_files()
    records = [loops.analyse(loops.read(p)) for p in files]
    result = tune_on_loops(records, Cylinder(10e-3, 5e-3, 200e9, 0.3, law="palmgren"), elements=6)
    p = result.model.provenance
    assert p.kind == "MeasuredContact"
    assert sorted(p.loops) == sorted(f.name for f in files)  # each measured file, by its name
    assert p.reference["normal"] == {"kind": "Cylinder", "length": 10e-3, "radius": 5e-3, "E": 200e9, "nu": 0.3,
                                     "mu": None, "law": "palmgren"}
    assert p.mu_source == "fitted from the slip forces" and p.reference["mu"] == result.reference.mu
    assert p.normal_load == result.reference.normal_load and len(p.points_t) == 6
    assert "tuned on a MeasuredContact" in p.describe() and "normal: Cylinder (palmgren law)" in p.describe()


def test_a_reference_built_on_an_mdr_array_names_its_profile():
    punch = describe_reference(mdr(Sphere.paper(), max_load=37.5, elements=50,
                                   profile=RoundedPunch(1e-3, 5e-3)).as_reference())
    assert punch["model"]["profile"] == {"kind": "RoundedPunch", "flat_radius": 1e-3, "edge_radius": 5e-3}
    exact = mdr(Sphere.paper(), max_load=37.5, elements=200)
    d = describe_reference(exact.as_reference())
    assert d["kind"] == "MDRContact" and d["model"]["kind"] == "MDRModel" and d["model"]["max_load"] == 37.5
    assert "kt" not in d["model"]  # arrays are left out: the file keeps the points, not the data
    model = tune(exact.as_reference(), 30.0, elements=3)
    assert model.provenance.reference == d and not isinstance(model, MDRModel)
