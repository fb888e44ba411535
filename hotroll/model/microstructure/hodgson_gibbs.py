"""Hodgson and Gibbs' C-Mn set (issue 33; docs/theory.md 1g).

P.D. Hodgson, R.K. Gibbs: A mathematical model to predict the mechanical properties of hot
rolled C-Mn and microalloyed steels, ISIJ International 32 (1992) 1329-1338. The constants as
pyroll-jmak-recrystallization 3.0.0 quotes them (``material_data.py``, C-Mn; its comment also
cites Maccagno, Jonas and Hodgson, ISIJ Int. 36 (1996) 720), except the SRX half time's grain
exponent: 2 here, as Hodgson and Gibbs write it (PyRolL ships 1, recrystallising 100x faster at
d0 = 100 um; docs/theory.md 1g says where each constant was read).
"""
from hotroll.model.microstructure.base import GrowthLaw, PowerTerm, RecrystallisationSet
from hotroll.model.microstructure.registry import register

HODGSON_GIBBS = register(RecrystallisationSet(
    name="hodgson_gibbs_cmn",
    description="C-Mn steel, Hodgson and Gibbs (1992)",
    source="P.D. Hodgson, R.K. Gibbs, ISIJ International 32 (1992) 1329-1338",
    q_def=300e3,
    critical=PowerTerm(5.6e-4, grain=0.3, zener=0.17),
    srx_time=PowerTerm(2.3e-15, strain=-2.5, grain=2.0, q=230e3),
    srx_exponent=1.0,
    srx_grain=PowerTerm(343.0, strain=-0.5, grain=0.4, q=-45e3),
    mdrx_time=PowerTerm(1.1, zener=-0.8, q=230e3),
    mdrx_exponent=1.5,
    mdrx_grain=PowerTerm(2.6e4, zener=-0.23),
    growth=GrowthLaw(exponent=7.0, K=1.45e27, q=400e3),
    steels=("S355J2", "C20"),
    temperature_range=(1073.15, 1573.15),
    validity="0.06-0.25 %C, 0.3-1.7 %Mn, d0 40-150 um, 850-1000 degC, strain 0.3-2.4, "
             "strain rate 0.03-3 1/s (as PyRolL's comment quotes it); rolling rates of 10-200 "
             "1/s are an extrapolation",
))
