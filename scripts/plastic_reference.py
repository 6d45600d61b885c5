#!/usr/bin/env python3
"""Mitsuba 3's own values of its plastic and roughplastic BSDFs: tests/support/plastic_mitsuba_table.h.

tests/shared/plastic_test.cpp checks kernels/shared/materials/plastic.h and
roughplastic.h against these numbers. For a handful of parameter sets (named
and numeric indices, colours, `nonlinear` on and off, Beckmann and GGX at
several roughnesses) this script loads the plugin with mi.load_dict in the
RGB variant the oracle uses (llvm_ad_rgb) and writes, for fixed pairs of
local directions (z the shading normal; wo Mitsuba's si.wi, the direction
back along the path, wi its `wo`, where the path goes next):

- eval (RGB; Mitsuba's includes the cosine of wi) and pdf, all lobes;
- plastic: the delta lobe's sample (sample1 = 0): its weight and its pdf,
  which Mitsuba sets to the lobe's probability;
- roughplastic: what Mitsuba precomputes per material, read back from the
  diffuse lobe alone (BSDFContext component 1): its table of the rough
  interface's transmittance at cos theta = max(1e-6, k / 63), k = 0..63, and
  the internal reflectance. At wo = wi = mu the diffuse lobe's eval is
  d / (1 - R) t(mu)^2 mu / (pi eta^2) with `nonlinear` off, and
  d / (1 - d R) ... with it on; their ratio at mu = 1 gives R, then each
  eval at a table node gives t there.

The directions are rounded to float32 before Mitsuba sees them and written
as those floats; every value is float32, Mitsuba's, written as the shortest
decimal that reads back as that float.

With --check it writes nothing and fails (exit 1, with a diff) when the
committed table differs from what Mitsuba gives now; without Mitsuba it exits
77 (CTest's skip).

Usage: scripts/plastic_reference.py [--check] [--variant llvm_ad_rgb]
"""
import math
import pathlib
import sys

import numpy as np

ROOT = pathlib.Path(__file__).resolve().parent.parent
TABLE = ROOT / "tests" / "support" / "plastic_mitsuba_table.h"
sys.path.insert(0, str(ROOT / "scripts"))
from mitsuba_table import table_main  # noqa: E402
TABLE_SIZE = 64  # Mitsuba's MI_ROUGH_TRANSMITTANCE_RES

# (name, plugin dictionary beyond "type"); None for a parameter left at Mitsuba's default.
PLASTICS = [
    ("defaults", {}),
    ("coloured nonlinear", {"diffuse_reflectance": [0.8, 0.3, 0.1], "specular_reflectance": [0.9, 0.7, 0.5],
                            "int_ior": 1.9, "ext_ior": 1.0, "nonlinear": True}),
    ("coloured linear bk7", {"diffuse_reflectance": [0.8, 0.3, 0.1], "int_ior": "bk7", "nonlinear": False}),
    ("index below 1", {"diffuse_reflectance": [0.2, 0.6, 0.9], "int_ior": 1.33, "ext_ior": 1.5, "nonlinear": True}),
]
ROUGH_PLASTICS = [
    ("defaults", {}),
    ("ggx 0.3 coloured nonlinear", {"distribution": "ggx", "alpha": 0.3, "diffuse_reflectance": [0.8, 0.3, 0.1],
                                    "specular_reflectance": [0.9, 0.7, 0.5], "nonlinear": True}),
    ("ggx 0.05", {"distribution": "ggx", "alpha": 0.05, "int_ior": 1.5, "ext_ior": 1.0}),
    ("ggx 1", {"distribution": "ggx", "alpha": 1.0, "diffuse_reflectance": [0.9, 0.9, 0.9], "nonlinear": True}),
    ("beckmann 0.5 nonlinear", {"distribution": "beckmann", "alpha": 0.5, "diffuse_reflectance": [0.3, 0.5, 0.7],
                                "int_ior": "bk7", "nonlinear": True}),
]

# (cos theta of wo, cos theta of wi, azimuth of wi minus that of wo, in radians); wo at azimuth 0.4.
PAIRS = [
    (0.9, 0.9, math.pi),    # the mirror configuration
    (0.5, 0.5, math.pi),    # the mirror configuration, off normal
    (0.2, 0.25, 3.0),       # near the mirror direction, near grazing
    (0.95, 0.6, 1.0),
    (0.5, 0.95, 2.5),
    (0.3, 0.1, 0.3),
    (0.7, -0.4, 1.0),       # wi below the surface: 0
]


def direction(cos_theta, phi):
    sin_theta = math.sqrt(max(0.0, 1.0 - cos_theta * cos_theta))
    return np.array([sin_theta * math.cos(phi), sin_theta * math.sin(phi), cos_theta], dtype=np.float32)


def pairs():
    return [(direction(c_o, 0.4), direction(c_i, 0.4 + dphi)) for c_o, c_i, dphi in PAIRS]


def shortest(value):
    """The shortest decimal that reads back as the float32 `value`."""
    return np.format_float_scientific(np.float32(value), unique=True, trim="0")


def vector(values):
    return "{" + ", ".join(shortest(v) for v in values) + "}"


class Bsdf:
    def __init__(self, mi, plugin, parameters):
        import drjit as dr

        self.mi, self.dr = mi, dr
        colours = {k: {"type": "rgb", "value": v} if isinstance(v, list) else v for k, v in parameters.items()}
        self.bsdf = mi.load_dict({"type": plugin, **colours})
        self.eta = float(np.array(mi.traverse(self.bsdf)["eta"], dtype=np.float32).reshape(-1)[0])

    def interaction(self, wo):
        si = self.dr.zeros(self.mi.SurfaceInteraction3f, len(wo))
        si.wi = self.mi.Vector3f(*np.array(wo, dtype=np.float32).T)
        return si

    def eval_pdf(self, wo, wi, component=None):
        ctx = self.mi.BSDFContext()
        if component is not None:
            ctx.component = component
        si = self.interaction(wo)
        w = self.mi.Vector3f(*np.array(wi, dtype=np.float32).T)
        value = np.array(self.bsdf.eval(ctx, si, w)).reshape(3, -1).T
        pdf = np.array(self.bsdf.pdf(ctx, si, w)).reshape(-1)
        return value, pdf

    def delta_sample(self, wo):
        """Mitsuba's sample with sample1 = 0: the delta lobe wherever its probability is > 0."""
        si = self.interaction(wo)
        n = len(wo)
        bs, weight = self.bsdf.sample(self.mi.BSDFContext(), si, self.mi.Float(np.zeros(n, dtype=np.float32)),
                                      self.mi.Point2f(np.full(n, 0.5, dtype=np.float32),
                                                      np.full(n, 0.5, dtype=np.float32)))
        return np.array(weight).reshape(3, -1).T, np.array(bs.pdf).reshape(-1)


def precomputed(mi, parameters):
    """Mitsuba's transmittance table and internal reflectance of a roughplastic, read back from its diffuse lobe."""
    linear = Bsdf(mi, "roughplastic", {**parameters, "diffuse_reflectance": 0.5, "nonlinear": False})
    nonlinear = Bsdf(mi, "roughplastic", {**parameters, "diffuse_reflectance": 0.5, "nonlinear": True})
    mu = np.maximum(np.float32(1e-6), np.linspace(0, 1, TABLE_SIZE, dtype=np.float32))
    w = [np.array([math.sqrt(max(0.0, 1.0 - float(m) * float(m))), 0.0, float(m)], dtype=np.float32) for m in mu]
    value_linear = linear.eval_pdf(w, w, component=1)[0][:, 0].astype(np.float64)
    value_nonlinear = nonlinear.eval_pdf(w, w, component=1)[0][:, 0].astype(np.float64)
    ratio = value_nonlinear[-1] / value_linear[-1]  # (1 - R) / (1 - R / 2) at mu = 1
    reflectance = (ratio - 1.0) / (0.5 * ratio - 1.0)
    eta = linear.eta
    transmittance = np.sqrt(value_linear * (1.0 - reflectance) * math.pi * eta * eta /
                            (0.5 * np.array([float(v[2]) for v in w])))
    return transmittance, reflectance


def case_lines(mi, plugin, name, parameters):
    bsdf = Bsdf(mi, plugin, parameters)
    get = lambda key, default: parameters.get(key, default)
    diffuse = get("diffuse_reflectance", 0.5)
    diffuse = diffuse if isinstance(diffuse, list) else [diffuse] * 3
    specular = get("specular_reflectance", 1.0)
    specular = specular if isinstance(specular, list) else [specular] * 3
    wo = [p[0] for p in pairs()]
    wi = [p[1] for p in pairs()]
    value, pdf = bsdf.eval_pdf(wo, wi)
    lines = [f'    {{"{name}",',
             f"     {'true' if get('nonlinear', False) else 'false'}, {shortest(bsdf.eta)}, {vector(diffuse)}, "
             f"{vector(specular)},"]
    if plugin == "roughplastic":
        distribution = get("distribution", "beckmann")
        lines.append(f"     {'true' if distribution == 'beckmann' else 'false'}, {shortest(get('alpha', 0.1))},")
        transmittance, reflectance = precomputed(mi, parameters)
        lines.append(f"     {shortest(reflectance)},")
        lines.append("     " + vector(transmittance) + ",")
    lines.append("     {{")
    if plugin == "plastic":
        delta_weight, delta_pdf = bsdf.delta_sample(wo)
    for k in range(len(wo)):
        row = f"      {{{vector(wo[k])}, {vector(wi[k])}, {vector(value[k])}, {shortest(pdf[k])}"
        if plugin == "plastic":
            row += f", {vector(delta_weight[k])}, {shortest(delta_pdf[k])}"
        lines.append(row + "},")
    lines.append("     }}},")
    return lines


def table(mi, variant):
    lines = [
        "// Mitsuba 3's plastic and roughplastic evaluated by Mitsuba itself: generated",
        f"// by scripts/plastic_reference.py from Mitsuba {mi.__version__} ({variant}); do not",
        "// edit, run the script. Included by tests/shared/plastic_test.cpp only.",
        "#pragma once",
        "",
        "#include <array>",
        "",
        "// One value a field, as the script writes them.",
        "// clang-format off",
        "namespace wp::test::plastic_mitsuba {",
        "",
        f"inline constexpr int kPairs = {len(PAIRS)};",
        f"inline constexpr int kTableSize = {TABLE_SIZE};",
        "",
        "// Local directions (z the shading normal): wo back along the path (Mitsuba's",
        "// si.wi), wi where it goes next; Mitsuba's eval (with the cosine of wi) and pdf.",
        "// The plastic's delta sample (sample1 = 0): its weight and Mitsuba's pdf, the",
        "// lobe's probability.",
        "struct PlasticPair {",
        "    std::array<double, 3> wo, wi, eval;",
        "    double pdf;",
        "    std::array<double, 3> delta_weight;",
        "    double delta_pdf;",
        "};",
        "struct RoughPlasticPair {",
        "    std::array<double, 3> wo, wi, eval;",
        "    double pdf;",
        "};",
        "",
        "// A material: its nonlinear flag, Mitsuba's eta (int_ior / ext_ior, float),",
        "// its reflectances (specular 1 where Mitsuba has none).",
        "struct PlasticCase {",
        "    const char* name;",
        "    bool nonlinear;",
        "    double eta;",
        "    std::array<double, 3> diffuse, specular;",
        "    std::array<PlasticPair, kPairs> pairs;",
        "};",
        "// And the distribution, alpha, Mitsuba's internal reflectance and transmittance",
        "// table read back from its diffuse lobe.",
        "struct RoughPlasticCase {",
        "    const char* name;",
        "    bool nonlinear;",
        "    double eta;",
        "    std::array<double, 3> diffuse, specular;",
        "    bool beckmann;",
        "    double alpha;",
        "    double internal_reflectance;",
        "    std::array<double, kTableSize> transmittance;",
        "    std::array<RoughPlasticPair, kPairs> pairs;",
        "};",
        "",
        "inline constexpr PlasticCase kPlastic[] = {",
    ]
    for name, parameters in PLASTICS:
        lines += case_lines(mi, "plastic", name, parameters)
    lines += ["};", "", "inline constexpr RoughPlasticCase kRoughPlastic[] = {"]
    for name, parameters in ROUGH_PLASTICS:
        lines += case_lines(mi, "roughplastic", name, parameters)
    lines += ["};", "", "}  // namespace wp::test::plastic_mitsuba", "// clang-format on", ""]
    return "\n".join(lines)


def main():
    return table_main("plastic_reference", __doc__.split("\n")[0], TABLE, table)


if __name__ == "__main__":
    sys.exit(main())
