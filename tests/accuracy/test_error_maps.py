"""The accuracy error maps: words and units on the axes, numbers readable at report width, mirror phases merged."""

import dataclasses

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pytest  # noqa: E402

from microslip import Sphere, accuracy, mdr, paths, tune  # noqa: E402
from microslip.common.report import REPORT_WIDTH  # noqa: E402

SPHERE = Sphere.paper()
METRICS = ("energy_error", "force_difference")


@pytest.fixture(scope="module")
def report():
    family = paths.default_family(SPHERE, 37.5, ratios=(0.0, 0.6), phases_deg=(0.0, 90.0, 180.0),
                                  amplitudes=(0.5, 2.0), levels=(0.55, 1.0), steps_per_cycle=120)
    return accuracy(tune(SPHERE, 37.5, elements=4), mdr(SPHERE, max_load=37.5, elements=800), family)


def _mirror_pairs(rep):
    """Index pairs (phi = 0°, phi = 180°) of paths equal in every other parameter, with N_a > 0."""
    key = lambda k: tuple(rep.paths[k].params[n] for n in ("ratio", "level", "amplitude"))  # noqa: E731
    phase = rep.param("phase_deg")
    at_180 = {key(k): k for k in np.flatnonzero(phase == 180.0)}
    return [(k, at_180[key(k)]) for k in np.flatnonzero((phase == 0.0) & (rep.param("ratio") > 0))]


def test_mirror_phases_have_equal_errors_and_share_a_panel(report):
    pairs = _mirror_pairs(report)
    assert len(pairs) == 4
    for name in METRICS:  # the data first: phi = 0° and 180° are mirror images (t -> -t half a cycle later)
        v = report.metric(name)
        for a, b in pairs:
            # equal to round-off of the two marches (measured up to 3.4e-13 relative on the full family)
            assert v[b] == pytest.approx(v[a], rel=1e-9, nan_ok=True)
    _, _, panels = report.error_maps(METRICS)
    assert [phases for phases, _ in panels] == [(0.0, 180.0), (90.0,)]
    fig = report.plot()
    titles = [ax.get_title() for ax in fig.axes if ax.get_title()]
    assert titles == ["worst energy error (%), φ = 0° and 180°", "worst energy error (%), φ = 90°",
                      "worst force difference (%), φ = 0° and 180°", "worst force difference (%), φ = 90°"]
    plt.close(fig)


def test_phases_with_different_errors_keep_their_own_panels(report):
    _, b = _mirror_pairs(report)[0]
    changed = report.force_difference.copy()
    changed[b] *= 3.0  # one phi = 180° path now differs from its mirror image
    other = dataclasses.replace(report, force_difference=changed)
    _, _, panels = other.error_maps(METRICS)
    assert [phases for phases, _ in panels] == [(0.0,), (90.0,), (180.0,)]
    fig = other.plot()
    assert sum("φ = 180°" in ax.get_title() for ax in fig.axes) == 2
    plt.close(fig)


def test_axes_say_in_words_what_they_show(report):
    fig = report.plot()
    maps = [ax for ax in fig.axes if ax.get_title()]
    for ax in maps:
        assert "tangential amplitude / gross-slip displacement" in ax.get_xlabel()
        assert "load amplitude" in ax.get_ylabel() and "ratio N_a / N_m" in ax.get_ylabel()
    bars = [ax for ax in fig.axes if not ax.get_title()]
    assert [ax.get_ylabel() for ax in bars] == ["worst energy error (%)", "worst force difference (%)"]
    plt.close(fig)


def test_cell_numbers_are_readable_at_report_width(report):
    fig = report.plot()
    scale = min(1.0, REPORT_WIDTH / fig.get_size_inches()[0])  # the HTML report shrinks wider figures
    for ax in (ax for ax in fig.axes if ax.get_title()):
        im = ax.get_images()[0]
        texts = ax.texts
        assert texts and len(texts) == int(np.isfinite(im.get_array()).sum())
        for t in texts:
            # 7 pt on the page at least, and no more than 3 significant digits
            assert t.get_fontsize() * scale >= 7.0
            assert len(t.get_text().replace(".", "").lstrip("0")) <= 3
            # contrast with the cell (WCAG ratio; 4.5 is asked of body text)
            x, y = t.get_position()
            cell = im.cmap(im.norm(im.get_array()[int(round(y)), int(round(x))]))
            assert _contrast(cell, matplotlib.colors.to_rgba(t.get_color())) >= 4.5
    plt.close(fig)


def _contrast(a, b) -> float:
    def luminance(c):
        r, g, b = (v / 12.92 if v <= 0.04045 else ((v + 0.055) / 1.055) ** 2.4 for v in c[:3])
        return 0.2126 * r + 0.7152 * g + 0.0722 * b

    la, lb = sorted((luminance(a), luminance(b)))
    return (lb + 0.05) / (la + 0.05)
