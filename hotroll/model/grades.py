"""Published Hensel-Spittel parameter sets, selectable by name.

    >>> from hotroll.model.grades import get_grade, list_grades
    >>> g = get_grade("S355J2")
    >>> law = g.law()                       # HenselSpittel, A in Pa, T in K at the interface
    >>> law.sigma(0.3, 10.0, 1373.15)       # Pa

Every set carries its source (author, title, year, page/table when known) and *where it was read*
for this library.  Only sets whose numbers were read in an accessible text are included; nothing is
reconstructed from memory.  What was not found is said so (``validity`` entries None).

All sets are in Spittel's original form (no strain / strain-rate offsets), T in deg C inside the
formula, A converted from the published MPa to Pa.  The pyroll-freiberg-flow-stress package (where
the steel sets were read) evaluates the same coefficients at (eps + 0.1, edot + 0.1); its value at
(eps, edot, T) is ``get_grade(name).law().sigma(eps + 0.1, edot + 0.1, T)`` (see
``tests/model/test_flow_stress.py``).  We keep the original form because the Landolt-Boernstein formula
has no offsets (as also printed in the pyroll team's own paper table,
pyroll-project/publication-weiner-variation, weiner_variation/tbl/flow_stress.tex).

Densities are room-temperature values (kg/m^3) with their own source; the hot density is lower by
the thermal expansion (a few percent).
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import Mapping, Optional, Tuple

from hotroll.model.flow_stress import HenselSpittel, ValidityRange

_PYROLL = ("pyroll-freiberg-flow-stress 3.0.1.post1 (PyPI wheel, file "
           "pyroll/freiberg_flow_stress/materials.py; same numbers in "
           "github.com/pyroll-project/pyroll-freiberg-flow-stress, commit 2d44406)")
_LB_STEEL = ("M. Spittel, T. Spittel: Metal Forming Data of Ferrous Alloys - deformation "
             "behaviour, Landolt-Boernstein, New Series, Group VIII Advanced Materials and "
             "Technologies, Vol. 2C1, H. Warlimont (ed.), Springer, Berlin Heidelberg, 2009, "
             "ISBN 978-3-540-44758-0")


@dataclass(frozen=True)
class GradeData:
    """One published parameter set.

    ``law_params``: HenselSpittel keyword arguments, A in Pa, m_i as published (T in deg C).
    ``validity_celsius``: (strain, strain_rate [1/s], temperature [deg C]) ranges as published, each
    None when it could not be read.  ``density``: kg/m^3 at room temperature, or None.
    """

    name: str
    description: str
    law_params: Mapping[str, float]
    validity_celsius: Tuple[Optional[Tuple[float, float]], Optional[Tuple[float, float]],
                            Optional[Tuple[float, float]]]
    density: Optional[float]
    source: str
    read_at: str
    density_source: str = ""
    aliases: Tuple[str, ...] = ()
    notes: str = ""
    kind: str = "HenselSpittel"
    #: the family whose elastic moduli E(T) the strip takes (model/strip_elasticity.py)
    family: str = "steel"

    @property
    def validity(self) -> ValidityRange:
        s, r, t = self.validity_celsius
        return ValidityRange.from_celsius(strain=s, strain_rate=r, temperature_c=t)

    def law(self, **kwargs) -> HenselSpittel:
        """The HenselSpittel law of this set; kwargs (strain_min, eps0, ...) are passed on."""
        kwargs.setdefault("validity", self.validity)
        kwargs.setdefault("name", self.name)
        return HenselSpittel(**dict(self.law_params), **kwargs)

    def describe(self) -> dict:
        return {
            "name": self.name,
            "description": self.description,
            "law": self.kind,
            "law_params (A in Pa, T in degC)": dict(self.law_params),
            "validity (strain, strain_rate 1/s, T degC)": self.validity_celsius,
            "density_kg_per_m3": self.density,
            "density_source": self.density_source,
            "source": self.source,
            "read_at": self.read_at,
            "notes": self.notes,
            "elastic family": self.family,
        }


_GRADES = (
    GradeData(
        name="S355J2",
        description="structural steel S355J2 (1.0577), hot forming",
        law_params=dict(A=2852.66e6, m1=-0.00244, m2=0.41934, m4=0.00088, m5=-0.00149,
                        m7=0.12169, m8=0.000127),
        validity_celsius=(None, None, None),
        density=7840.0,
        density_source=("7.84 g/cm^3 at 20 degC for EN 10025-2 S355J0 (+N), the sister grade "
                        "of the same chemistry, structural-steels.com/"
                        "en-10025-2-grade-s355j0-normalized-c3d7qq.html (no S355J2 density page "
                        "was found)"),
        source=_LB_STEEL + "; datasheet S355J2 (page not read)",
        read_at=_PYROLL + ", hook _s355j2, whose docstring cites the Landolt-Boernstein volume",
        aliases=("1.0577", "S355"),
        notes=("m3 = m9 = 0: the rate exponent is m8*T_C alone (0.127 at 1000 degC). Validity "
               "ranges not found in a readable text; strain floor defaults to 0.03."),
    ),
    GradeData(
        name="C45",
        description="unalloyed quenched-and-tempered steel C45 (1.0503), hot forming",
        law_params=dict(A=3268.49e6, m1=-0.00267855, m2=0.34446, m4=0.000551814, m5=-0.00132042,
                        m7=0.0166334, m8=0.000149907),
        validity_celsius=(None, None, None),
        density=7850.0,
        density_source=("7.85 g/cm^3, 'physical properties at ambient temperature', datasheet "
                        "1.0503/C45, www.zhonganzt.com/1.0503-s45c-g10450-aisi-1045/"),
        source=(_LB_STEEL + "; 'Steel symbol/number: C45/1.0503', pp. 210-215, "
                "doi:10.1007/978-3-540-44760-3_26 (pages as cited in "
                "pyroll-project/publication-weiner-variation, weiner_variation/refs.bib; "
                "the datasheet itself was not read)"),
        read_at=(_PYROLL + ", hook _c45; identical set in the package's tests/test_hook.py"),
        aliases=("1.0503",),
        notes="m3 = m9 = 0. Validity ranges not found in a readable text.",
    ),
    GradeData(
        name="C20",
        description="unalloyed steel C20/C22, hot forming",
        law_params=dict(A=3304.39e6, m1=-0.00281, m2=0.34766, m4=0.00002, m5=-0.00130,
                        m7=0.07632, m8=0.000148),
        validity_celsius=(None, None, None),
        density=None,
        density_source="not looked up",
        source=_LB_STEEL + "; datasheet C20 (page not read)",
        read_at=_PYROLL + ", hook _c20 (materials 'c20', 'c22')",
        aliases=("C22",),
        notes="m3 = m9 = 0. Validity ranges not found in a readable text.",
    ),
    GradeData(
        name="Al99.5",
        description="commercially pure aluminium Al99.5 (EN AW-1050A, 3.0255), hot forming, "
                    "deformed (not annealed) initial state",
        law_params=dict(A=367.651e6, m1=-0.00463, m2=0.32911, m4=0.00167, m5=-0.00207,
                        m7=0.16592, m8=0.000241),
        validity_celsius=((0.03, 1.50), (0.01, 500.0), (250.0, 550.0)),
        density=2705.0,
        density_source=("2.705 kg/dm^3 at 20 degC, temper O, aluminium-guide.com/1050a-aluminium-"
                        "grade"),
        source=("M. Spittel, T. Spittel: Metal Forming Data of Non-Ferrous Alloys - Light "
                "Metals, Landolt-Boernstein, New Series, Group VIII, Vol. 2C2, H. Warlimont (ed.), "
                "Springer, ISBN 978-3-642-13863-8; datasheet Al99.5, hot forming, deformed state "
                "('pages 1-2' of the datasheet per the transcription below; the handbook itself "
                "was not read)"),
        read_at=("two public Python files on GitHub found with the code search (repository "
                 "name not shown by the index): 'al995_hot_deformed.py' (index id 29919702997) "
                 "and a rolling force script (index id 29260785978) giving the same numbers and "
                 "ranges; the second evaluates (1+phi)^(m5*theta) and phidot^(m8*theta) as in "
                 "Spittel's form, the first drops the theta factors (a transcription slip: "
                 "m8 = 0.000241 alone would make the law rate-insensitive)"),
        aliases=("AL995", "EN AW-1050A", "AA1050A", "1050A", "3.0255"),
        family="aluminium",
        notes=("The only aluminium Hensel-Spittel set found in a readable text. Rate exponent "
               "m8*T_C = 0.060 at 250 degC .. 0.133 at 550 degC."),
    ),
)

_INDEX = {}
for _g in _GRADES:
    for _key in (_g.name, *_g.aliases):
        _INDEX[_key.replace(" ", "").lower()] = _g


def list_grades() -> list[str]:
    """Names of the available grades (aliases are accepted by :func:`get_grade` too)."""
    return [g.name for g in _GRADES]


def get_grade(name: str) -> GradeData:
    """The grade named ``name`` (case- and space-insensitive; aliases such as '1.0577' work)."""
    try:
        return _INDEX[str(name).replace(" ", "").lower()]
    except KeyError:
        raise KeyError(f"unknown grade {name!r}; available: {', '.join(list_grades())}") from None
