"""compare.png names its case (workflows/compare.py): the figure of FE against slab theory is
drawn with the title "<case>: contact pressure and shear, FE vs slab" (the drawing spied on,
the pass of tests/workflows/test_compare.py solved: about 2 s)."""
from __future__ import annotations

import hotroll.workflows.compare as compare
from tests.workflows.test_compare import _case


def test_the_compare_figure_is_titled_with_the_case(tmp_path, monkeypatch):
    titles = []
    monkeypatch.setattr(compare, "plot_compare_profiles",
                        lambda *args, title=None, **kw: titles.append(title))
    compare.run_compare(_case(), tmp_path)
    assert titles == ["thin_coulomb: contact pressure and shear, FE vs slab"]
