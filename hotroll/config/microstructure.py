"""A schedule's [microstructure] section (issue 33): the recrystallisation kinetics between
passes (``model/microstructure``), validated before anything runs.

    [microstructure]
    model = "hodgson_gibbs_cmn"     # a set of model/microstructure; "none": each transport's
                                    # strain_retained
    grain_size = 100e-6             # m, the austenite grain size entering the first pass
    retained_share = 1.0            # lambda: eps_next = eps_pass + lambda (1 - X) eps_exit
"""
from __future__ import annotations

from pydantic import model_validator

from hotroll.config.base import PosFloat, Problems, Section, field
from hotroll.model.microstructure import SETS, get_set, sets_for

#: The grain sizes the kinetics accept (m): 1 um to 2 mm.
GRAIN_RANGE = (1e-6, 2e-3)


class MicrostructureConfig(Section):
    model: str = field("none", "recrystallisation parameter set between the passes; none keeps "
                       "each transport's strain_retained", "",
                       '"none" or ' + ", ".join(f'"{n}"' for n in SETS))
    grain_size: PosFloat | None = field(
        None, "austenite grain size entering the first pass (needed with a model)", "m",
        f"in [{GRAIN_RANGE[0]:g}, {GRAIN_RANGE[1]:g}]")
    retained_share: float = field(
        1.0, "share lambda of the unrecrystallised strain carried into the next pass (Beynon "
        "and Sellars: 1; models with recovery: about 0.5)", "", "in [0, 1]", ge=0, le=1)

    @model_validator(mode="after")
    def _check(self) -> MicrostructureConfig:
        problems = []
        if self.model != "none" and self.model not in SETS:
            problems.append(f"microstructure.model: unknown set {self.model!r} (allowed: none, "
                            f"{', '.join(SETS)})")
        elif self.model != "none":
            d = self.grain_size
            if d is None:
                problems.append("microstructure.grain_size: needed with a model (m, the "
                                "austenite grain size entering the first pass)")
            elif not GRAIN_RANGE[0] <= d <= GRAIN_RANGE[1]:
                problems.append(f"microstructure.grain_size: must be in [{GRAIN_RANGE[0]:g}, "
                                f"{GRAIN_RANGE[1]:g}] m, got {d:g} m")
        if problems:
            raise Problems(problems)
        return self

    @property
    def kinetics(self):
        """The parameter set, or None."""
        return None if self.model == "none" else get_set(self.model)


def check_schedule(mic: MicrostructureConfig, grade: str | None, temperatures,
                   transports) -> list[str]:
    """The schedule-wide problems of a kinetics model: the material's grade without the set,
    an entry temperature outside its range, a transport's strain_retained given with it
    (``transports``: (k, TransportConfig or None))."""
    s = mic.kinetics
    if s is None:
        return []
    problems = []
    if grade is not None and s.name not in sets_for(grade):
        problems.append(f"microstructure.model: the set {s.name!r} is for {', '.join(s.steels)}; "
                        f"material.grade {grade!r} has none (use microstructure.model = "
                        f"\"none\" and each transport's strain_retained)")
    lo, hi = s.temperature_range
    bad = [T for T in temperatures if not lo <= T <= hi]
    if bad:
        problems.append(f"strip.temperature: {min(bad):.2f}..{max(bad):.2f} K outside the "
                        f"set {s.name!r}'s range {lo:.2f}..{hi:.2f} K (austenite)")
    for k, tr in transports:
        if tr is not None and "strain_retained" in tr.model_fields_set:
            problems.append(f"pass[{k}].transport.strain_retained: not with microstructure."
                            f"model (the kinetics give the retained strain)")
    return problems
