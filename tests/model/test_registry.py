"""The one registry of laws (hotroll/model/registry.py) and its entry points: a real distribution
(a dist-info directory with entry_points.txt on sys.path, as pip installs one) adds a friction
law that a case selects and ``hotroll validate`` accepts; a name twice, an unknown name and a
broken plugin are refused with their names."""
from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest

from hotroll.model.flow_stress import LAWS
from hotroll.model.friction import FRICTION_LAWS, FrictionSpec
from hotroll.model.heat_transfer import HEAT_TRANSFER_LAWS
from hotroll.model.microstructure import SETS
from hotroll.model.registry import PluginError, Registry, UnknownName

ROOT = Path(__file__).resolve().parents[2]

#: A friction law of another package: tau = share k, written as hotroll's own laws are.
LAW_MODULE = '''
from dataclasses import dataclass

from hotroll.model.friction import FrictionLaw, FrictionSpec
from hotroll.model.parameters import Parameter


@dataclass(frozen=True)
class ShareFriction(FrictionLaw):
    share: float = 0.5
    name = "shear_share"
    uses_k = True

    def limit(self, *, pressure=None, k=None):
        return self.share * k

    def limit_partials(self, *, pressure=None, k=None):
        return 0.0, self.share


SPEC = FrictionSpec(
    name="shear_share", summary="tau = share k", source="a test's plugin",
    parameters=(Parameter("share", "share of k", "", "in (0, 1]", gt=0.0, le=1.0),),
    build=lambda p, v_reg, m: ShareFriction(v_reg, share=p["share"]), v_reg_fraction=1e-3)
'''


def install(site: Path, dist: str, group: str, entries: dict[str, str],
            modules: dict[str, str]) -> Path:
    """A distribution ``dist`` 1.0 in ``site``: its modules and its entry points of ``group``."""
    info = site / f"{dist.replace('-', '_')}-1.0.dist-info"
    info.mkdir(parents=True)
    (info / "METADATA").write_text(f"Metadata-Version: 2.1\nName: {dist}\nVersion: 1.0\n")
    (info / "entry_points.txt").write_text(
        f"[{group}]\n" + "".join(f"{k} = {v}\n" for k, v in entries.items()))
    for name, text in modules.items():
        (site / f"{name}.py").write_text(text)
    return site


def fresh(kind: str = "test_friction") -> Registry[FrictionSpec]:
    """A friction registry of its own (group ``hotroll.test_friction``: the suite's registries
    never see the test's plugins) with hotroll's three laws."""
    reg = Registry(kind, "friction law", FrictionSpec)
    for name, spec in FRICTION_LAWS.items():
        reg.register(name, spec)
    return reg


def test_a_plugin_law_is_loaded_on_the_first_lookup_after_hotrolls_own(tmp_path, monkeypatch):
    site = install(tmp_path, "fake-share", "hotroll.test_friction",
                   {"shear_share": "fake_share_law:SPEC"}, {"fake_share_law": LAW_MODULE})
    monkeypatch.syspath_prepend(str(site))
    reg = fresh()
    assert "fake_share_law" not in sys.modules          # nothing loaded before a lookup
    assert reg.names() == ["viscoplastic", "coulomb", "tresca", "shear_share"]
    spec = reg.get("shear_share")
    assert spec is sys.modules["fake_share_law"].SPEC
    law = spec.build({"share": 0.4}, 1e-3, 0.2)
    assert law.limit(k=2.0) == pytest.approx(0.8)       # the plugin's law, built as hotroll's
    assert reg.names() == ["viscoplastic", "coulomb", "tresca", "shear_share"]   # loaded once


def test_a_plugin_module_that_registers_itself_is_registered_once(tmp_path, monkeypatch):
    """A module written as hotroll's own (``SPEC = REG.register(...)`` on import) and named by
    an entry point too: one law, no "registered twice"."""
    monkeypatch.setattr(sys.modules[__name__], "SELF_REGISTERING", fresh(), raising=False)
    text = LAW_MODULE + f"\nfrom {__name__} import SELF_REGISTERING\n" \
                        "SELF_REGISTERING.register(SPEC.name, SPEC)\n"
    site = install(tmp_path, "fake-self", "hotroll.test_friction",
                   {"shear_share": "fake_self_law:SPEC"}, {"fake_self_law": text})
    monkeypatch.syspath_prepend(str(site))
    assert SELF_REGISTERING.names()[-1] == "shear_share"  # noqa: F821 - set above
    assert len(SELF_REGISTERING) == 4                       # noqa: F821


def test_a_name_twice_is_refused_in_hotroll_and_from_a_plugin(tmp_path, monkeypatch):
    reg = fresh()
    with pytest.raises(ValueError, match="friction law 'coulomb' registered twice"):
        reg.register("coulomb", FRICTION_LAWS["coulomb"])
    text = LAW_MODULE.replace('name="shear_share"', 'name="coulomb"')
    site = install(tmp_path, "fake-twice", "hotroll.test_friction",
                   {"coulomb": "fake_twice_law:SPEC"}, {"fake_twice_law": text})
    monkeypatch.syspath_prepend(str(site))
    with pytest.raises(PluginError) as e:
        reg.names()
    assert str(e.value) == (
        "the hotroll.test_friction entry point coulomb = 'fake_twice_law:SPEC' (distribution "
        "fake-twice 1.0) is no usable friction law: ValueError: friction law 'coulomb' "
        "registered twice")
    assert reg._items["coulomb"] is FRICTION_LAWS["coulomb"]     # hotroll's own law kept


def test_an_unknown_name_is_refused_naming_the_known_ones():
    with pytest.raises(UnknownName) as e:
        FRICTION_LAWS.get("cuolomb")
    assert str(e.value) == "unknown friction law 'cuolomb' (allowed: viscoplastic, coulomb, tresca)"
    with pytest.raises(KeyError, match="unknown flow-stress law 'x' .allowed: norton-hoff, "):
        LAWS["x"]
    assert "cuolomb" not in FRICTION_LAWS and FRICTION_LAWS.get("cuolomb", None) is None


@pytest.mark.parametrize("module, value, error", [
    ("import fake_no_such_module\n", "fake_broken_a:SPEC",
     "ModuleNotFoundError: No module named 'fake_no_such_module' (at {site}/fake_broken_a.py:1)"),
    (LAW_MODULE, "fake_broken_b:ShareFriction", "TypeError: a type, not a FrictionSpec"),
    (LAW_MODULE, "fake_broken_c:SPEC",
     "ValueError: the entry point is named 'broken', the friction law 'shear_share'"),
    (LAW_MODULE, "fake_broken_d:NOPE",
     "AttributeError: module 'fake_broken_d' has no attribute 'NOPE'"),
])
def test_a_broken_plugin_is_refused_naming_the_entry_point_and_distribution(
        tmp_path, monkeypatch, module, value, error):
    name = value.split(":")[0]
    site = install(tmp_path, "fake-broken", "hotroll.test_friction", {"broken": value},
                   {name: module})
    monkeypatch.syspath_prepend(str(site))
    reg = fresh()
    head = (f"the hotroll.test_friction entry point broken = '{value}' (distribution "
            "fake-broken 1.0) is no usable friction law: ")
    for _ in range(2):                      # the lookup after it is refused too
        with pytest.raises(PluginError) as e:
            reg.get("coulomb")
        assert str(e.value).startswith(head + error.format(site=site))


def test_the_checks_of_a_registry_apply_to_plugins(tmp_path, monkeypatch):
    """A flow-stress plugin whose parameter clashes with Misaka's is refused as hotroll's own."""
    text = ("from dataclasses import replace\nfrom hotroll.model.flow_stress import LAWS\n"
            "from hotroll.model.parameters import Parameter\n"
            "SPEC = replace(LAWS['misaka'], name='ppm', parameters=(Parameter("
            "'carbon', '', 'ppm', ''),))\n")
    site = install(tmp_path, "fake-ppm", "hotroll.test_flow_stress",
                   {"ppm": "fake_ppm_law:SPEC"}, {"fake_ppm_law": text})
    monkeypatch.syspath_prepend(str(site))
    from hotroll.model.flow_stress.registry import LawSpec, _same_parameters
    reg = Registry("test_flow_stress", "flow-stress law", LawSpec, _same_parameters)
    reg.register("misaka", LAWS["misaka"])
    with pytest.raises(PluginError, match="ValueError: parameter 'carbon' of 'ppm' differs from "
                                          "'misaka'"):
        reg.names()


def test_the_four_registries_and_their_groups():
    """hotroll's own laws, each once, in their group; the old names are the registries."""
    from hotroll.model.flow_stress.registry import FLOW_STRESS_LAWS
    assert LAWS is FLOW_STRESS_LAWS
    assert {r.group: r.names() for r in (LAWS, FRICTION_LAWS, HEAT_TRANSFER_LAWS, SETS)} == {
        "hotroll.flow_stress": ["norton-hoff", "hensel-spittel", "misaka"],
        "hotroll.friction": ["viscoplastic", "coulomb", "tresca"],
        "hotroll.heat_transfer": ["constant", "convection_radiation"],
        "hotroll.microstructure": ["hodgson_gibbs_cmn"]}
    for reg in (LAWS, FRICTION_LAWS, HEAT_TRANSFER_LAWS, SETS):
        assert all(reg[n].name == n for n in reg)


def _hotroll(args: list[str], site: Path | None, cwd: Path) -> subprocess.CompletedProcess:
    """``python -m hotroll.cli ARGS`` on this tree, ``site`` (a plugin) on its path or not."""
    path = [str(site)] if site else []
    env = dict(os.environ, PYTHONPATH=os.pathsep.join(path + [str(ROOT)]), NO_COLOR="1",
               COLUMNS="200")
    return subprocess.run([sys.executable, "-m", "hotroll.cli", *args], cwd=cwd, env=env,
                          capture_output=True, text=True, timeout=120)


def test_a_case_selects_a_plugin_law_and_hotroll_validate_accepts_it(tmp_path):
    """Through the command line in a process of its own (the case schema is built from the
    registry on import): refused without the plugin, accepted with it, the law's parameter a
    field of [friction] with its range."""
    site = install(tmp_path / "site", "fake-share", "hotroll.friction",
                   {"shear_share": "fake_share_law:SPEC"}, {"fake_share_law": LAW_MODULE})
    text = (ROOT / "hotroll/examples/cases/example1.toml").read_text()
    case = tmp_path / "case.toml"
    case.write_text(text.replace('law = "viscoplastic"', 'law = "shear_share"')
                    .replace('a_f = "estimate"', "share = 0.4"))
    without = _hotroll(["validate", str(case)], None, tmp_path)
    assert without.returncode == 2 and "friction.law" in without.stderr + without.stdout
    with_plugin = _hotroll(["validate", str(case)], site, tmp_path)
    assert with_plugin.returncode == 0, with_plugin.stderr
    assert 'law = "shear_share"' in with_plugin.stdout and "share = 0.4" in with_plugin.stdout
    bad = tmp_path / "bad.toml"
    bad.write_text(case.read_text().replace("share = 0.4", "share = 1.5"))
    refused = _hotroll(["validate", str(bad)], site, tmp_path)
    assert refused.returncode == 2 and "friction.share" in refused.stderr + refused.stdout


def test_hotroll_with_a_broken_plugin_ends_on_the_clear_error(tmp_path):
    site = install(tmp_path / "site", "fake-broken", "hotroll.friction",
                   {"broken": "fake_broken_cli:SPEC"},
                   {"fake_broken_cli": "x = 1\nraise RuntimeError('the plugin is broken')\n"})
    proc = _hotroll(["validate", "example1"], site, tmp_path)
    assert proc.returncode == 1
    last = proc.stderr.strip().splitlines()[-1]
    assert last == (f"hotroll.model.registry.PluginError: the hotroll.friction entry point broken "
                    f"= 'fake_broken_cli:SPEC' (distribution fake-broken 1.0) is no usable "
                    f"friction law: RuntimeError: the plugin is broken (at "
                    f"{site}/fake_broken_cli.py:2)")
    assert proc.stderr.count("Traceback") == 1          # not the plugin's traceback as well


def test_a_plugin_law_solves_as_the_built_in_law_it_equals(tmp_path):
    """The plugin's tau = share k through the FE (a process of its own) is hotroll's Tresca law
    tau = factor k at share = factor: every figure of the summary the same to 1e-9."""
    import json
    import math

    from hotroll.config.case import load_case
    from hotroll.workflows.runner import run_case

    site = install(tmp_path / "site", "fake-share", "hotroll.friction",
                   {"shear_share": "fake_share_law:SPEC"}, {"fake_share_law": LAW_MODULE})
    text = (ROOT / "hotroll/examples/cases/hot_strip_finishing.toml").read_text()
    assert 'law = "coulomb"\nmu = 0.3' in text
    (tmp_path / "plugin.toml").write_text(text.replace('law = "coulomb"\nmu = 0.3',
                                                       'law = "shear_share"\nshare = 0.8'))
    (tmp_path / "tresca.toml").write_text(text.replace('law = "coulomb"\nmu = 0.3',
                                                       'law = "tresca"\nfactor = 0.8'))
    proc = _hotroll(["run", "plugin.toml", "--out", "plugin", "--no-figures"], site, tmp_path)
    assert proc.returncode == 0, proc.stderr
    run_case(load_case(tmp_path / "tresca.toml").with_overrides(**{"output.figures": False}),
             tmp_path / "tresca")
    plugin, tresca = (json.loads((tmp_path / d / "summary.json").read_text())
                      for d in ("plugin", "tresca"))
    assert (plugin.pop("friction_law"), tresca.pop("friction_law")) == ("shear_share", "tresca")
    assert tresca.pop("friction_factor") == 0.8 and plugin.pop("friction_factor") is None
    numbers = [k for k, v in tresca.items() if isinstance(v, float) and math.isfinite(v)
               and "wall" not in k]
    assert "roll_force" in numbers and plugin.keys() == tresca.keys()
    assert {k: plugin[k] for k in numbers} == pytest.approx({k: tresca[k] for k in numbers},
                                                            rel=1e-9)
